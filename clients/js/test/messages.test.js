// The client's message constructors are the schema's messages (no server needed).

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import * as messages from '../messages.js';
import { CLIENT_OPS, SERVER_OPS } from '../wire_messages.js';

const SCHEMA = JSON.parse(readFileSync(new URL('../../../protocol/schema/protocol.json', import.meta.url)));
const DEFS = SCHEMA.$defs;
const MADE = {
	create: messages.createMessage('c1.1', 'Ball', [0.5]),
	call: messages.callMessage('c1.1', 'setPosition', [[0, 1, 0]]),
	delete: messages.deleteMessage('c1.1'),
	batch: messages.batchMessage([messages.deleteMessage('c1.1')]),
	ping: messages.pingMessage(),
};

test('every message a client sends has a constructor, and each makes the schema\'s message', () => {
	assert.deepEqual(Object.keys(MADE).sort(), [...DEFS.clientMessage.properties.op.enum].sort());
	assert.deepEqual([...CLIENT_OPS].sort(), Object.keys(MADE).sort());
	for (const [op, message] of Object.entries(MADE)) {
		const { properties, required } = DEFS[op];
		assert.equal(message.op, op);
		assert.deepEqual(Object.keys(message).filter((key) => !(key in properties)), [], op);
		// the protocol core adds the id when the request leaves
		assert.deepEqual(required.filter((key) => !(key in message)), [], op);
	}
});

test('the client knows every message a server sends', () => {
	assert.deepEqual([...SERVER_OPS].sort(), [...DEFS.serverMessage.properties.op.enum].sort());
});
