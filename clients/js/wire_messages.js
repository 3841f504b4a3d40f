// One typed definition (a JSDoc typedef) per wire message, and the op lists. Written by
// `make generate` (generate/message_types.py) from protocol/schema/protocol.json; do not
// edit (a test fails when the two differ). Messages stay plain objects: messages.js
// makes the ones a client sends, protocol.js checks the ops of those a server sends.

/**
 * @typedef {object} Create
 * @property {'create'} op
 * @property {number} [id]
 * @property {string} object
 * @property {string} type
 * @property {Array<*>} [args]
 */

/**
 * @typedef {object} Call
 * @property {'call'} op
 * @property {number} [id]
 * @property {string} object
 * @property {string} method
 * @property {Array<*>} [args]
 */

/**
 * @typedef {object} Delete
 * @property {'delete'} op
 * @property {number} [id]
 * @property {string} object
 */

/**
 * @typedef {object} Batch
 * @property {'batch'} op
 * @property {number} [id]
 * @property {Array<Object<string, *>>} ops
 */

/**
 * @typedef {object} Ping
 * @property {'ping'} op
 * @property {number} [id]
 */

/**
 * @typedef {object} Hello
 * @property {'hello'} op
 * @property {1} protocol
 * @property {string} client
 * @property {string} role
 * @property {string} scene
 * @property {number} time
 * @property {number} tickRate
 * @property {Object<string, number>} limits
 * @property {string} engine
 * @property {Object<string, number>} slots
 * @property {Object<string, *>} physics
 * @property {string} [resume]
 */

/**
 * @typedef {object} Snapshot
 * @property {'snapshot'} op
 * @property {string} scene
 * @property {number} seq
 * @property {number} time
 * @property {Object<string, *>} camera
 * @property {Object<string, *>} physics
 * @property {string} [caption]
 * @property {Array<Object<string, *>>} nodes
 * @property {Array<Array<string>>} contacts
 * @property {Object<string, number>} [forces]
 * @property {Object<string, Object<string, *>>} [sensors]
 */

/**
 * @typedef {object} Ok
 * @property {'ok'} op
 * @property {number} id
 * @property {*} [result]
 * @property {Object<string, *>} [changes]
 * @property {Array<string>} [warnings]
 */

/**
 * @typedef {object} Error
 * @property {'error'} op
 * @property {(number|null)} id
 * @property {string} code
 * @property {string} message
 * @property {string} [request]
 * @property {Object<string, *>} [details]
 */

/**
 * @typedef {object} Frame
 * @property {'frame'} op
 * @property {number} seq
 * @property {number} time
 * @property {*} [angles]
 * @property {*} [poses]
 * @property {*} [updates]
 * @property {Object<string, *>} [camera]
 * @property {Object<string, *>} [physics]
 * @property {string} [caption]
 * @property {Object<string, *>} [contacts]
 * @property {Object<string, Object<string, *>>} [sensors]
 * @property {Object<string, number>} [forces]
 * @property {Object<string, number>} [limited]
 */

/**
 * @typedef {object} Added
 * @property {'added'} op
 * @property {number} seq
 * @property {Array<Object<string, *>>} nodes
 */

/**
 * @typedef {object} Removed
 * @property {'removed'} op
 * @property {number} seq
 * @property {Array<string>} ids
 */

/**
 * @typedef {object} WarningMessage
 * @property {'warning'} op
 * @property {string} code
 * @property {string} message
 */

export const CLIENT_OPS = Object.freeze(["create", "call", "delete", "batch", "ping"]);
export const SERVER_OPS = Object.freeze(["hello", "snapshot", "ok", "error", "frame", "added", "removed", "warning"]);
