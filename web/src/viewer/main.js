// The viewer page: one page watching one scene of the server that served it.

import { Connection } from './connection.js';
import { readOptions, socketUrl } from './options.js';
import { mountRecorder } from './recorder.js';
import { Replay, mountTimeline } from './replay.js';
import { mountRobotDrop } from './robot_drop.js';
import { mountViewer } from './viewer.js';

const options = readOptions();
if (options.recording) {   // a recording, played here (read-only: motor panels change nothing)
	let replay = null;
	const viewer = mountViewer({ options, request: () => Promise.reject(new Error('a recording cannot be changed')),
		cursor: () => replay?.sceneTime() ?? null, span: () => replay?.span() ?? null, plotting: true, framing: true });
	replay = new Replay(options.recording, (message) => viewer.receive(message));
	mountTimeline(replay);
	window.VP.replay = replay;
	replay.open().then(() => {
		viewer.setState('replay');
		return replay.readAll((ticks) => viewer.plots.preload(ticks));
	}).catch((error) => viewer.setState(`replay failed: ${error.message}`));
} else {
	let connection = null;
	const viewer = mountViewer({ options, request: (message) => connection.request(message), plotting: true, framing: true });
	connection = new Connection(socketUrl(options), {
		onMessage: (message) => viewer.receive(message),
		onState: (state) => viewer.setState(state),
	});
	if (options.role === 'controller') {
		mountRecorder(options);
		mountRobotDrop(options, viewer.stage.camera, viewer.stage.renderer.domElement);
	}
}
