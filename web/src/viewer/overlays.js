// Overlays chosen in the URL: parts in contact glow (touch-color), collision envelopes
// drawn in crimson (debug-physics), and a ring, disc and axes at every slot (show-slots).

import * as THREE from 'three';

const CRIMSON = 'crimson';
const SLOT_SIZE = 0.1;

export class Overlays {
	constructor(tree, options) {
		this.tree = tree;
		this.options = options;
		this.touching = new Map();   // id -> how many contacts it has
		this.glow = options.touchColor ? new THREE.Color(options.touchColor) : null;
		tree.on('added', (object) => this.decorate(object));
	}

	decorate(object) {
		const node = object.userData.node;
		const shape = object.userData.shape;
		if (this.options.debugPhysics && shape?.userData.envelope) {
			const envelope = shape.userData.envelope();
			const lines = new THREE.LineSegments(new THREE.EdgesGeometry(envelope, 1),
				new THREE.LineBasicMaterial({ color: CRIMSON, depthTest: false, transparent: true }));
			lines.renderOrder = 1;
			lines.name = 'envelope';
			shape.add(lines);
			if (!shape.children.some((mesh) => mesh.geometry === envelope)) envelope.dispose();  // made for this
		}
		if (this.options.showSlots && node.type === 'Slot') object.add(slotMarker());
		if (this.touching.has(node.id)) this.paint(object, true);
	}

	// All contact pairs at once (a snapshot).
	reset(pairs) {
		for (const id of this.touching.keys()) this.paintId(id, false);
		this.touching.clear();
		this.contacts({ begin: pairs, end: [] });
	}

	// A frame's contact changes.
	contacts({ begin, end }) {
		for (const pair of end) for (const id of pair) this.count(id, -1);
		for (const pair of begin) for (const id of pair) this.count(id, +1);
	}

	count(id, change) {
		const count = (this.touching.get(id) ?? 0) + change;
		if (count > 0) this.touching.set(id, count); else this.touching.delete(id);
		this.paintId(id, count > 0);
	}

	paintId(id, on) {
		const object = this.tree.objects.get(id);
		if (object) this.paint(object, on);
	}

	paint(object, on) {
		if (!this.glow) return;
		object.userData.shape?.traverse((mesh) => {
			if (mesh.isMesh && mesh.material.emissive) mesh.material.emissive.copy(on ? this.glow : BLACK);
		});
	}
}

const BLACK = new THREE.Color('black');

function slotMarker() {
	const marker = new THREE.Group();
	marker.name = 'slot-marker';
	const material = new THREE.MeshBasicMaterial({ color: CRIMSON, side: THREE.DoubleSide, transparent: true, opacity: 0.35, depthTest: false });
	const ring = new THREE.Mesh(new THREE.RingGeometry(SLOT_SIZE * 0.8, SLOT_SIZE, 32),
		new THREE.MeshBasicMaterial({ color: CRIMSON, side: THREE.DoubleSide, depthTest: false }));
	const disc = new THREE.Mesh(new THREE.CircleGeometry(SLOT_SIZE * 0.8, 32), material);
	ring.rotation.x = disc.rotation.x = -Math.PI / 2;   // in the slot's XZ plane, facing +Y
	const axes = new THREE.AxesHelper(SLOT_SIZE * 2);
	axes.material.depthTest = false;
	for (const part of [ring, disc, axes]) { part.renderOrder = 2; marker.add(part); }
	return marker;
}
