// The viewer as a piece any page can mount: the picture, the status line, motor panels,
// the gesture box and window.VP, fed the server's messages by whoever holds the
// connection (the viewer page's own, or the JavaScript client's in a 1.0 page).

import * as THREE from 'three';
import { callMessage } from '/client/messages.js';
import { dispatch, makeHandlers } from './handlers.js';
import { installInspection } from './inspection.js';
import { Lasers } from './lasers.js';
import { Logo, SOFTWARE_TURNS } from './logo.js';
import { Motion } from './motion.js';
import { Overlays } from './overlays.js';
import { MotorPanels } from './panel.js';
import { Heat } from './heat.js';
import { Plots } from './plots.js';
import { Stage } from './stage.js';
import { StatusLine } from './status.js';
import { SceneTree } from './tree.js';

const STYLESHEET = new URL('../viewer.css', import.meta.url).href;

// The element with `id`, made (with `tag` and `className`) when the page has none.
function element(id, tag, className) {
	let found = document.getElementById(id);
	if (!found) {
		found = Object.assign(document.createElement(tag), { id, className });
		document.body.append(found);
	}
	return found;
}

function linkStylesheet() {
	if ([...document.styleSheets].some((sheet) => sheet.href === STYLESHEET)) return;
	document.head.append(Object.assign(document.createElement('link'), { rel: 'stylesheet', href: STYLESHEET }));
}

// options: readOptions()'s; request(message) → promise of the answer's result;
// guiFor(robotId): a lil-gui panel the page made for that robot (else one is made); watchLink: shown in the
// status line (a page's own scene); drawnElsewhere(id): true for the SceneMeshes a page draws itself.
// cursor(), span(): where a recording's player stands and the recording's [start, end]
// (scene time), for the plots; null live.
// plotting: a Plots button; framing: frame what the scene holds when part of it is out of
// view and no script placed the camera (both the viewer page's; a 1.0 page keeps the
// manual's camera and look).
export function mountViewer({ options, request, guiFor, watchLink = null, drawnElsewhere, cursor = () => null,
	span = () => null, plotting = false, framing = false }) {
	linkStylesheet();
	const status = element('status', 'div', 'status');
	const caption = element('caption', 'div', 'caption');
	caption.hidden = true;
	const gestureBox = element('gesture', 'pre', 'gesture');
	gestureBox.hidden = true;
	const stage = new Stage(document.body, options.fps, options.quality);
	const root = new THREE.Group();
	root.name = 'robots';
	stage.scene.add(root);

	const tree = new SceneTree(root, drawnElsewhere);
	const motion = new Motion(tree);
	const view = {
		tree, stage, motion,
		overlays: new Overlays(tree, options),
		lasers: new Lasers(tree, stage.scene),
		hook: installInspection(stage, tree, motion),
		status: new StatusLine(status, options.scene, watchLink, () => stage.pictures, options.recording),
		caption: (text) => { caption.textContent = text; caption.hidden = !text; },
	};
	const heat = new Heat(tree, () => stage.invalidate());
	const plots = new Plots({ motorsOf: (robot) => tree.objects.get(robot)?.userData.node.motors, cursor, span,
		heat: (on) => heat.toggle(on), named: (id) => tree.named(id) });
	Object.assign(view.hook, { plots, heat });
	if (plotting) {
		const plotButton = Object.assign(element('plot-button', 'button', 'plot-button'), { textContent: 'Plots' });
		plotButton.addEventListener('click', () => plots.open());
	}
	const frameButton = Object.assign(element('frame-button', 'button', 'frame-button'),
		{ textContent: 'Frame all', title: 'Frame what the scene holds (F)' });
	const frameAll = () => stage.frame(tree.root);
	frameButton.addEventListener('click', frameAll);
	window.addEventListener('keydown', (event) => {
		const typing = event.target instanceof HTMLInputElement || event.target instanceof HTMLTextAreaElement;
		if (!typing && !event.ctrlKey && !event.metaKey && !event.altKey && event.key.toLowerCase() === 'f') frameAll();
	});
	Object.assign(view.hook, { frameAll });
	const logo = new Logo(stage.scene, stage.software && options.fps === null ? 1000 / SOFTWARE_TURNS : 0);
	const handlers = makeHandlers(view);
	const panels = new MotorPanels(tree, {
		// a controller steers its own robots and shared ones (the server refuses the rest)
		editable: (robot) => options.role === 'controller' && (robot.shared || robot.owner === view.hook.client),
		setAngle: (motorId, angle) => request(
			callMessage(motorId, 'setAngle', [angle])).catch(() => {}),
		showGesture: (text) => { gestureBox.textContent = text; gestureBox.hidden = false; },
		guiFor,
		every: options.role === 'controller',
		container: element('motor-panels', 'div', 'motor-panels'),
	});

	// what the viewer itself put in the scene is not a page's mesh to share (meshes.js)
	for (const child of stage.scene.children) child.userData.vpLocal = true;
	const reframe = () => framing && stage.frameIfCut(tree.root);
	tree.on('loaded', () => { stage.invalidate(); reframe(); });
	stage.beforeRender.push((now) => {
		const moved = motion.step(now / 1000);
		if (moved) stage.invalidate();
		// a move ended in this step (a script placed something after making it; on a slow
		// page a move starts and ends in one step): it may be out of view now. Framed
		// before this picture, so a picture that is drawn() shows it.
		if (moved && !motion.busy) reframe();
		if (logo.step(now, tree.objects.size === 0)) stage.invalidate();
		view.lasers.step();
		panels.step();
	});
	stage.afterRender.push(() => { panels.show(); view.hook.drew(stage.renderMs); });
	return {
		scene: stage.scene,
		stage,
		plots,
		receive: (message) => {
			dispatch(handlers, message);
			if (message.op === 'snapshot' || message.op === 'added' || message.camera) reframe();
			view.hook.handled(message);
			plots.receive(message);
			heat.receive(message);
		},
		setState: (state) => view.status.setState(state),
	};
}
