// The WebSocket to the server, reopened after every loss (a server restart, a network
// hiccup) with a growing pause; each new connection starts with a fresh snapshot. A
// connection the server refuses (an error before its hello: a bad scene name, role or
// engine) is not retried: trying again would not help. Request ids and answers are the
// JavaScript client's protocol core, one per connection.

import { Backoff } from '/client/backoff.js';
import { ProtocolCore } from '/client/protocol.js';

export class Connection {
	constructor(url, { onMessage, onState }) {
		this.url = url;
		this.onMessage = onMessage;
		this.onState = onState;
		this.socket = null;
		this.core = null;
		this.backoff = new Backoff();
		this.open();
	}

	open() {
		this.onState('connecting');
		const socket = this.socket = new WebSocket(this.url);
		const core = this.core = new ProtocolCore({
			onMessage: (message) => this.onMessage(message),
			onRefusal: (error) => { socket.refused = error.serverMessage ?? error.message; },
		});
		socket.onopen = () => { this.backoff.reset(); this.onState('connected'); };
		socket.onmessage = (event) => core.receive(event.data);
		socket.onclose = () => this.lost(socket, core);
	}

	lost(socket, core) {
		if (socket !== this.socket) return;
		core.lost(new Error('connection lost'));
		if (socket.refused) return this.onState(`refused: ${socket.refused}`);
		this.onState('reconnecting');
		setTimeout(() => this.open(), this.backoff.next());
	}

	// Send a request; the promise settles with its result (or the server's error).
	request(message) {
		if (this.socket?.readyState !== WebSocket.OPEN) return Promise.reject(new Error('not connected'));
		const { text, answer } = this.core.request(message, { wait: true });
		this.socket.send(text);
		return answer;
	}
}
