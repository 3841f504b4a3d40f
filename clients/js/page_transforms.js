// Transforms a page wrote directly to its objects (`part.position.x = …`, as 1.0's pages
// do): what the server last knew of each object is kept in `object.vp.known`, the
// objects that differ from it are found when a step ends, and each becomes its
// setTransforms entry. The entry's rotation is the base one (what the object shows less a
// motor's turn), its position a slider's base (less what it slid): what the server keeps.

import * as THREE from 'three';
import { baseRotation, scaleAbove, shownPosition } from './pose.js';

const base = new THREE.Quaternion();
const scale = new THREE.Vector3();  // the scales above a slider
const slid = new THREE.Vector3();   // how far a slider moved what hangs on it
const ZERO = new THREE.Vector3();

// The object's position, rotation, scale and visibility as the server knows them now.
export function remember(object) {
	const known = object.vp.known;
	object.position.toArray(known, 0);
	object.quaternion.toArray(known, 3);
	object.scale.toArray(known, 7);
	object.vp.visible = object.visible;
}

// True when an object's position, rotation or scale differs from what the server knows.
export function moved({ position: p, quaternion: q, scale: s, vp: { known } }) {
	return p.x !== known[0] || p.y !== known[1] || p.z !== known[2]
		|| q.x !== known[3] || q.y !== known[4] || q.z !== known[5] || q.w !== known[6]
		|| s.x !== known[7] || s.y !== known[8] || s.z !== known[9];
}

// A moved object's setTransforms entry: [x, y, z, qx, qy, qz, qw] and its scale only when
// that changed. Its base rotation (and a slider's base position) take the page's change.
export function transformEntry(object) {
	baseRotation(base, object.quaternion, object.vp);
	object.vp.base.copy(base);
	const position = object.position.clone();
	if (object.vp.slides) {   // less what the slider moved it by
		position.sub(shownPosition(slid, ZERO, base, object.vp, scaleAbove(scale, object)));
		object.vp.basePosition.copy(position);
	}
	const entry = [...position.toArray(), ...base.toArray()];
	const s = object.scale, known = object.vp.known;
	if (s.x !== known[7] || s.y !== known[8] || s.z !== known[9]) entry.push(s.x, s.y, s.z);
	return entry;
}
