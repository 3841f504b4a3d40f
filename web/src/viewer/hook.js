// window.VP: what tests (and curious people in the console) can read of the viewer.

import { meshesLoading } from './meshes.js';

export function installHook(stage, tree, motion) {
	const hook = {
		scene: stage.scene,    // the THREE.Scene
		camera: stage.camera,
		renderer: stage.renderer,
		objects: tree.objects, // object id -> Object3D (userData.node: the server's description)
		seq: 0,                // the last frame's (or snapshot's) sequence number
		time: 0,               // and its scene time
		frames: 0,             // frames and snapshots received
		snapshots: 0,
		rendered: 0,           // pictures drawn
		angleTimes: new Map(), // motor id -> when its last new angle arrived (epoch ms)
		client: null,
		role: null,
		frame(message) {
			hook.seq = message.seq;
			hook.time = message.time;
			if (message.op === 'snapshot') hook.snapshots++; else hook.frames++;
		},
		// The angle the server last gave a motor (what the picture moves towards).
		angle(id) {
			return tree.objects.get(id)?.userData.node.angle;
		},
		// How long the last picture took to draw (ms).
		get renderMs() {
			return stage.renderMs;
		},
		// True when the picture shows everything received (nothing left to draw).
		drawn() {
			return !stage.needsRender && !motion.busy && meshesLoading() === 0;
		},
		// The angle a motor is drawn at now.
		shownAngle(id) {
			return tree.objects.get(id)?.userData.shownAngle;
		},
	};
	window.VP = hook;
	return hook;
}
