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
const motion = new Motion(tree);
const view = {
	tree, stage, motion,
	overlays: new Overlays(tree, options),
	lasers: new Lasers(tree, stage.scene),
	hook: installHook(stage, tree, motion),
	status: new StatusLine(document.getElementById('status'), options.scene),
};
const logo = new Logo(stage.scene);
const handlers = makeHandlers(view);
const connection = new Connection(socketUrl(options), {
	onMessage: (message) => dispatch(handlers, message),
	onState: (state) => view.status.setState(state),
});
const gestureBox = document.getElementById('gesture');
const panels = new MotorPanels(tree, {
	editable: options.role === 'controller',
	setAngle: (motorId, angle) => connection.request(
		{ op: 'call', object: motorId, method: 'setAngle', args: [angle] }).catch(() => {}),
	showGesture: (text) => { gestureBox.textContent = text; gestureBox.hidden = false; },
});

tree.on('loaded', () => stage.invalidate());

stage.beforeRender.push((now) => {
	if (motion.step(now / 1000)) stage.invalidate();
	if (logo.step(now, tree.objects.size === 0)) stage.invalidate();
	view.lasers.step();
	panels.step();
});
stage.afterRender.push(() => { view.hook.rendered++; });
