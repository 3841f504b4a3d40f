// A motor's pose: its base rotation turned about its axis, the other way when flipped.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';
import { baseRotation, scaleAbove, shownPosition, shownRotation } from '../pose.js';

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

test('a slider keeps its rotation and moves along its axis by scene lengths, whatever the scale above', () => {
	const slider = { axis: [0, 0, 2], angle: 0.6, flipped: false, slides: true };
	assert.ok(shownRotation(new THREE.Quaternion(), base, slider).equals(base), 'no turn');
	const position = new THREE.Vector3(1, 2, 3);
	const along = new THREE.Vector3(0, 0, 1).applyQuaternion(base);
	const shown = shownPosition(new THREE.Vector3(), position, base, slider, new THREE.Vector3(2, 2, 2));
	// in its parent's frame, which the parent's scale of 2 stretches: 0.3 there is 0.6 in the scene
	assert.ok(shown.distanceTo(position.clone().addScaledVector(along, 0.3)) < 1e-12);
	const flipped = shownPosition(new THREE.Vector3(), position, base, { ...slider, flipped: true }, new THREE.Vector3(1, 1, 1));
	assert.ok(flipped.distanceTo(position.clone().addScaledVector(along, -0.6)) < 1e-12);
	const motor = { axis: 'z', angle: 0.6, flipped: false };
	assert.ok(shownPosition(new THREE.Vector3(), position, base, motor, new THREE.Vector3(1, 1, 1)).equals(position));
});

test('the scale above an object is the product of its parents', () => {
	const outer = new THREE.Group(), inner = new THREE.Group(), leaf = new THREE.Group();
	outer.scale.set(2, 3, 4);
	inner.scale.set(0.5, 2, 1);
	outer.add(inner);
	inner.add(leaf);
	assert.deepEqual(scaleAbove(new THREE.Vector3(), leaf).toArray(), [1, 6, 4]);
});
