// The plain three.js meshes a page adds to its scene (getScene(), or below its parts),
// shared as SceneMeshes of the server's scene, as 1.0's sensors met every mesh: made when
// first seen, placed when they move (one setTransforms entry each, in the step's one
// message), recoloured, hidden and shown, deleted when the page takes them away.
//
// Lights, cameras, lines, points, sprites and helpers stay the page's own, as does
// anything marked `userData.vpLocal` (the viewer's ground, lights and robots).
// `mesh.userData.vpShape = 'hull'` sends a mesh as its convex hull instead of its
// triangles. A geometry edited in place is not sent again: give the mesh a new one.

import * as THREE from 'three';
import { createMessage, deleteMessage } from './messages.js';

const position = new THREE.Vector3(), quaternion = new THREE.Quaternion(), scale = new THREE.Vector3();
const FULL_TURN = 2 * Math.PI;

export class PageMeshes {
	// roots(): the objects whose descendants are the page's (its scene, the client's parts).
	constructor(session, roots) {
		this.session = session;
		this.roots = roots;
		this.records = new Map();   // mesh -> {id, geometry, matrix, color, visible, pass}
		this.ids = new Set();       // ids of the SceneMeshes made for meshes (the page draws them)
		this.pass = 0;
		this.warned = new Set();
	}

	owns(id) { return this.ids.has(id); }

	// Walk the page's objects: new meshes are made, moved ones get an entry in
	// `transforms`, meshes no longer there are deleted.
	sync(transforms) {
		const pass = ++this.pass, roots = this.roots(), found = [];
		for (const root of roots) this.visit(root, true, found);
		// world matrices only when there are meshes to place: a page of parts alone (as
		// most are) skips updating every part's matrix each step
		if (found.length) for (const root of roots) root.updateMatrixWorld();
		for (let k = 0; k < found.length; k += 2) this.track(found[k], found[k + 1], pass, transforms);
		for (const [mesh, record] of this.records) if (record.pass !== pass) this.forget(mesh, record);
	}

	// The page's meshes below `object`, each followed by whether it is shown, into `found`.
	visit(object, shown, found) {
		for (const child of object.children) {
			if (child.userData.vpLocal || child.type.endsWith('Helper')) continue;
			const visible = shown && child.visible;
			if (child.isMesh && !child.vp) found.push(child, visible);
			if (child.children.length) this.visit(child, visible, found);
		}
	}

	track(mesh, visible, pass, transforms) {
		let record = this.records.get(mesh);
		if (record && record.geometry !== mesh.geometry) {
			this.forget(mesh, record);
			record = null;
		}
		record ??= this.make(mesh);
		if (!record) return;
		record.pass = pass;
		if (changed(record.matrix, mesh.matrixWorld.elements)) {
			mesh.matrixWorld.decompose(position, quaternion, scale);
			transforms[record.id] = [...position.toArray(), ...quaternion.toArray(),
				Math.abs(scale.x), Math.abs(scale.y), Math.abs(scale.z)];   // mirrored: drawn unmirrored elsewhere
		}
		const color = colorOf(mesh);
		if (color !== record.color && color !== null) this.session.call(record.id, 'setColor', [color]);
		if (visible !== record.visible) this.session.call(record.id, 'setVisible', [visible]);
		Object.assign(record, { color, visible });
	}

	make(mesh) {
		if (mesh.isInstancedMesh || mesh.isSkinnedMesh || !(mesh.geometry?.attributes?.position?.count >= 3)) {
			this.warnOnce(mesh.type, `a ${mesh.type} stays in this page only (not shared with the scene)`);
			this.records.set(mesh, { id: null, geometry: mesh.geometry, matrix: null, pass: this.pass });
			return null;
		}
		const id = this.session.newId();
		const color = colorOf(mesh);
		const geometry = this.describe(mesh);
		this.session.send(createMessage(id, 'SceneMesh', color === null ? [geometry] : [geometry, color]));
		this.ids.add(id);
		const record = { id, geometry: mesh.geometry, matrix: new Float64Array(16).fill(NaN), color, visible: true };
		this.records.set(mesh, record);
		return record;
	}

	forget(mesh, record) {
		this.records.delete(mesh);
		if (!record.id) return;
		this.ids.delete(record.id);
		if (!this.session.closed) this.session.send(deleteMessage(record.id));
	}

	// The SceneMesh geometry of a mesh: three.js's own primitives as such, any other geometry
	// as its triangles (or its hull), within the server's limits.
	describe(mesh) {
		const geometry = mesh.geometry, p = geometry.parameters ?? {};
		if (geometry.type === 'BoxGeometry') return { kind: 'box', size: [p.width, p.height, p.depth] };
		if (geometry.type === 'SphereGeometry' && p.phiLength >= FULL_TURN && p.thetaStart === 0 && p.thetaLength >= Math.PI) {
			return { kind: 'sphere', radius: p.radius };
		}
		if ((geometry.type === 'CylinderGeometry' || geometry.type === 'ConeGeometry') && !p.openEnded && p.thetaLength >= FULL_TURN) {
			const cone = geometry.type === 'ConeGeometry';
			return { kind: 'cylinder', radiusTop: cone ? 0 : p.radiusTop, radiusBottom: cone ? p.radius : p.radiusBottom,
				height: p.height, segments: p.radialSegments };
		}
		return this.mesh(geometry, mesh.userData.vpShape === 'hull');
	}

	mesh(geometry, hull) {
		const limits = this.session.hello.limits;
		let vertices = Array.from(geometry.attributes.position.array);
		const count = vertices.length / 3;
		const indices = geometry.index ? Array.from(geometry.index.array) : null;
		const triangles = (indices?.length ?? count) / 3;
		if (!hull && count <= limits.shapeVertices && triangles <= limits.shapeTriangles) {
			return indices ? { kind: 'triangles', vertices, indices } : { kind: 'triangles', vertices };
		}
		if (count > limits.shapeVertices) {   // a hull of evenly picked vertices: close enough
			const step = Math.ceil(count / limits.shapeVertices);
			vertices = vertices.filter((_, k) => Math.floor(k / 3) % step === 0);
			this.warnOnce('large', `a mesh of ${count} vertices is shared as the hull of every ${step}th`);
		}
		return { kind: 'hull', vertices };
	}

	warnOnce(key, text) {
		if (this.warned.has(key)) return;
		this.warned.add(key);
		console.warn(`Virtual Prosthetics: ${text}`);
	}
}

// Copies `elements` into `known` and tells whether anything differed.
function changed(known, elements) {
	let differs = false;
	for (let k = 0; k < 16; k++) {
		if (known[k] !== elements[k]) {
			known[k] = elements[k];
			differs = true;
		}
	}
	return differs;
}

function colorOf(mesh) {
	const material = Array.isArray(mesh.material) ? mesh.material[0] : mesh.material;
	return material?.color?.isColor ? material.color.getHex() : null;
}
