// What the viewer does with each server message: a map from op to handler.

export function makeHandlers(view) {
	const { tree, motion, overlays, lasers, stage, hook } = view;
	return {
		hello(message) {
			motion.period = 1 / message.tickRate;
			hook.client = message.client;
			hook.role = message.role;
		},
		snapshot(message) {
			motion.clear();
			lasers.clear();
			tree.clear();
			tree.add(message.nodes);
			overlays.reset(message.contacts);
			stage.setCamera(message.camera);
			hook.frame(message);
		},
		added(message) {
			tree.add(message.nodes);
		},
		removed(message) {
			tree.remove(message.ids);
		},
		frame(message) {
			const now = performance.now() / 1000;
			for (const [id, fields] of Object.entries(message.updates ?? {})) tree.update(id, fields);
			for (const [id, pose] of Object.entries(message.poses ?? {})) motion.pose(id, pose, now);
			for (const [id, angle] of Object.entries(message.angles ?? {})) motion.angle(id, angle, now);
			if (message.contacts) overlays.contacts(message.contacts);
			if (message.sensors) lasers.readings(message.sensors);
			if (message.camera) stage.setCamera(message.camera);
			hook.frame(message);
		},
		ok() {},
		error(message) {
			console.warn(`server: ${message.code}: ${message.message}`);
		},
	};
}

export function dispatch(handlers, message) {
	const handler = handlers[message.op];
	if (!handler) throw new Error(`unknown message op ${message.op}`);
	handler(message);
}
