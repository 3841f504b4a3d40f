// The client's copy of the scene as the server describes it: node states by id, camera,
// server time, contacts and the watched sensors' readings, kept current by the server's
// messages (sans-I/O: it is handed messages, it never reads a socket).

import { fromWire } from './codec.js';

export class Mirror {
	// wants(id): whether someone listens to contact changes of node `id` (only those
	// are queued as events).
	constructor({ wants = () => true } = {}) {
		this.wants = wants;
		this.nodes = new Map();    // id -> description (fields as the server sends them)
		this.camera = null;
		this.time = 0;
		this.seq = 0;
		this.contacts = new Set(); // "a|b"
		this.readings = new Map(); // sensor id -> {distance, touch, position, objects}
		this.events = [];          // [kind, a, b] contact changes not yet dispatched
		this.listeners = [];       // (kind, id, fields) for every node change
	}

	// Fold one server message (snapshot, added, removed, frame) into the mirror.
	apply(message) {
		switch (message.op) {
			case 'snapshot': {
				// after a reconnection: what is still there stays (changed), the rest goes
				const fresh = new Set(message.nodes.map((node) => node.id));
				for (const id of [...this.nodes.keys()]) if (!fresh.has(id)) this.forget(id);
				this.camera = message.camera;
				for (const node of message.nodes) {
					if (this.nodes.has(node.id)) this.change(node.id, node);
					else this.add([node]);
				}
				this.contacts = new Set(message.contacts.map(([a, b]) => `${a}|${b}`));
				this.tick(message);
				break;
			}
			case 'added': this.add(message.nodes); break;
			case 'removed': for (const id of message.ids) this.forget(id); break;
			case 'frame':
				this.applyChanges(message);
				if (message.contacts) this.contactChanges(message.contacts);
				for (const [id, reading] of Object.entries(message.sensors ?? {})) {
					this.readings.set(id, { ...reading, distance: fromWire(reading.distance) });
				}
				this.tick(message);
				break;
		}
	}

	// Fold a change set: an `ok` answer's `changes` or a frame's fields.
	applyChanges(changes) {
		this.add(changes.added ?? []);
		for (const [id, fields] of Object.entries(changes.updates ?? {})) this.change(id, fields);
		for (const [id, angle] of Object.entries(changes.angles ?? {})) this.change(id, { angle });
		for (const [id, pose] of Object.entries(changes.poses ?? {})) {
			this.change(id, { position: pose.slice(0, 3), quaternion: pose.slice(3) });
		}
		if (changes.camera) this.camera = changes.camera;
		for (const id of changes.removed ?? []) this.forget(id);
	}

	add(nodes) {
		for (const node of nodes) {
			this.nodes.set(node.id, { ...node });
			this.emit('added', node.id, node);
		}
	}

	change(id, fields) {
		const node = this.nodes.get(id);
		if (!node) return;
		Object.assign(node, fields);
		this.emit('changed', id, fields);
	}

	forget(id) {
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

	// The parts below a robot (motors and sensors included, slots not), in tree order.
	parts(robotId) {
		return [...this.walk(robotId)].filter((n) => n.id !== robotId && n.type !== 'Slot');
	}

	// A robot's motors in index order, as the server lists them.
	motors(robotId) {
		return (this.nodes.get(robotId)?.motors ?? []).map((id) => this.nodes.get(id)).filter(Boolean);
	}
}
