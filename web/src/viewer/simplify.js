// Fewer triangles for the same shape (meshoptimizer, as three.js ships it). Software
// WebGL spends a picture's time on vertices, not on pixels or draw calls: the demo's
// round fingers hold 3 136 triangles each, and 200 of them keep a finger's look.
// Unlike three.js's SimplifyModifier this bounds the error, so a shape that cannot lose
// that many triangles (the anthropomorphic palm) keeps what it needs.

import * as THREE from 'three';
import { MeshoptSimplifier } from 'three/addons/libs/meshopt_simplifier.module.js';
import { mergeVertices } from 'three/addons/utils/BufferGeometryUtils.js';

const ERROR = 0.01;  // how far the surface may move, relative to the mesh's size

// `geometry` with about `share` of its triangles, or more where the shape allows no
// more loss; a new geometry with the same attributes (colours included).
export async function simplified(geometry, share) {
	await MeshoptSimplifier.ready;
	if (geometry.index === null) geometry = mergeVertices(geometry);
	const index = geometry.index.array;
	const target = Math.max(3, Math.floor(index.length * share / 3) * 3);
	const [indices] = MeshoptSimplifier.simplify(new Uint32Array(index), packedPositions(geometry), 3,
		target, ERROR);
	const [remap, count] = MeshoptSimplifier.compactMesh(indices);
	const result = new THREE.BufferGeometry();
	for (const [name, attribute] of Object.entries(geometry.attributes)) {
		result.setAttribute(name, remapped(attribute, remap, count));
	}
	result.setIndex(new THREE.BufferAttribute(indices, 1));
	return result;
}

function packedPositions(geometry) {
	const position = geometry.getAttribute('position');
	const packed = new Float32Array(position.count * 3);
	for (let i = 0; i < position.count; i++) {
		packed.set([position.getX(i), position.getY(i), position.getZ(i)], 3 * i);
	}
	return packed;
}

// The vertices still referenced, in their new order (remap: old → new, or 0xffffffff).
function remapped(attribute, remap, count) {
	const size = attribute.itemSize;
	const result = new THREE.BufferAttribute(new attribute.array.constructor(count * size), size, attribute.normalized);
	for (let i = 0; i < remap.length; i++) {
		if (remap[i] === 0xffffffff) continue;
		for (let k = 0; k < size; k++) result.setComponent(remap[i], k, attribute.getComponent(i, k));
	}
	return result;
}
