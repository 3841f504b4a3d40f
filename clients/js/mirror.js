// The client's copy of the scene as the server describes it: node states by id, camera,
// server time, contacts and the watched sensors' readings, kept current by the server's
// messages (sans-I/O: it is handed messages, it never reads a socket).
//
// It also holds what this client's own requests will do before the server has answered
// them (prediction.js): a predicted field is held until the answer to the
// request that predicted it arrives. Meanwhile the server's values for that field (frames
// and earlier answers, which do not yet include the request) are put aside; once the
// answer is in they replace the prediction, so the mirror never stays wrong for long, and
// never flickers back in between.

import { fromWire } from './codec.js';
import { eachAngle } from './pose.js';

export class Mirror {
	// wants(id): whether someone listens to contact changes of node `id` (only those
	// are queued as events).
	constructor({ wants = () => true } = {}) {
		this.wants = wants;
		this.nodes = new Map();    // id -> description (fields as the server sends them)
		this.camera = null;
		this.caption = '';         // what viewers show in a corner (setCaption)
		this.physics = { mode: 'kinematic' };
		this.forces = new Map();   // dynamic mode: part id -> newtons pressing on it
		this.time = 0;
		this.seq = 0;
		this.contacts = new Set(); // "a|b"
		this.readings = new Map(); // sensor id -> {distance, touch, position, objects, force}
		this.events = [];          // [kind, a, b] contact changes not yet dispatched
		this.listeners = [];       // (kind, id, fields) for every node change
		this.held = new Map();     // id -> {until, known, fields, server}, by until: see predict
		this.physicsHeld = null;   // {until, server}: this client's setPhysics, not yet answered
	}

	// Fold one server message (snapshot, added, removed, frame) into the mirror.
	apply(message) {
		switch (message.op) {
			case 'snapshot': {
				// after a reconnection: what is still there stays (changed), the rest goes
				const fresh = new Set(message.nodes.map((node) => node.id));
				// (a node this client has asked for and the server not yet made stays)
				for (const id of [...this.nodes.keys()]) {
					if (!fresh.has(id) && this.held.get(id)?.known !== false) this.forget(id);
				}
				this.camera = message.camera;
				this.caption = message.caption ?? '';
				if (message.physics) this.serverPhysics(message.physics);
				this.forces = new Map(Object.entries(message.forces ?? {}));   // pressing now (frames: changes)
				for (const node of message.nodes) {
					if (this.nodes.has(node.id)) this.change(node.id, node);
					else this.add([node]);
				}
				this.contacts = new Set(message.contacts.map(([a, b]) => `${a}|${b}`));
				this.readings = new Map();   // none of a world that may be gone (a restore)
				this.readSensors(message.sensors);
				this.tick(message);
				break;
			}
			case 'added': this.add(message.nodes); break;
			case 'removed': for (const id of message.ids) this.forget(id); break;
			case 'frame':
				this.applyChanges(message);
				if (message.contacts) this.contactChanges(message.contacts);
				this.readSensors(message.sensors);
				this.tick(message);
				break;
		}
	}

	readSensors(sensors) {
		for (const [id, reading] of Object.entries(sensors ?? {})) {
			this.readings.set(id, { ...reading, distance: fromWire(reading.distance) });
		}
	}

	// Fold a change set: an `ok` answer's `changes` or a frame's fields.
	applyChanges(changes) {
		this.add(changes.added ?? []);
		for (const [id, fields] of Object.entries(changes.updates ?? {})) this.change(id, fields);
		for (const [id, angle] of eachAngle(changes.angles, (robot) => this.nodes.get(robot)?.motors)) this.change(id, { angle });
		for (const [id, pose] of Object.entries(changes.poses ?? {})) {
			this.change(id, { position: pose.slice(0, 3), quaternion: pose.slice(3) });
		}
		if (changes.camera) this.camera = changes.camera;
		if (changes.caption !== undefined) this.caption = changes.caption;
		if (changes.physics) this.serverPhysics(changes.physics);
		for (const [id, force] of Object.entries(changes.forces ?? {})) {
			if (force) this.forces.set(id, force);
			else this.forces.delete(id);
		}
		for (const id of changes.removed ?? []) this.forget(id);
	}

	// Nodes the server made (or sent again after a reconnection).
	add(nodes) {
		for (const node of nodes) {
			const hold = this.held.get(node.id);
			if (hold) hold.known = true;
			const fresh = { ...node, ...this.divert(node.id, node) };
			this.nodes.set(node.id, fresh);
			this.emit('added', node.id, fresh);
		}
	}

	// Fields of a node the server changed.
	change(id, fields) {
		if (!this.nodes.has(id)) return;
		const kept = this.divert(id, fields);
		this.set(id, Object.keys(kept).length ? Object.fromEntries(
			Object.entries(fields).filter(([key]) => !(key in kept))) : fields);
	}

	set(id, fields) {
		const node = this.nodes.get(id);
		if (!node || !Object.keys(fields).length) return;
		Object.assign(node, fields);
		this.emit('changed', id, fields);
	}

	// The server's values of fields held for a prediction are put aside; returns the
	// predicted values that stand instead.
	divert(id, fields) {
		const hold = this.held.get(id), node = this.nodes.get(id);
		const kept = {};
		if (!hold) return kept;
		for (const key of hold.fields) {
			if (!(key in fields)) continue;
			hold.server[key] = fields[key];
			if (node && key in node) kept[key] = node[key];
		}
		return kept;
	}

	// This client's request `until` (not yet sent or answered) will set these fields of
	// node `id` (making the node if it is new): they are set now and held until its answer.
	predict(id, fields, until) {
		const node = this.nodes.get(id);
		const hold = this.held.get(id) ?? { until, known: Boolean(node), server: {}, fields: new Set() };
		// requests are numbered in order: moved to the end, the holds stay ordered by until
		this.held.delete(id);
		this.held.set(id, hold);
		hold.until = Math.max(hold.until, until);
		for (const key of Object.keys(fields)) {
			if (hold.known && !hold.fields.has(key) && node) hold.server[key] = node[key];
			hold.fields.add(key);
		}
		if (node) {
			this.set(id, fields);
		} else {
			this.nodes.set(id, { id, ...fields });
			this.emit('added', id, this.nodes.get(id));
		}
	}

	// The scene's physics as the server sent it: put aside while a setPhysics of this
	// client's is unanswered, as a node's predicted fields are.
	serverPhysics(physics) {
		if (this.physicsHeld) this.physicsHeld.server = physics;
		else this.physics = physics;
	}

	// This client's request `until` (a setPhysics) will make the scene's physics `physics`.
	predictPhysics(physics, until) {
		this.physicsHeld = { until, server: this.physicsHeld?.server ?? this.physics };
		this.physics = physics;
	}

	// The server answered every request up to `id`: predictions made for them give way
	// to what it said (a node it never made goes).
	release(id) {
		if (this.physicsHeld && this.physicsHeld.until <= id) {
			this.physics = this.physicsHeld.server;
			this.physicsHeld = null;
		}
		for (const [nodeId, hold] of this.held) {
			if (hold.until > id) break;   // and every later one
			this.held.delete(nodeId);
			if (!hold.known) this.forget(nodeId);
			else this.set(nodeId, Object.fromEntries(Object.entries(hold.server).filter(
				([key, value]) => !same(this.nodes.get(nodeId)?.[key], value))));
		}
	}

	forget(id) {
		this.held.delete(id);
		if (!this.nodes.delete(id)) return;
		this.readings.delete(id);
		this.emit('removed', id, null);
	}

	emit(kind, id, fields) {
		for (const listener of this.listeners) listener(kind, id, fields);
	}

	contactChanges({ begin, end }) {
		for (const [kind, pairs] of [['begin', begin], ['end', end]]) {
			for (const [a, b] of pairs) if (this.wants(a) || this.wants(b)) this.events.push([kind, a, b]);
		}
		for (const [a, b] of end) this.contacts.delete(`${a}|${b}`);
		for (const [a, b] of begin) this.contacts.add(`${a}|${b}`);
	}

	tick(message) {
		this.time = message.time;
		this.seq = message.seq;
	}

	// A node and its descendants, depth first, pre-order.
	*walk(id) {
		const stack = [id];
		while (stack.length) {
			const node = this.nodes.get(stack.pop());
			if (!node) continue;
			yield node;
			for (let i = node.children.length - 1; i >= 0; i--) stack.push(node.children[i]);
		}
	}

	// The parts below a robot (motors and sensors included, slots and page meshes not),
	// in tree order.
	parts(robotId) {
		return [...this.walk(robotId)].filter((n) => n.id !== robotId && n.type !== 'Slot' && n.type !== 'SceneMesh');
	}

	// A robot's motors in index order, as the server lists them.
	motors(robotId) {
		return (this.nodes.get(robotId)?.motors ?? []).map((id) => this.nodes.get(id)).filter(Boolean);
	}
}

function same(a, b) {
	return a === b || JSON.stringify(a) === JSON.stringify(b);
}
