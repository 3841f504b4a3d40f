// What the viewer does with each server message: a map from op to handler.

import { eachAngle } from '/client/pose.js';

const QUIET_FRAME = new Set(['op', 'seq', 'time', 'sensors', 'forces']);  // readings: see lasers

export function makeHandlers(view) {
	const { tree, motion, overlays, lasers, stage, hook, status, caption } = view;
	return {
		hello(message) {
			motion.period = 1 / message.tickRate;
			hook.client = message.client;
			hook.role = message.role;
		},
		snapshot(message) {
			motion.clear();
			tree.clear();
			tree.add(message.nodes);
			overlays.reset(message.contacts);
			stage.setCamera(message.camera);
			caption(message.caption ?? '');
			status.physics(message.physics?.mode);
			hook.frame(message);
		},
		added(message) {
			tree.add(message.nodes);
			stage.invalidate();
		},
		removed(message) {
			tree.remove(message.ids);
			stage.invalidate();
		},
		frame(message) {
			status.frame();
			hook.frame(message);
			if (message.sensors && lasers.readings(message.sensors)) stage.invalidate();
			if (Object.keys(message).every((key) => QUIET_FRAME.has(key))) return;
			stage.invalidate();
			const now = performance.now() / 1000;
			for (const [id, fields] of Object.entries(message.updates ?? {})) tree.update(id, fields);
			for (const [id, pose] of Object.entries(message.poses ?? {})) motion.pose(id, pose, now);
			for (const [id, angle] of eachAngle(message.angles, (robot) => tree.objects.get(robot)?.userData.node.motors)) {
				motion.angle(id, angle, now);
				hook.angleTimes.set(id, performance.timeOrigin + performance.now());
			}
			if (message.contacts) overlays.contacts(message.contacts);
			if (message.camera) stage.setCamera(message.camera);
			if (message.caption !== undefined) caption(message.caption);
			if (message.physics) status.physics(message.physics.mode);
		},
		error(message) {
			console.warn(`server: ${message.code}: ${message.message}`);
		},
		warning(message) {
			console.warn(`scene ${message.code}: ${message.message}`);
			status.warn(message.code === 'saved' ? null : message.message);
		},
	};
}

export function dispatch(handlers, message) {
	const handler = handlers[message.op];
	if (!handler) throw new Error(`unknown message op ${message.op}`);
	handler(message);
}
