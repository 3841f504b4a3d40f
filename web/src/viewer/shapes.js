// What each part looks like: a map from the server's geometry kind to a builder. Every
// builder returns a group of meshes (shadows on) whose materials belong to this part
// alone (so that one part can glow), and, for a physical part, a function giving the
// geometry of its collision envelope (only debug-physics asks). Parts shaped by GLB
// files are built in meshes.js.

import * as THREE from 'three';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';
import { sensorTexture } from './textures.js';
import { mesh as fileMesh } from './meshes.js';

const EDGE_OPACITY = 0.3;

function color(value) {
	return new THREE.Color(typeof value === 'number' ? value : value ?? 'dimgray');
}

function sphere(g) {
	const geometry = new THREE.SphereGeometry(g.radius, 32, 16);
	return { meshes: [new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: color(g.color) }))],
		envelope: () => new THREE.SphereGeometry(g.radius, 12, 6) };
}

function box(g) {
	const geometry = new THREE.BoxGeometry(...g.size);
	return { meshes: [new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: color(g.color) }))], envelope: () => geometry };
}

function convex(g) {
	const geometry = new ConvexGeometry(g.points.map((p) => new THREE.Vector3(...p)));
	const surface = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ color: color(g.color), flatShading: true }));
	if (!g.edges) return { meshes: [surface], envelope: () => geometry };  // a page's hull
	const edges = new THREE.LineSegments(new THREE.EdgesGeometry(geometry),
		new THREE.LineBasicMaterial({ color: color(g.edges), transparent: true, opacity: EDGE_OPACITY }));
	return { meshes: [surface, edges], envelope: () => geometry };
}

// A page's mesh as its triangles (a SceneMesh of kind triangles).
function triangles(g) {
	const geometry = new THREE.BufferGeometry();
	geometry.setAttribute('position', new THREE.Float32BufferAttribute(g.vertices, 3));
	geometry.setIndex(g.indices);
	geometry.computeVertexNormals();
	return { meshes: [new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: color(g.color) }))],
		envelope: () => new ConvexGeometry(pointsOf(g.vertices)) };
}

function pointsOf(flat) {
	const points = [];
	for (let k = 0; k < flat.length; k += 3) points.push(new THREE.Vector3(flat[k], flat[k + 1], flat[k + 2]));
	return points;
}

const AXIS_TURN = { x: new THREE.Euler(0, 0, Math.PI / 2), y: new THREE.Euler(), z: new THREE.Euler(Math.PI / 2, 0, 0) };

// A motor's drum (radius, length, sides, axis, center) or a page's cylinder (a SceneMesh:
// radiusTop, radiusBottom, height, segments, upright at the origin as three.js makes it).
function cylinder(g) {
	const geometry = g.segments
		? new THREE.CylinderGeometry(g.radiusTop, g.radiusBottom, g.height, g.segments)
		: new THREE.CylinderGeometry(g.radius, g.radius, g.length, g.sides);
	const mesh = new THREE.Mesh(geometry, new THREE.MeshPhongMaterial({ color: color(g.color), shininess: 100 }));
	if (g.axis) mesh.rotation.copy(AXIS_TURN[g.axis]);
	if (g.center) mesh.position.set(...g.center);
	return { meshes: [mesh], envelope: () => geometry };
}

function dome(g) {
	const geometry = new THREE.SphereGeometry(1, 32, 8, 0, 2 * Math.PI, 0, Math.PI / 2);
	const mesh = new THREE.Mesh(geometry, new THREE.MeshLambertMaterial({ color: color(g.color), map: sensorTexture() }));
	mesh.scale.set(g.radius, g.height, g.radius);
	return { meshes: [mesh], envelope: null };
}

export const SHAPES = { sphere, box, convex, triangles, cylinder, dome, mesh: fileMesh };

// The meshes of one part, in a group named 'shape'; null for an unknown kind.
export function buildShape(geometry, physical, node) {
	const builder = SHAPES[geometry.kind];
	if (!builder) {
		console.warn(`no shape for geometry kind ${geometry.kind}`);
		return null;
	}
	const { meshes, envelope, recolor, ready } = builder(geometry, node);
	const group = new THREE.Group();
	group.name = 'shape';
	for (const mesh of meshes) {
		mesh.castShadow = mesh.receiveShadow = mesh.isMesh;
		group.add(mesh);
	}
	group.userData.envelope = physical ? envelope : null;
	group.userData.recolor = recolor ?? null;
	group.userData.ready = ready ?? null;  // a promise while a file loads
	return group;
}

// A shape's new colour (a SceneMesh's setColor).
export function paint(shape, value) {
	shape.traverse((child) => { if (child.isMesh) child.material.color = color(value); });
}

// Free the GPU memory of an object and everything below it.
export function dispose(object) {
	object.traverse((child) => {
		child.geometry?.dispose();
		const materials = Array.isArray(child.material) ? child.material : [child.material];
		for (const material of materials) material?.dispose();
	});
}
