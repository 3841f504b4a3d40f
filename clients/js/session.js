// One client's conversation with one scene, without any socket (sans-I/O): the protocol
// core, the mirror of the scene, the client's three.js objects (one Object3D per node,
// parented and posed as on the server) and the outbox. A transport hands it the
// server's texts (receive) and gives it a function that sends a text.
//
// Requests made during one task (one animation step, one page script) leave as one
// WebSocket message, after the transforms the page wrote directly to its objects
// (`part.position.x = …`) have been compared with what the server last knew. An
// animation step's requests nobody waits for go as one batch: applied as one, answered once.

import * as THREE from 'three';
import { encode } from './codec.js';
import { ConnectionLost } from './errors.js';
import { batchMessage, callMessage, createMessage } from './messages.js';
import { Mirror } from './mirror.js';
import { moved, remember, transformEntry } from './page_transforms.js';
import { scaleAbove, shownPosition, shownRotation } from './pose.js';
import { Prediction } from './prediction.js';
import { ProtocolCore } from './protocol.js';
import { DEFAULT_SECONDS, within } from './waiting.js';

const ONE = [1, 1, 1];
const scale = new THREE.Vector3();  // the scales above a slider, while it is posed
const POSED = ['position', 'quaternion', 'angle', 'flipped', 'scale', 'visible'];
const TEXT_BYTES = 512 * 1024;   // well under the server's messageBytes (1 MiB)

let current = null;

// The session new objects go to: the last one connected.
export function currentSession() {
	if (!current) throw new ConnectionLost('not connected: await connect() first');
	return current;
}

export function setCurrentSession(session) {
	current = session;
}

export class Session {
	// send(text): the transport; classes: type name -> class (for objects made elsewhere);
	// timeout: seconds to wait for each answer waited on (waiting.js).
	constructor({ send, classes = {}, timeout = DEFAULT_SECONDS, onWarning = (text) => console.warn(`server: ${text}`) }) {
		this.transmit = send;
		this.timeout = timeout;
		this.classes = classes;
		this.hello = null;
		this.closed = null;
		this.objects = new Map();        // id -> Object3D
		this.root = new THREE.Group();   // objects without a parent on the server
		this.nextName = 1;
		this.outbox = [];                // texts, or {text} entries (null until known: sendLater)
		this.meshFiles = null;           // a page's own mesh files (mesh_files.js), once connected
		this.flushing = false;
		this.gathered = null;            // while an animation step runs: its requests nobody waits for
		this.listeners = [];             // (message) for every server message not an answer
		this.mirror = new Mirror({ wants: (id) => this.hearsContacts(id) });
		this.mirror.listeners.push((kind, id, fields) => this.mirrored(kind, id, fields));
		this.core = new ProtocolCore({
			onMessage: (message) => this.heard(message),
			onChanges: (changes) => this.mirror.applyChanges(changes),
			onWarning,
			onRefused: (ids) => this.unsay(ids),
			onAnswered: (id) => this.mirror.release(id),
			onRefusal: (error) => this.welcome.reject(error),
		});
		this.prediction = null;          // from hello on (it knows the slot counts)
		this.ready = new Promise((resolve, reject) => { this.welcome = { resolve, reject }; });
		this.ended = new Promise((resolve) => { this.end = resolve; });   // resolves with why
	}

	get clientId() { return this.hello?.client; }

	// --- from the server ------------------------------------------------------------------

	receive(text) {
		this.core.receive(text);
	}

	heard(message) {
		if (message.op === 'hello') {
			this.hello = message;
			this.prediction = new Prediction(this.mirror, { slots: message.slots, classes: this.classes, physics: message.physics });
		} else if (message.op !== 'error') {
			this.mirror.apply(message);
		}
		if (message.op === 'snapshot') this.welcome.resolve(this);
		if (message.op === 'frame') this.dispatchContacts();
		for (const listener of this.listeners) listener(message);
	}

	// A new connection, as the same client, replaced a lost one (transport.js); the
	// server's fresh hello and snapshot follow and resync the mirror.
	// Requests from id `sentBefore` on were made after the loss (sent on the new connection).
	reconnected(sentBefore) {
		this.core.reconnected(new ConnectionLost('the connection dropped before a request was '
			+ 'answered (it may or may not have been applied); reconnected'), sentBefore);
		this.mirror.release(sentBefore - 1);   // lost requests: the snapshot says what holds
	}

	// The connection closed: waiters hear it, later requests throw.
	lost(reason) {
		this.closed = reason;
		this.end(reason);
		const error = new ConnectionLost(reason);
		this.core.lost(error);
		this.welcome.reject(error);
	}

	// --- the objects ----------------------------------------------------------------------

	newId() {
		if (!this.hello) throw new ConnectionLost('not connected: await connect() first');
		return `${this.clientId}.${this.nextName++}`;
	}

	// A new object made by this client: registered, then created on the server (and in
	// the mirror at once, as the server will make it: send). A mesh part made from a file
	// of the page's own is created once the file is uploaded (mesh_files.js).
	make(object, type, args) {
		const id = this.newId();
		this.register(object, id, type);
		object.vp.slots = this.hello.slots[type] ?? 0;
		const message = createMessage(id, type, trimmed(args.map((a) => this.arg(a))));
		const at = object.constructor.vpFileArgument, file = message.args[at];
		if (typeof file !== 'string' || !this.meshFiles) return void this.send(message);
		this.sendLater(message, this.meshFiles.nameFor(file).then((name) => {
			message.args[at] = name;
			return message;
		}));
	}

	register(object, id, type) {
		object.vp = { id, type, session: this, base: new THREE.Quaternion(), angle: 0,
			basePosition: new THREE.Vector3(),
			known: new Float64Array(10), visible: true, slots: 0 };
		object.name = id;
		this.objects.set(id, object);
		this.root.add(object);
		remember(object);
	}

	// The object for a node id: the one this client made, or one made now for it.
	object(id) {
		let object = this.objects.get(id);
		const node = this.mirror.nodes.get(id);
		if (!object && node) {
			const Class = this.classes[node.type] ?? this.classes.Part;
			object = Class.adopt(this, id, node.type);
			this.pose(object, node);
			this.place(object, node);
		}
		return object;
	}

	// Ids in readings and contacts: the object, or the id itself ("ground").
	resolve(id) {
		return this.object(id) ?? id;
	}

	mirrored(kind, id, fields) {
		if (kind === 'removed') {
			const object = this.objects.get(id);
			this.objects.delete(id);
			object?.removeFromParent();
			return;
		}
		const object = this.object(id);
		if (!object) return;
		if (kind === 'added') {
			object.vp.slots = Math.max(object.vp.slots, this.slotCount(fields));
			this.pose(object, fields);
			this.place(object, fields);
			return;
		}
		if (Object.keys(fields).length === 1 && 'angle' in fields) {   // a motor turned: only that
			object.vp.angle = fields.angle;
			this.turn(object);
		} else if (POSED.some((field) => field in fields)) {
			this.pose(object, this.mirror.nodes.get(id));
		}
		if ('parent' in fields || 'children' in fields) this.place(object, this.mirror.nodes.get(id));
		if ('name' in fields && fields.name) object.name = fields.name;
	}

	// Calls the server refused: their objects show what the server holds again (a
	// setter changed them here at once); an object it never made is dropped here too.
	unsay(ids) {
		for (const id of ids) {
			const object = this.objects.get(id), node = this.mirror.nodes.get(id);
			if (object && node) this.pose(object, node);
			else if (object && !node) this.mirrored('removed', id);
		}
	}

	slotCount(node) {
		const prefix = `${node.id}/s`;
		return node.children.filter((child) => child.startsWith(prefix)).length;
	}

	// An object posed as its node: position, base rotation and a motor's turn (or slide).
	pose(object, node) {
		if (node.position) object.position.fromArray(node.position);
		if (node.position) object.vp.basePosition.fromArray(node.position);
		if (node.slides) object.vp.slides = true;
		if (node.quaternion) object.vp.base.fromArray(node.quaternion);
		if (node.angle !== undefined) object.vp.angle = node.angle;
		if (node.axis) object.vp.axis = node.axis;
		if (node.flipped !== undefined) object.vp.flipped = node.flipped;
		object.scale.fromArray(node.scale ?? ONE);
		object.visible = node.visible ?? true;
		this.turn(object);
	}

	// The quaternion an object shows: its base rotation, a motor turned about its axis (a
	// slider's position: moved along it).
	turn(object) {
		shownRotation(object.quaternion, object.vp.base, object.vp);
		if (object.vp.slides) {
			shownPosition(object.position, object.vp.basePosition, object.vp.base, object.vp,
				scaleAbove(scale, object));
		}
		remember(object);
	}

	place(object, node) {
		const parent = node.parent ? this.object(node.parent) : null;
		if ((parent ?? this.root) !== object.parent) (parent ?? this.root).add(object);
		for (const childId of node.children ?? []) {
			const child = this.objects.get(childId);
			if (child && child.parent !== object) object.add(child);
		}
		if (object.vp.slides) this.turn(object);   // how far it moves: by the scales above it
	}

	// --- transforms a page wrote directly (page_transforms.js) ---------------------------

	// Send, as one setTransforms, every object's position, rotation and scale that changed
	// since the server knew it (the page's meshes too); visibility changes as setVisible.
	syncTransforms() {
		const transforms = {};
		for (const object of this.objects.values()) {
			const changed = moved(object);
			if (changed) transforms[object.vp.id] = transformEntry(object);
			if (object.visible !== object.vp.visible) this.call(object.vp.id, 'setVisible', [object.visible]);
			else if (!changed) continue;   // what the server knows already: a fifth of a step's CPU
			remember(object);
		}
		this.meshes?.sync(transforms);
		const ids = Object.keys(transforms);
		const most = this.hello.limits.transformsPerCall;
		for (let start = 0; start < ids.length; start += most) {
			const part = Object.fromEntries(ids.slice(start, start + most).map((id) => [id, transforms[id]]));
			this.call('scene', 'setTransforms', [part]);
		}
	}

	// --- requests -------------------------------------------------------------------------

	// An argument as it travels: objects as references, the rest as the codec says.
	arg(value) {
		if (value?.vp?.id) return { ref: value.vp.id };
		if (Array.isArray(value)) return value.map((v) => this.arg(v));
		return value;
	}

	call(object, method, args, { wait = false } = {}) {
		return this.send(callMessage(object, method, args.map((a) => this.arg(a))), { wait });
	}

	// Queue a request; it leaves with the others of this task. What it will do to the
	// tree and the motors shows in the mirror at once (prediction.js), as 1.0 did it at
	// once. With `wait`, a promise of its result.
	send(message, { wait = false } = {}) {
		if (this.gathered && !wait) return this.hold(message);
		const { text, answer } = this.requested(message, { wait });
		this.queue(text);
		return answer && within(answer, this.timeout, () => `no answer to ${message.op} ${message.method ?? ''}`.trim());
	}

	// Queue a request whose final form `ready` gives later: it and every request after
	// it wait here until then, so the server still takes them in order.
	sendLater(message, ready) {
		const { id } = this.requested(message);
		const entry = { text: null };
		this.queue(entry);
		ready.then((final) => {
			entry.text = encode({ ...final, id });
			this.flush();
		});
	}

	// A request numbered, and what it does predicted (a closed session or a kept error
	// throws); what the step gathered so far leaves first.
	requested(message, options) {
		this.sendGathered();
		if (this.closed) throw new ConnectionLost(this.closed);
		this.core.raiseDeferred();
		this.prediction?.request(message, this.core.nextId);
		return this.core.request(message, options);
	}

	// Run an animation step: the requests it makes that nobody waits for, and the
	// transforms it wrote, leave as one batch (so as one request of the server's, applied
	// as one: a refused one undoes the others, and the next call throws it) when it ends,
	// or earlier, before a request someone waits for.
	gathering(step) {
		this.gathered = [];
		try {
			step();
			if (!this.closed) this.syncTransforms();
		} finally {
			this.sendGathered();
			this.gathered = null;
		}
	}

	// Keep a request of the step; what it does is predicted now, until the batch's answer
	// (the id the batch will have: nothing else is numbered before it leaves).
	hold(message) {
		if (this.closed) throw new ConnectionLost(this.closed);
		this.core.raiseDeferred();
		this.prediction?.request(message, this.core.nextId);
		const text = encode(message);
		this.core.checkSize(message, text);
		this.gathered.push({ message, bytes: text.length });
		return null;
	}

	// The gathered requests as batches of at most messagesPerText operations and about
	// TEXT_BYTES each (a lone one as it is).
	sendGathered() {
		if (!this.gathered?.length) return;
		let chunk = [], bytes = 0;
		const send = () => {
			if (chunk.length) this.queue(this.core.request(chunk.length === 1 ? chunk[0] : batchMessage(chunk)).text);
			chunk = [];
			bytes = 0;
		};
		for (const held of this.gathered.splice(0)) {
			if (chunk.length && (bytes + held.bytes > TEXT_BYTES || chunk.length >= this.maxPerText)) send();
			chunk.push(held.message);
			bytes += held.bytes + 1;
		}
		send();
	}

	queue(entry) {
		this.outbox.push(entry);
		if (this.outbox.length === 1 && !this.flushing) queueMicrotask(() => this.flush());
	}

	// Send the transforms written directly and every queued request, as few texts as fit.
	flush() {
		if (this.closed) return;
		this.flushing = true;
		try {
			this.syncTransforms();
		} finally {
			this.flushing = false;
		}
		const waiting = this.outbox.findIndex((entry) => entry.text === null);
		const texts = (waiting < 0 ? this.outbox.splice(0) : this.outbox.splice(0, waiting)).map((entry) => entry.text ?? entry);
		let group = [], bytes = 2;
		for (const text of texts) {
			if (group.length && (bytes + text.length > TEXT_BYTES || group.length >= this.maxPerText)) {
				this.transmit(join(group));
				group = [];
				bytes = 2;
			}
			group.push(text);
			bytes += text.length + 1;
		}
		if (group.length) this.transmit(join(group));
	}

	get maxPerText() {
		return this.hello.limits.messagesPerText;
	}

	// Resolves once the server has answered everything sent so far; throws a kept error.
	async sync() {
		this.flush();
		await within(this.core.settle(), this.timeout, () => `no answer to ${this.core.unanswered.size} requests`);
		if (this.closed) throw new ConnectionLost(this.closed);
		this.core.raiseDeferred();
	}

	// --- contacts -------------------------------------------------------------------------

	hearsContacts(id) {
		const object = this.objects.get(id);
		return Boolean(object?.hearsContacts);
	}

	dispatchContacts() {
		for (const [kind, a, b] of this.mirror.events.splice(0)) {
			for (const [self, other] of [[a, b], [b, a]]) {
				const object = this.objects.get(self);
				if (object?.hearsContacts) object[`${kind}Contact`](this.resolve(other));
			}
		}
	}
}

function join(texts) {
	return texts.length === 1 ? texts[0] : `[${texts.join(',')}]`;
}

// Arguments without trailing left-out ones (the server's defaults apply).
export function trimmed(args) {
	const out = args.map((a) => (a === undefined ? null : a));
	while (out.length && out[out.length - 1] === null) out.pop();
	return out;
}
