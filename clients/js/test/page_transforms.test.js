// Transforms a page writes to its objects: found against what the server knows, and sent
// as the base pose the server keeps (a motor's turn and a slider's slide taken out).

import assert from 'node:assert/strict';
import test from 'node:test';
import * as THREE from 'three';
import { moved, remember, transformEntry } from '../page_transforms.js';
import { shownPosition, shownRotation } from '../pose.js';

function object(vp = {}) {
	const made = new THREE.Object3D();
	made.vp = { base: new THREE.Quaternion(), basePosition: new THREE.Vector3(), angle: 0,
		known: new Float64Array(10), ...vp };
	remember(made);
	return made;
}

test('an object the page moved, turned or scaled differs from what the server knows until remembered', () => {
	const box = object();
	assert.equal(moved(box), false);
	for (const change of [(o) => { o.position.x = 0.5; }, (o) => { o.rotation.y = 0.1; },
		(o) => { o.scale.z = 2; }]) {
		change(box);
		assert.equal(moved(box), true);
		remember(box);
		assert.equal(moved(box), false);
	}
	box.visible = false;   // visibility travels as setVisible, not as a transform
	assert.equal(moved(box), false);
	assert.equal(box.vp.visible, true);
	remember(box);
	assert.equal(box.vp.visible, false);
});

test("a turned motor's entry carries the base rotation under its turn, and a scale only when it changed", () => {
	const motor = object({ axis: 'z', angle: 0.7, flipped: true });
	const base = new THREE.Quaternion().setFromEuler(new THREE.Euler(0.2, 0.4, -0.3));
	shownRotation(motor.quaternion, base, motor.vp);   // what the page sees after turning it
	motor.position.set(1, 2, 3);
	const entry = transformEntry(motor);
	assert.equal(entry.length, 7);
	assert.deepEqual(entry.slice(0, 3), [1, 2, 3]);
	assert.ok(new THREE.Quaternion().fromArray(entry, 3).angleTo(base) < 1e-7);
	assert.ok(motor.vp.base.angleTo(base) < 1e-7, 'the object keeps the new base too');
	motor.scale.set(1, 3, 1);
	assert.deepEqual(transformEntry(motor).slice(7), [1, 3, 1]);
});

test("a slider's entry is the place it slides from, whatever the scale of what it hangs on", () => {
	const parent = new THREE.Object3D();
	parent.scale.set(2, 2, 2);
	const slider = object({ axis: 'x', angle: 0.4, flipped: false, slides: true });
	parent.add(slider);
	const from = new THREE.Vector3(0.5, 0, -1);
	shownPosition(slider.position, from, slider.vp.base, slider.vp, new THREE.Vector3(2, 2, 2));
	assert.ok(slider.position.distanceTo(from) > 0.1, 'the slide moved it');
	const entry = transformEntry(slider);
	assert.ok(new THREE.Vector3().fromArray(entry).distanceTo(from) < 1e-12);
	assert.ok(slider.vp.basePosition.distanceTo(from) < 1e-12);
});
