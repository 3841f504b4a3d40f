// three.js turns Euler angles into the same quaternions as the server, for all six orders:
// against the server's answers in protocol/vectors/rotations.json, and live.

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import * as THREE from 'three';
import * as Prosthetic from '../virtual-prosthetics.js';

const vectors = JSON.parse(readFileSync(new URL('../../../protocol/vectors/rotations.json', import.meta.url)));
const ORDERS = ['XYZ', 'XZY', 'YXZ', 'YZX', 'ZXY', 'ZYX'];
const URL_ = process.env.VP_URL;

function close(actual, expected, label) {
	actual.forEach((value, i) => assert.ok(Math.abs(value - expected[i]) < 1e-12, `${label}: ${actual} vs ${expected}`));
}

test('three.js Euler → quaternion equals the server\'s for every order (vectors)', () => {
	const seen = new Set();
	for (const { send, expect } of vectors.steps) {
		if (send.method !== 'setRotation') continue;
		const [x, y, z, order] = send.args;
		const q = new THREE.Quaternion().setFromEuler(new THREE.Euler(x, y, z, order));
		close(q.toArray(), Object.values(expect[0].changes.poses)[0].slice(3), order);
		seen.add(order);
	}
	assert.deepEqual([...seen].sort(), [...ORDERS].sort());
});

test('a part turned in three.js style is turned the same on the server (live)', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-rotations-${process.pid}` });
	try {
		const parts = ORDERS.map((order) => {
			const part = new Prosthetic.Part();
			part.rotation.set(0.3, -0.5, 0.7, order);   // written directly: sent as a quaternion
			return part;
		});
		const viaSetter = ORDERS.map((order) => {
			const part = new Prosthetic.Part();
			part.setRotation(0.3, -0.5, 0.7, order);      // the manual's setter: sent as Euler angles
			return part;
		});
		await Prosthetic.sync();
		ORDERS.forEach((order, i) => {
			const expected = new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3, -0.5, 0.7, order)).toArray();
			for (const part of [parts[i], viaSetter[i]]) {
				close(session.mirror.nodes.get(part.vp.id).quaternion, expected, order);
				close(part.quaternion.toArray(), expected, `${order} (here)`);
			}
		});
	} finally {
		Prosthetic.close();
	}
});
