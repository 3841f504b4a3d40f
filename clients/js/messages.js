// One constructor per message a client sends, and the ops a server sends, as
// protocol/schema/protocol.json defines them (test/messages.test.js fails when they differ).
// Ids are added by the protocol core (protocol.js) when a request leaves.

export const SERVER_OPS = Object.freeze(['hello', 'snapshot', 'ok', 'error', 'frame', 'added', 'removed', 'warning']);

// `new type(...args)` as object `object` (args as they travel: objects as {ref}).
export function createMessage(object, type, args = []) {
	return { op: 'create', object, type, args };
}

// A manual method `method` of object `object` ('scene' for the scene's own).
export function callMessage(object, method, args = []) {
	return { op: 'call', object, method, args };
}

// Remove object `object` and what hangs below it.
export function deleteMessage(object) {
	return { op: 'delete', object };
}

// Several requests applied together, all or none.
export function batchMessage(ops) {
	return { op: 'batch', ops };
}

export function pingMessage() {
	return { op: 'ping' };
}
