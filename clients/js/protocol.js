// The client's side of the protocol, without any socket (sans-I/O): request ids, the
// answers being waited for, errors of requests nobody waits for (kept until the next
// call), warnings, and which server message goes where. The browser and Node transports
// feed it text and send what it returns; tests drive it directly.

import { encode } from './codec.js';
import { ProtocolError, ServerError } from './errors.js';
import { SERVER_OPS } from './wire_messages.js';

const UTF8 = new TextEncoder();
const ID_ROOM = 24;   // bytes: `,"id":` and the largest id

export class ProtocolCore {
	// onMessage(message): every server message that is not an answer; onChanges(changes):
	// what an answer says its request changed; onWarning(text): remarks in answers and the
	// scene's warnings;
	// onRefusal(error): the server refused the connection (an error before its hello: a
	// bad scene name, role or token; connecting again would not help);
	// onAnswered(id): every request up to `id` is answered and its changes told;
	// onRefused(ids): the objects a refused call or creation named (what was done here
	// at once for them did not happen on the server).
	constructor({ onMessage = () => {}, onChanges = () => {}, onWarning = () => {}, onRefused = () => {},
		onAnswered = () => {}, onRefusal = () => {} } = {}) {
		this.onMessage = onMessage;
		this.onRefusal = onRefusal;
		this.welcomed = false;     // a hello arrived
		this.onChanges = onChanges;
		this.onAnswered = onAnswered;
		this.onWarning = onWarning;
		this.onRefused = onRefused;
		this.nextId = 1;
		this.waiting = new Map();  // id -> { resolve, reject }
		this.unanswered = new Map(); // id -> the object ids a call names, oldest first
		this.deferred = [];        // ServerErrors of requests nobody waited for
		this.settled = [];         // [id, resolve]: called once every request up to id is answered
		this.messageBytes = 1 << 20; // the server's (hello's limits say)
	}

	// The text to send for `message` with a fresh id; with `wait`, also a promise of
	// the answer's result (rejected with a ServerError for an error answer).
	request(message, { wait = false } = {}) {
		const text = encode({ ...message, id: this.nextId });
		this.checkSize(message, text);
		const id = this.nextId++;
		this.unanswered.set(id, named(message));
		if (!wait) return { id, text, answer: null };
		const answer = new Promise((resolve, reject) => this.waiting.set(id, { resolve, reject }));
		return { id, text, answer };
	}

	// Refuse here, as the server would, a request whose text is over the server's
	// messageBytes: the server cannot tell which request such a text held, so its refusal
	// would answer none, and the caller would wait in vain.
	checkSize(message, text) {
		if (text.length * 3 + ID_ROOM <= this.messageBytes) return;   // (3 bytes a UTF-16 unit at most)
		const size = UTF8.encode(text).length + ID_ROOM;
		if (size <= this.messageBytes) return;
		throw new ServerError('too_large', `a ${message.op} request of ${size} bytes is over the server's limit of ${this.messageBytes} bytes (limit messageBytes; vp-server --limit messageBytes=N changes it)`,
			message.op, { limit: 'messageBytes', value: this.messageBytes, flag: '--limit messageBytes=N' });
	}

	// Take one text from the server. Unknown or malformed messages throw ProtocolError.
	receive(text) {
		let message;
		try {
			message = JSON.parse(text);
		} catch (error) {
			throw new ProtocolError(`the server sent text that is not JSON: ${String(text).slice(0, 80)}`);
		}
		if (message === null || typeof message !== 'object' || !SERVER_OPS.includes(message.op)) {
			throw new ProtocolError(`the server sent an unknown message: ${String(text).slice(0, 80)}`);
		}
		const isAnswer = (message.op === 'ok' || message.op === 'error') && message.id != null;
		if (message.op === 'warning') this.onWarning(`scene ${message.code}: ${message.message}`);
		if (!isAnswer) {
			if (message.op === 'hello') {
				this.welcomed = true;
				this.messageBytes = message.limits?.messageBytes ?? this.messageBytes;
			}
			if (message.op === 'error' && !this.welcomed) this.onRefusal(ServerError.fromWire(message));
			else if (message.op === 'error') this.deferred.push(ServerError.fromWire(message));
			this.onMessage(message);
			return message;
		}
		if (message.changes) this.onChanges(message.changes);
		for (const warning of message.warnings ?? []) this.onWarning(warning);
		this.answered(message);
		return message;
	}

	answered(message) {
		const targets = this.unanswered.get(message.id);
		this.unanswered.delete(message.id);
		const waiter = this.waiting.get(message.id);
		this.waiting.delete(message.id);
		this.onAnswered(message.id);
		if (message.op === 'error') {
			const error = ServerError.fromWire(message);
			if (targets?.length) this.onRefused(targets);
			if (waiter) waiter.reject(error); else this.deferred.push(error);
		} else if (waiter) {
			waiter.resolve(message.result);
		}
		this.release();
	}

	// Resolve the settle() promises whose requests are all answered (or lost).
	release() {
		const oldest = this.unanswered.keys().next().value ?? Infinity;
		const due = this.settled.filter(([id]) => id < oldest);
		this.settled = this.settled.filter(([id]) => id >= oldest);
		for (const [, resolve] of due) resolve();
	}

	// Throw the first kept error of a request nobody waited for.
	raiseDeferred() {
		if (this.deferred.length) throw this.deferred.shift();
	}

	// A promise that resolves once every request sent so far is answered (later ones
	// need not be: a page sending every frame still gets there).
	settle() {
		if (this.unanswered.size === 0) return Promise.resolve();
		return new Promise((resolve) => this.settled.push([this.nextId - 1, resolve]));
	}

	// A new connection replaced a lost one (as the same client): requests the loss left
	// unanswered may or may not have been applied. Their waiters hear `error`; the others'
	// loss is thrown by the next call.
	// Requests from `sentBefore` on were made after the loss and wait to go on the new
	// connection: they are not lost.
	reconnected(error, sentBefore = this.nextId) {
		const lost = [...this.unanswered.keys()].filter((id) => id < sentBefore);
		if (lost.some((id) => !this.waiting.has(id))) this.deferred.push(error);
		for (const id of lost) {
			this.unanswered.delete(id);
			this.waiting.get(id)?.reject(error);
			this.waiting.delete(id);
		}
		this.release();
	}

	// The connection is gone: every waiter hears it.
	lost(error) {
		for (const { reject } of this.waiting.values()) reject(error);
		this.waiting.clear();
		this.unanswered.clear();
		for (const [, resolve] of this.settled.splice(0)) resolve();
	}
}

// The objects a call or creation names: its object, or each one a setTransforms places
// (a batch: those its operations name).
function named(message) {
	if (message.op === 'batch') return message.ops.flatMap((op) => named(op) ?? []);
	if (message.op === 'create') return [message.object];
	if (message.op !== 'call') return null;
	if (message.method === 'setTransforms') return Object.keys(message.args[0] ?? {});
	return [message.object];
}
