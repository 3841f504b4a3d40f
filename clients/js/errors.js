// Errors of the JavaScript client.
//
//   VPError              base of everything the client throws
//   ├── ServerError      the server answered a request with an error (code, message, details)
//   ├── ProtocolError    the server sent something the protocol does not define
//   ├── ConnectionLost   the WebSocket closed (or never opened)
//   └── Timeout          the server did not answer in time (waiting.js)

export class VPError extends Error {
	constructor(message) {
		super(message);
		this.name = new.target.name;
	}
}

export class ServerError extends VPError {
	// The error answer of the server, its wire fields as properties.
	constructor(code, message, request = null, details = {}) {
		super(`${code}: ${message}`);
		Object.assign(this, { code, request, details, serverMessage: message });
	}

	static fromWire(wire) {
		return new ServerError(wire.code, wire.message, wire.request ?? null, wire.details ?? {});
	}
}

export class ProtocolError extends VPError {}

export class ConnectionLost extends VPError {}

// `what` did not come within `seconds`; the message says how to wait longer.
export class Timeout extends VPError {
	constructor(what, seconds) {
		super(`${what} within ${seconds} s (connect({timeout: S}) or VP_TIMEOUT=S waits longer)`);
		Object.assign(this, { what, seconds });
	}
}
