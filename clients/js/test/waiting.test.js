// How long the client waits: the caller's figure, else VP_TIMEOUT, else the default; a
// wait that runs out is a Timeout naming how to wait longer.

import assert from 'node:assert/strict';
import test from 'node:test';
import { Timeout } from '../errors.js';
import { DEFAULT_SECONDS, ENVIRONMENT, waitSeconds, within } from '../waiting.js';

function withEnvironment(value, run) {
	const before = process.env[ENVIRONMENT];
	if (value === undefined) delete process.env[ENVIRONMENT]; else process.env[ENVIRONMENT] = value;
	try {
		return run();
	} finally {
		if (before === undefined) delete process.env[ENVIRONMENT]; else process.env[ENVIRONMENT] = before;
	}
}

test('the wait is the caller\'s, else VP_TIMEOUT\'s, else the default', () => {
	withEnvironment(undefined, () => assert.equal(waitSeconds(), DEFAULT_SECONDS));
	withEnvironment('', () => assert.equal(waitSeconds(), DEFAULT_SECONDS));
	withEnvironment('2.5', () => assert.equal(waitSeconds(), 2.5));
	withEnvironment('2.5', () => assert.equal(waitSeconds(7), 7));
	assert.equal(waitSeconds(Infinity), Infinity);
});

test('a wait that is not a positive number is refused naming where it came from', () => {
	for (const wrong of [0, -3, NaN, '10', true]) {
		assert.throws(() => waitSeconds(wrong), /timeout must be a positive number of seconds/);
	}
	withEnvironment('soon', () => assert.throws(() => waitSeconds(), /VP_TIMEOUT must be/));
});

test('a promise that does not settle in time becomes a Timeout saying how to wait longer', async () => {
	const never = new Promise(() => {});
	await assert.rejects(within(never, 0.05, () => 'no answer to call'), (error) => {
		assert.ok(error instanceof Timeout);
		assert.equal(error.what, 'no answer to call');
		assert.equal(error.seconds, 0.05);
		assert.match(error.message, /within 0\.05 s \(connect\(\{timeout: S\}\) or VP_TIMEOUT=S waits longer\)/);
		return true;
	});
	assert.equal(await within(Promise.resolve(4), 0.05, () => 'x'), 4);
	await assert.rejects(within(Promise.reject(new Error('its own')), 10, () => 'x'), /its own/);
	assert.equal(within(never, Infinity, () => 'x'), never, 'for ever: the promise itself');
});
