// The WebSocket under a session: the browser's, Node's own (22+), or `ws` from npm.

import { ProtocolError } from './errors.js';
import { Session } from './session.js';

async function socketClass() {
	if (globalThis.WebSocket) return globalThis.WebSocket;
	return (await import('ws')).default;
}

// Open a session on `url` (ws://host:port/ws?scene=…&role=…); resolves once the scene's
// snapshot has arrived, rejects with the server's error when it refuses. onMessage hears
// every server message that is not an answer, from the hello on.
export async function openSession(url, classes, onMessage = null) {
	const WebSocketClass = await socketClass();
	const socket = new WebSocketClass(url);
	const session = new Session({ send: (text) => socket.send(text), classes });
	if (onMessage) session.listeners.push(onMessage);
	session.socket = socket;
	socket.onmessage = (event) => {
		const text = typeof event.data === 'string' ? event.data : String(event.data);
		try {
			session.receive(text);
		} catch (error) {
			if (!(error instanceof ProtocolError)) throw error;
			console.error(error);
			socket.close(1002, 'protocol error');
		}
	};
	socket.onclose = (event) => session.lost(`connection closed (${event.code}${event.reason ? `: ${event.reason}` : ''})`);
	socket.onerror = () => {};   // the close that follows says it
	await session.ready;
	return session;
}
