// The Virtual Prosthetics logo: a white metallic "V" of three rings, spinning while the
// scene is empty.

import * as THREE from 'three';

// Turns a second where WebGL draws in software and the page set no ?fps=: a logo turned at
// every picture the cap allows (15 a second) kept SwiftShader drawing for a decoration,
// 1.25 cores for a viewer of an empty scene against 0.36 for one of a box that stands.
export const SOFTWARE_TURNS = 2;

export class Logo {
	// gapMs: at least this long between two turns (0: a turn at every picture)
	constructor(scene, gapMs = 0) {
		this.gapMs = gapMs;
		this.turnedAt = -Infinity;
		const material = new THREE.MeshStandardMaterial({ color: 'white', metalness: 0.6, roughness: 0.25 });
		const ring = (radius, x, y) => {
			const mesh = new THREE.Mesh(new THREE.TorusGeometry(radius, radius * 0.22, 24, 64), material);
			mesh.position.set(x, y, 0);
			mesh.castShadow = true;
			return mesh;
		};
		this.group = new THREE.Group();
		this.group.name = 'logo';
		// two rings high on the arms of the V, one small ring at its point
		this.group.add(ring(0.32, -0.42, 1.45), ring(0.32, 0.42, 1.45), ring(0.2, 0, 0.62));
		scene.add(this.group);
	}

	// True when the picture changed.
	step(now, empty) {
		if (!empty || now - this.turnedAt < this.gapMs) {
			const hidden = !empty && this.group.visible;
			if (hidden) this.group.visible = false;
			return hidden;
		}
		this.group.visible = true;
		this.group.rotation.y = now / 1000;
		this.turnedAt = now;
		return true;
	}
}
