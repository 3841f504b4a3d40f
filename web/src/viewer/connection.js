// The WebSocket to the server, reopened after every loss (a server restart, a network
// hiccup) with a growing pause; each new connection starts with a fresh snapshot. A
// connection the server refuses (an error before its hello: a bad scene name, role or
// engine) is not retried: trying again would not help. Request ids and answers are the
// JavaScript client's protocol core, one per connection.

import { ProtocolCore } from '/client/protocol.js';

const RETRY_FIRST = 250, RETRY_MAX = 4000;

export class Connection {
	constructor(url, { onMessage, onState }) {
		this.url = url;
		this.onMessage = onMessage;
		this.onState = onState;
		this.socket = null;
		this.core = null;
		this.retry = RETRY_FIRST;
		this.open();
	}

	open() {
		this.onState('connecting');
		const socket = this.socket = new WebSocket(this.url);
		const core = this.core = new ProtocolCore({
			onMessage: (message) => {
				if (message.op === 'hello') socket.welcomed = true;
				if (message.op === 'error' && !socket.welcomed) socket.refused = message.message;
				this.onMessage(message);
			},
		});
		socket.welcomed = false;
		socket.onopen = () => { this.retry = RETRY_FIRST; this.onState('connected'); };
		socket.onmessage = (event) => core.receive(event.data);
		socket.onclose = () => this.lost(socket, core);
	}

	lost(socket, core) {
		if (socket !== this.socket) return;
		core.lost(new Error('connection lost'));
		if (socket.refused) return this.onState(`refused: ${socket.refused}`);
		this.onState('reconnecting');
		setTimeout(() => this.open(), this.retry);
		this.retry = Math.min(RETRY_MAX, this.retry * 2);
	}

	// Send a request; the promise settles with its result (or the server's error).
	request(message) {
		if (this.socket?.readyState !== WebSocket.OPEN) return Promise.reject(new Error('not connected'));
		const { text, answer } = this.core.request(message, { wait: true });
		this.socket.send(text);
		return answer;
	}
}
