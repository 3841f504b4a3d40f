// How a motor shows its angle: its base rotation turned about its axis, the other way when
// flipped (server/core/model/motor.py). The client's objects and the viewer's both pose by it.

import * as THREE from 'three';

export const AXES = Object.freeze({ x: new THREE.Vector3(1, 0, 0), y: new THREE.Vector3(0, 1, 0), z: new THREE.Vector3(0, 0, 1) });
const turn = new THREE.Quaternion();
const vector = new THREE.Vector3();

// The turn of a motor about `axis` ('x', 'y', 'z' or a unit [x, y, z]) by `angle` (a
// flipped motor turns the other way).
export function motorTurn(axis, angle, flipped) {
	const unit = typeof axis === 'string' ? AXES[axis] : vector.set(...axis).normalize();
	return turn.setFromAxisAngle(unit, flipped ? -angle : angle);
}

// `out` set to what a node shows: `base` turned by its motor (a node without an axis: base).
export function shownRotation(out, base, { axis, angle, flipped }) {
	out.copy(base);
	return axis ? out.multiply(motorTurn(axis, angle, flipped)) : out;
}

// `out` set to the base rotation under what a node shows (its motor's turn taken back out).
export function baseRotation(out, shown, { axis, angle, flipped }) {
	out.copy(shown);
	return axis ? out.multiply(motorTurn(axis, angle, flipped).invert()) : out;
}

// A change set's `angles` as [motor id, angle] pairs: a robot's come as one array in the
// order of its `motors` (`motorsOf(robotId)`, read after the same change set's updates),
// a motor that is no robot's by its own id.
export function* eachAngle(angles, motorsOf) {
	for (const [id, value] of Object.entries(angles ?? {})) {
		if (!Array.isArray(value)) {
			yield [id, value];
			continue;
		}
		const motors = motorsOf(id) ?? [];
		for (let k = 0; k < value.length && k < motors.length; k++) yield [motors[k], value[k]];
	}
}
