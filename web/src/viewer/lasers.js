// Sensor lasers: a half-transparent line from each laser sensor to what it hits, with a
// dot at the hit point. The distance comes with every frame; the line follows the
// sensor as drawn (so it moves as smoothly as the robot).

import * as THREE from 'three';
import { fromWire } from '/client/codec.js';

const STUB = 0.055;   // a laser that hits nothing is drawn this long (as in 1.0)
const origin = new THREE.Vector3(), direction = new THREE.Vector3(), tip = new THREE.Vector3();

export class Lasers {
	constructor(tree, scene) {
		this.tree = tree;
		this.group = new THREE.Group();
		this.group.name = 'lasers';
		scene.add(this.group);
		this.beams = new Map();   // sensor id -> {line, dot, distance}
		tree.on('added', (object) => this.maybeAdd(object));
		tree.on('removed', (object) => this.drop(object.name));
	}

	maybeAdd(object) {
		const node = object.userData.node;
		if (node.type !== 'Sensor' || node.laserColor == null) return;
		const color = new THREE.Color(node.laserColor);
		const line = new THREE.Line(new THREE.BufferGeometry().setFromPoints([origin, origin]),
			new THREE.LineBasicMaterial({ color, transparent: true, opacity: 0.5 }));
		const dot = new THREE.Mesh(new THREE.SphereGeometry(0.015, 12, 6), new THREE.MeshBasicMaterial({ color }));
		line.frustumCulled = false;
		this.group.add(line, dot);
		this.beams.set(node.id, { line, dot, distance: Infinity, object });
	}

	drop(id) {
		const beam = this.beams.get(id);
		if (!beam) return;
		for (const part of [beam.line, beam.dot]) {
			part.removeFromParent();
			part.geometry.dispose();
			part.material.dispose();
		}
		this.beams.delete(id);
	}

	// A frame's sensor readings; true when a beam changed length.
	readings(sensors) {
		let changed = false;
		for (const [id, reading] of Object.entries(sensors)) {
			const beam = this.beams.get(id);
			const distance = fromWire(reading.distance);
			if (beam && beam.distance !== distance) {
				beam.distance = distance;
				changed = true;
			}
		}
		return changed;
	}

	// Redraw every beam from where its sensor is drawn now.
	step() {
		for (const beam of this.beams.values()) {
			beam.object.updateWorldMatrix(true, false);
			const e = beam.object.matrixWorld.elements;
			origin.setFromMatrixPosition(beam.object.matrixWorld);
			direction.set(e[4], e[5], e[6]).normalize();
			const hit = Number.isFinite(beam.distance);
			tip.copy(origin).addScaledVector(direction, hit ? beam.distance : STUB);
			beam.line.geometry.setFromPoints([origin, tip]);
			beam.dot.position.copy(tip);
			beam.dot.visible = hit && beam.object.visible;
			beam.line.visible = beam.object.visible;
		}
	}
}
