// The Virtual Prosthetics logo: a white metallic "V" of three rings, spinning while the
// scene is empty.

import * as THREE from 'three';

export class Logo {
	constructor(scene) {
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
		const changed = empty || this.group.visible;
		this.group.visible = empty;
		if (empty) this.group.rotation.y = now / 1000;
		return changed;
	}
}
