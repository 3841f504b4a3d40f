// A motor's pose: its base rotation turned about its axis, the other way when flipped.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';
import { baseRotation, shownRotation } from '../pose.js';

const base = new THREE.Quaternion().setFromEuler(new THREE.Euler(0.3, -0.2, 0.1));

test('a motor shows its base turned by its angle about its axis, a flipped one the other way', () => {
	const shown = shownRotation(new THREE.Quaternion(), base, { axis: 'z', angle: 0.5, flipped: false });
	const expected = base.clone().multiply(new THREE.Quaternion().setFromAxisAngle(new THREE.Vector3(0, 0, 1), 0.5));
	assert.ok(shown.angleTo(expected) < 1e-7);
	const flipped = shownRotation(new THREE.Quaternion(), base, { axis: 'z', angle: -0.5, flipped: true });
	assert.ok(flipped.angleTo(expected) < 1e-7);
	assert.ok(shownRotation(new THREE.Quaternion(), base, { angle: 0.5 }).equals(base), 'no axis: no turn');
});

test('the base under what a motor shows is found again', () => {
	for (const axis of ['x', 'y', 'z']) {
		const motor = { axis, angle: 1.2, flipped: axis === 'y' };
		const shown = shownRotation(new THREE.Quaternion(), base, motor);
		assert.ok(baseRotation(new THREE.Quaternion(), shown, motor).angleTo(base) < 1e-7, axis);
	}
});
