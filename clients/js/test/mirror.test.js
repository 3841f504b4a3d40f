// The mirror holds this client's predictions until their answers (no server needed).

import assert from 'node:assert/strict';
import test from 'node:test';
import { Mirror } from '../mirror.js';

const motor = { id: 'm', type: 'MotorZ', parent: null, children: [], angle: 0, min: -1, max: 1 };

function frame(seq, changes) {
	return { op: 'frame', seq, time: seq / 60, ...changes };
}

test('a predicted angle stands through frames sent before its request was applied', () => {
	const mirror = new Mirror();
	mirror.add([motor]);
	mirror.predict('m', { angle: 0.5 }, 7);
	mirror.apply(frame(1, { angles: { m: 0.1 } }));        // the server before request 7
	assert.equal(mirror.nodes.get('m').angle, 0.5);
	mirror.applyChanges({ angles: { m: 0.5 } });          // request 7's answer
	mirror.release(7);
	mirror.apply(frame(2, { angles: { m: -0.2 } }));       // someone turned it since
	assert.equal(mirror.nodes.get('m').angle, -0.2);
});

test('a prediction the server did not follow gives way to what it said, once answered', () => {
	const mirror = new Mirror();
	mirror.add([motor, { id: 'r', type: 'Robot', parent: null, children: [], motors: [] }]);
	const seen = [];
	mirror.listeners.push((kind, id, fields) => seen.push([kind, id, fields]));
	mirror.predict('m', { parent: 'r' }, 3);
	mirror.predict('r', { children: ['m'], motors: ['m'] }, 3);
	mirror.apply(frame(1, { updates: { r: { children: [] } } }));
	assert.deepEqual(mirror.nodes.get('r').children, ['m']);
	mirror.release(2);                                     // an earlier request: still held
	assert.deepEqual(mirror.nodes.get('r').motors, ['m']);
	mirror.release(3);                                     // refused: no changes came
	assert.deepEqual(mirror.nodes.get('r').children, []);
	assert.deepEqual(mirror.nodes.get('r').motors, []);
	assert.equal(mirror.nodes.get('m').parent, null);
	assert.deepEqual(seen.slice(-2), [['changed', 'm', { parent: null }], ['changed', 'r', { children: [], motors: [] }]],
		'listeners hear it went back');
});

test('a predicted node stays until its creation is answered, and goes if it was refused', () => {
	const mirror = new Mirror();
	mirror.predict('b', { type: 'Ball', parent: null, children: [] }, 4);
	mirror.apply({ op: 'snapshot', nodes: [], camera: null, contacts: [], time: 0, seq: 0 });
	assert.ok(mirror.nodes.has('b'), 'a snapshot taken before the creation does not drop it');
	mirror.release(4);
	assert.ok(!mirror.nodes.has('b'));
	mirror.predict('c', { type: 'Ball', parent: null, children: [] }, 5);
	mirror.add([{ id: 'c', type: 'Ball', parent: null, children: [], geometry: { kind: 'sphere' } }]);
	mirror.release(5);
	assert.deepEqual(mirror.nodes.get('c').geometry, { kind: 'sphere' }, 'one the server made stays, as it made it');
});

test('a snapshot replaces the sensors\' readings: none of a world that may be gone', () => {
	const mirror = new Mirror();
	const snapshot = { op: 'snapshot', seq: 0, time: 0, camera: {}, physics: { mode: 'dynamic' }, nodes: [], contacts: [] };
	mirror.apply(snapshot);
	const pressed = { distance: 0.5, touch: 1, position: [0, 0, 0], objects: ['c1.b'], force: 3, contacts: [] };
	mirror.apply(frame(1, { sensors: { 'c1.s': pressed, 'c1.t': pressed } }));
	mirror.apply({ ...snapshot, sensors: { 'c1.s': { ...pressed, distance: 'Infinity', touch: 0, objects: [], force: 0 } } });
	assert.equal(mirror.readings.get('c1.s').distance, Infinity);
	assert.equal(mirror.readings.get('c1.s').touch, 0);
	assert.equal(mirror.readings.has('c1.t'), false);
});
