// A 1.0 page in the browser: connect to the server that served this module, join the
// scene named by ?scene= (or a fresh one of the page's own) and show the viewer in the
// page, fed by the client's own connection.

import { GUI } from 'lil-gui';
import { connect, useScene, watchUrl } from './runtime.js';

function freshName() {
	return `page-${Math.random().toString(36).slice(2, 10)}`;
}

export async function startPage(moduleUrl) {
	const server = new URL(moduleUrl);
	const viewerModule = (path) => import(new URL(`/web/viewer/${path}`, server).href);
	const [{ mountViewer }, { readOptions }] = await Promise.all([viewerModule('viewer.js'), viewerModule('options.js')]);
	const params = new URLSearchParams(window.location.search);
	const scene = params.get('scene') || freshName();
	const options = { ...readOptions(), scene, role: params.get('role') === 'viewer' ? 'viewer' : 'controller' };
	const guis = new Map();   // robot id -> the page's lil-gui panel
	const watchLink = params.get('scene') ? null : watchUrl(server, scene);
	let session = null;
	const viewer = mountViewer({
		options, watchLink,
		request: (message) => session.call(message.object, message.method, message.args, { wait: true }),
		guiFor: (robotId) => guis.get(robotId) ?? null,
		drawnElsewhere: (id) => session?.meshes.owns(id) ?? false,
	});
	useScene(viewer.scene);
	viewer.setState('connecting');
	const url = `${server.protocol === 'https:' ? 'wss:' : 'ws:'}//${server.host}`;
	session = await connect({
		url, scene, role: options.role, token: options.token,
		onMessage: (message) => {
			if (message.op === 'hello' && session) viewer.setState('connected');   // back again
			viewer.receive(message);
		},
	});
	session.makePanel = (robot, title) => {
		const gui = robot.gui ?? new GUI({ title });
		guis.set(robot.vp.id, gui);
		robot.gui = gui;
	};
	viewer.setState('connected');
	if (options.physics) session.call('scene', 'setPhysics', [options.physics]);   // ?physics=dynamic
	watchLoss(session, viewer);
	return session;
}

// The status line says when the connection is lost (the transport connects again; a new
// hello says it is back) and when the session has ended for good.
function watchLoss(session, viewer) {
	const watched = new WeakSet();
	const follow = () => {
		const socket = session.socket;
		if (watched.has(socket)) return;
		watched.add(socket);
		socket.addEventListener('close', () => { if (!session.closed) viewer.setState('reconnecting'); });
	};
	follow();
	session.listeners.push((message) => { if (message.op === 'hello') follow(); });
	session.ended.then(() => viewer.setState('disconnected'));
}
