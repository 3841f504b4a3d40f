// The viewer: one page watching one scene of the server that served it.

import * as THREE from 'three';
import { Connection } from './connection.js';
import { dispatch, makeHandlers } from './handlers.js';
import { installHook } from './hook.js';
import { Lasers } from './lasers.js';
import { Logo } from './logo.js';
import { Motion } from './motion.js';
import { readOptions, socketUrl } from './options.js';
import { Overlays } from './overlays.js';
import { MotorPanels } from './panel.js';
import { Stage } from './stage.js';
import { StatusLine } from './status.js';
import { SceneTree } from './tree.js';

const options = readOptions();
const stage = new Stage();
const root = new THREE.Group();
root.name = 'robots';
stage.scene.add(root);

const tree = new SceneTree(root);
const view = {
	tree, stage,
	motion: new Motion(tree),
	overlays: new Overlays(tree, options),
	lasers: new Lasers(tree, stage.scene),
	hook: installHook(stage, tree),
};
const logo = new Logo(stage.scene);
const status = new StatusLine(document.getElementById('status'), options.scene);
const handlers = makeHandlers(view);
const connection = new Connection(socketUrl(options), {
	onMessage: (message) => dispatch(handlers, message),
	onState: (state) => status.setState(state),
});
const gestureBox = document.getElementById('gesture');
const panels = new MotorPanels(tree, {
	editable: options.role === 'controller',
	setAngle: (motorId, angle) => connection.request(
		{ op: 'call', object: motorId, method: 'setAngle', args: [angle] }).catch(() => {}),
	showGesture: (text) => { gestureBox.textContent = text; gestureBox.hidden = false; },
});

stage.beforeRender.push((now) => {
	view.motion.step(now / 1000);
	view.lasers.step();
	panels.step();
	logo.step(now, tree.objects.size === 0);
	status.step(now);
	view.hook.rendered++;
});
