// One constructor per message a client sends, making the typed definitions of
// wire_messages.js (written from protocol/schema/protocol.json; test/messages.test.js fails
// when they differ). Ids are added by the protocol core (protocol.js) when a request leaves.

/** @typedef {import('./wire_messages.js').Create} Create */
/** @typedef {import('./wire_messages.js').Call} Call */
/** @typedef {import('./wire_messages.js').Delete} Delete */
/** @typedef {import('./wire_messages.js').Batch} Batch */
/** @typedef {import('./wire_messages.js').Ping} Ping */

// `new type(...args)` as object `object` (args as they travel: objects as {ref}).
/** @returns {Create} */
export function createMessage(object, type, args = []) {
	return { op: 'create', object, type, args };
}

// A manual method `method` of object `object` ('scene' for the scene's own).
/** @returns {Call} */
export function callMessage(object, method, args = []) {
	return { op: 'call', object, method, args };
}

// Remove object `object` and what hangs below it.
/** @returns {Delete} */
export function deleteMessage(object) {
	return { op: 'delete', object };
}

// Several requests applied together, all or none.
/** @returns {Batch} */
export function batchMessage(ops) {
	return { op: 'batch', ops };
}

/** @returns {Ping} */
export function pingMessage() {
	return { op: 'ping' };
}
