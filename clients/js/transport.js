// The WebSocket under a session: the browser's, Node's own (22+), or `ws` from npm. A
// connection lost (not closed by the page) is opened again as the same client (hello's
// `resume` key) while the server still keeps what the client made; what the page sends
// meanwhile waits and goes on the new connection.

import { Backoff } from './backoff.js';
import { ProtocolError } from './errors.js';
import { Session } from './session.js';
import { within } from './waiting.js';

const OPEN = 1;
const REPLACED = 4001;   // close code: this client connected again elsewhere (no coming back here)

async function socketClass() {
	if (globalThis.WebSocket) return globalThis.WebSocket;
	return (await import('ws')).default;
}

function withResume(url, key) {
	const address = new URL(url);
	address.searchParams.set('resume', key);
	return address.href;
}

// Open a session on `url` (ws://host:port/ws?scene=…&role=…); resolves once the scene's
// snapshot has arrived, rejects with the server's error when it refuses and with a Timeout
// when no snapshot came within `timeout` seconds. onMessage hears every server message that
// is not an answer, from the hello on.
export async function openSession(url, classes, { onMessage = null, timeout } = {}) {
	const WebSocketClass = await socketClass();
	const waiting = [];   // texts sent while no connection is open
	const session = new Session({
		send: (text) => (session.socket.readyState === OPEN ? session.socket.send(text) : waiting.push(text)),
		classes,
		timeout,
	});
	if (onMessage) session.listeners.push(onMessage);

	const open = (address) => new Promise((resolve) => {
		const socket = new WebSocketClass(address);
		let opened = false;
		socket.onopen = () => {
			opened = true;
			session.socket = socket;
			resolve(true);
		};
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
		socket.onclose = (event) => {
			if (!opened) return resolve(false);
			if (event.code === REPLACED) return session.lost(event.reason);
			lost(`connection closed (${event.code}${event.reason ? `: ${event.reason}` : ''})`);
		};
		socket.onerror = () => {};   // the close that follows says it
		if (!session.socket) session.socket = socket;   // the first: page.js listens to it
	});

	async function lost(reason) {
		const key = session.hello?.resume;
		if (session.closing || !key) return session.lost(reason);
		const sentBefore = session.core.nextId;   // later requests wait in `waiting`
		const deadline = Date.now() + 1000 * session.hello.limits.leaveGraceSeconds;
		for (const backoff = new Backoff(); Date.now() < deadline && !session.closing;) {
			if (await open(withResume(url, key))) {
				session.reconnected(sentBefore);
				for (const text of waiting.splice(0)) session.socket.send(text);
				return;
			}
			await new Promise((resolve) => setTimeout(resolve, backoff.next()));
		}
		session.lost(reason);
	}

	const address = url.split('?')[0];   // no token in messages
	const opened = (async () => {
		if (!(await open(url))) session.lost(`${address} could not be reached`);
		await session.ready;
	})();
	try {
		await within(opened, session.timeout, () => `no snapshot from ${address}`);
	} catch (error) {
		session.closing = true;   // given up: not a loss to come back from
		session.socket?.close();
		throw error;
	}
	return session;
}
