// How a motor shows its angle: its base rotation turned about its axis, the other way when
// flipped; a slider (`slides`) keeps its rotation and moves along its axis instead, by a
// length in scene units whatever the scales above it (server/core/model/motor.py). The
// client's objects and the viewer's both pose by it.

import * as THREE from 'three';

export const AXES = Object.freeze({ x: new THREE.Vector3(1, 0, 0), y: new THREE.Vector3(0, 1, 0), z: new THREE.Vector3(0, 0, 1) });
const turn = new THREE.Quaternion();
const vector = new THREE.Vector3();
const stretch = new THREE.Vector3();

// The turn of a motor about `axis` ('x', 'y', 'z' or a unit [x, y, z]) by `angle` (a
// flipped motor turns the other way).
export function motorTurn(axis, angle, flipped) {
	const unit = typeof axis === 'string' ? AXES[axis] : vector.set(...axis).normalize();
	return turn.setFromAxisAngle(unit, flipped ? -angle : angle);
}

// `out` set to what a node shows: `base` turned by its motor (a node without an axis, or a
// slider: base).
export function shownRotation(out, base, { axis, angle, flipped, slides }) {
	out.copy(base);
	return axis && !slides ? out.multiply(motorTurn(axis, angle, flipped)) : out;
}

// `out` set to the base rotation under what a node shows (its motor's turn taken back out).
export function baseRotation(out, shown, { axis, angle, flipped, slides }) {
	out.copy(shown);
	return axis && !slides ? out.multiply(motorTurn(axis, angle, flipped).invert()) : out;
}

// `out` set to where a slider shows what hangs on it: `position` (its own, in its parent's
// frame, rotated by `rotation`) moved along its axis by `angle` scene units, `scale` being
// the product of the scales above it (a node that does not slide: `position`).
export function shownPosition(out, position, rotation, { axis, angle, flipped, slides }, scale) {
	out.copy(position);
	if (!axis || !slides) return out;
	const unit = typeof axis === 'string' ? AXES[axis] : vector.set(...axis).normalize();
	const direction = vector.copy(unit).applyQuaternion(rotation);
	const along = stretch.copy(direction).multiply(scale).length() || 1;
	return out.addScaledVector(direction, (flipped ? -angle : angle) / along);
}

// The product of the scales above `object` (its parents', to the root).
export function scaleAbove(out, object) {
	out.set(1, 1, 1);
	for (let above = object.parent; above; above = above.parent) out.multiply(above.scale);
	return out;
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
