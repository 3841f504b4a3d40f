// window.VP: what tests (and curious people in the console) can read of the viewer.

import { meshesLoading } from './meshes.js';

const LOG = 2000;

function keep(log, entry) {
	if (log.length >= LOG) log.splice(0, log.length - LOG + 1);
	log.push(entry);
}

export function installInspection(stage, tree, motion) {
	const hook = {
		scene: stage.scene,    // the THREE.Scene
		camera: stage.camera,
		renderer: stage.renderer,
		quality: stage.quality, // the drawing level (quality.js) and how it adapts
		objects: tree.objects, // object id -> Object3D (userData.node: the server's description)
		seq: 0,                // the last frame's (or snapshot's) sequence number
		time: 0,               // and its scene time
		frames: 0,             // frames and snapshots received
		snapshots: 0,
		rendered: 0,           // pictures drawn
		angleTimes: new Map(), // motor id -> when its last new angle arrived (epoch ms)
		client: null,
		role: null,
		// the last LOG frames handled [seq, epoch ms after handling] and pictures' draw times (ms)
		frameLog: [],
		renderLog: [],
		longTasks: [],         // durations (ms) of main-thread tasks over 50 ms, as the browser saw them
		frame(message) {
			hook.seq = message.seq;
			hook.time = message.time;
			if (message.op === 'snapshot') hook.snapshots++; else hook.frames++;
		},
		handled(message) {
			if (message.op === 'frame') keep(hook.frameLog, [message.seq, performance.timeOrigin + performance.now()]);
		},
		drew(ms) {
			hook.rendered++;
			keep(hook.renderLog, ms);
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
	if (PerformanceObserver.supportedEntryTypes?.includes('longtask')) {
		new PerformanceObserver((list) => { for (const entry of list.getEntries()) keep(hook.longTasks, entry.duration); })
			.observe({ type: 'longtask' });
	}
	window.VP = hook;
	return hook;
}
