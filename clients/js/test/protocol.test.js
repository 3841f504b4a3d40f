// The protocol core and the codec, without sockets.
import assert from 'node:assert/strict';
import { test } from 'node:test';

import { encode, encodeNumbers, fromWire, wireNumber } from '../codec.js';
import { ProtocolError, ServerError } from '../errors.js';
import { ProtocolCore } from '../protocol.js';

test('non-finite numbers travel as strings and come back', () => {
	assert.deepEqual([Infinity, -Infinity, NaN, 1.5].map(wireNumber), ['Infinity', '-Infinity', 'NaN', 1.5]);
	assert.equal(fromWire('Infinity'), Infinity);
	assert.equal(fromWire('-Infinity'), -Infinity);
	assert.ok(Number.isNaN(fromWire('NaN')));
	assert.equal(fromWire('dimgray'), 'dimgray');
	assert.deepEqual(encodeNumbers({ args: [-Infinity, [NaN, 2]], name: 'x' }),
		{ args: ['-Infinity', ['NaN', 2]], name: 'x' });
	assert.equal(encode({ op: 'create', args: [Infinity] }), '{"op":"create","args":["Infinity"]}');
});

test('requests get increasing ids and waited answers resolve with their result', async () => {
	const core = new ProtocolCore();
	const first = core.request({ op: 'ping' }, { wait: true });
	const second = core.request({ op: 'call', object: 'c1.1', method: 'getAngle' }, { wait: true });
	assert.deepEqual([first.id, second.id], [1, 2]);
	assert.deepEqual(JSON.parse(second.text), { op: 'call', object: 'c1.1', method: 'getAngle', id: 2 });
	core.receive('{"op":"ok","id":2,"result":0.25}');
	core.receive('{"op":"ok","id":1,"result":{"time":1,"seq":2}}');
	assert.equal(await second.answer, 0.25);
	assert.deepEqual(await first.answer, { time: 1, seq: 2 });
});

test('a refused call or creation names its objects; an answered one and a deletion none', () => {
	const refused = [];
	const core = new ProtocolCore({ onRefused: (ids) => refused.push(ids) });
	core.request({ op: 'call', object: 'c1.1', method: 'setPosition', args: [1e9, 0, 0] });
	core.request({ op: 'call', object: 'scene', method: 'setTransforms',
		args: [{ 'c1.2': [0, 0, 0, 0, 0, 0, 1], 'c1.3': [1, 0, 0, 0, 0, 0, 1] }] });
	core.request({ op: 'call', object: 'c1.4', method: 'setAngle', args: [1] });
	core.request({ op: 'delete', object: 'c1.5' });
	core.request({ op: 'create', object: 'c1.6', type: 'Box', args: [1e9] });
	core.receive('{"op":"error","id":1,"code":"out_of_range","message":"too far"}');
	core.receive('{"op":"error","id":2,"code":"not_owner","message":"c2 owns c1.3"}');
	core.receive('{"op":"ok","id":3}');
	core.receive('{"op":"error","id":4,"code":"not_owner","message":"c2 owns c1.5"}');
	core.receive('{"op":"error","id":5,"code":"out_of_range","message":"too big"}');
	assert.deepEqual(refused, [['c1.1'], ['c1.2', 'c1.3'], ['c1.6']]);
});

test('an error answer rejects its waiter with the wire fields', async () => {
	const core = new ProtocolCore();
	const { answer } = core.request({ op: 'create' }, { wait: true });
	core.receive(JSON.stringify({ op: 'error', id: 1, code: 'wrong_type', message: 'radius must be a number',
		request: 'create', details: { argument: 'radius' } }));
	await assert.rejects(answer, (error) => error instanceof ServerError && error.code === 'wrong_type' &&
		error.details.argument === 'radius' && error.request === 'create');
});

test('errors of requests nobody waits for are kept for the next call', () => {
	const core = new ProtocolCore();
	core.request({ op: 'call' });
	core.request({ op: 'call' });
	core.receive('{"op":"error","id":1,"code":"cycle","message":"below itself","request":"call"}');
	core.receive('{"op":"ok","id":2}');
	assert.throws(() => core.raiseDeferred(), (error) => error.code === 'cycle');
	assert.doesNotThrow(() => core.raiseDeferred());  // each kept error is thrown once
});

test('settle waits for every answer; changes, warnings and other messages go to their handlers', async () => {
	const seen = { messages: [], changes: [], warnings: [] };
	const core = new ProtocolCore({
		onMessage: (m) => seen.messages.push(m.op), onChanges: (c) => seen.changes.push(c),
		onWarning: (w) => seen.warnings.push(w),
	});
	core.request({ op: 'call' });
	let settled = false;
	const done = core.settle().then(() => { settled = true; });
	core.receive('{"op":"frame","seq":3,"time":0.1}');
	await Promise.resolve();
	assert.equal(settled, false);
	core.receive('{"op":"ok","id":1,"changes":{"angles":{"c1.2":0.5}},"warnings":["attached to c1.1 itself"]}');
	await done;
	assert.deepEqual(seen, { messages: ['frame'], changes: [{ angles: { 'c1.2': 0.5 } }],
		warnings: ['attached to c1.1 itself'] });
});

test('settle waits for what was sent before it, not for requests sent after', async () => {
	const core = new ProtocolCore();
	core.request({ op: 'call' });                    // 1
	core.request({ op: 'call' });                    // 2
	const order = [];
	const first = core.settle().then(() => order.push('up to 2'));
	core.request({ op: 'call' });                    // 3: a page sending every frame
	const second = core.settle().then(() => order.push('up to 3'));
	core.receive('{"op":"ok","id":2}');
	await Promise.resolve();
	assert.deepEqual(order, []);                     // 1 is still unanswered
	core.receive('{"op":"ok","id":1}');
	await first;
	core.request({ op: 'call' });                    // 4, never answered here
	core.receive('{"op":"ok","id":3}');
	await second;
	assert.deepEqual(order, ['up to 2', 'up to 3']);
});

test('unknown or broken server messages fail loudly', () => {
	const core = new ProtocolCore();
	assert.throws(() => core.receive('{"op":"surprise"}'), ProtocolError);
	assert.throws(() => core.receive('not json'), ProtocolError);
	assert.throws(() => core.receive('[1, 2]'), ProtocolError);
});

test('a lost connection rejects every waiter', async () => {
	const core = new ProtocolCore();
	const { answer } = core.request({ op: 'ping' }, { wait: true });
	core.lost(new Error('gone'));
	await assert.rejects(answer, /gone/);
	await core.settle();  // nothing is left unanswered
});

test('a reconnection loses the requests sent before the loss, not those made after it', async () => {
	const core = new ProtocolCore();
	const before = core.request({ op: 'ping' }, { wait: true });
	const sentBefore = core.nextId;   // the connection is lost here
	const after = core.request({ op: 'ping' }, { wait: true });
	const settled = core.settle();
	core.reconnected(new Error('reconnected'), sentBefore);
	await assert.rejects(before.answer, /reconnected/);
	core.receive(JSON.stringify({ op: 'ok', id: after.id, result: 7 }));
	assert.equal(await after.answer, 7);   // it went on the new connection
	await settled;
});

test("the scene's warnings (changes not saved, replaced) go to onWarning and onMessage", () => {
	const seen = { messages: [], warnings: [] };
	const core = new ProtocolCore({
		onMessage: (m) => seen.messages.push(m.op), onWarning: (w) => seen.warnings.push(w),
	});
	core.receive('{"op":"warning","code":"not_saved","message":"changes to scene lab cannot be saved"}');
	assert.deepEqual(seen, { messages: ['warning'],
		warnings: ['scene not_saved: changes to scene lab cannot be saved'] });
});
