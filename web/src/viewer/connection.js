// The WebSocket to the server, reopened after every loss (a server restart, a network
// hiccup) with a growing pause; each new connection starts with a fresh snapshot. A
// connection the server refuses (an error before its hello: a bad scene name, role or
// engine) is not retried: trying again would not help.

const RETRY_FIRST = 250, RETRY_MAX = 4000;

export class Connection {
	constructor(url, { onMessage, onState }) {
		this.url = url;
		this.onMessage = onMessage;
		this.onState = onState;
		this.socket = null;
		this.retry = RETRY_FIRST;
		this.nextId = 1;
		this.pending = new Map(); // request id -> {resolve, reject}
		this.open();
	}

	open() {
		this.onState('connecting');
		const socket = this.socket = new WebSocket(this.url);
		socket.welcomed = false;
		socket.onopen = () => { this.retry = RETRY_FIRST; this.onState('connected'); };
		socket.onmessage = (event) => {
			const message = JSON.parse(event.data);
			if (message.op === 'hello') socket.welcomed = true;
			if (message.op === 'error' && !socket.welcomed) socket.refused = message.message;
			this.receive(message);
		};
		socket.onclose = () => this.lost(socket);
	}

	lost(socket) {
		if (socket !== this.socket) return;
		for (const { reject } of this.pending.values()) reject(new Error('connection lost'));
		this.pending.clear();
		if (socket.refused) return this.onState(`refused: ${socket.refused}`);
		this.onState('reconnecting');
		setTimeout(() => this.open(), this.retry);
		this.retry = Math.min(RETRY_MAX, this.retry * 2);
	}

	receive(message) {
		const waiter = message.id != null && this.pending.get(message.id);
		if (waiter) {
			this.pending.delete(message.id);
			if (message.op === 'error') waiter.reject(message); else waiter.resolve(message.result);
		}
		this.onMessage(message);
	}

	// Send a request; the promise settles with its result (or the error message).
	request(message) {
		const id = this.nextId++;
		return new Promise((resolve, reject) => {
			if (this.socket?.readyState !== WebSocket.OPEN) return reject(new Error('not connected'));
			this.pending.set(id, { resolve, reject });
			this.socket.send(JSON.stringify({ ...message, id }));
		});
	}
}
