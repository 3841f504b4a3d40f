// The manual's Sensor. Its readings come with every frame once it is watched: the first
// reading starts the watch, and until the first frame with a reading the methods return
// what 1.0 returns when nothing is sensed. sensePosition is worked out from the mirror.
// The exact forms (`await sensor.senseDistanceExact()`) ask the server.

import * as THREE from 'three';
import { Part, forward } from './objects.js';

const NOTHING = Object.freeze({ distance: Infinity, touch: 0, objects: [], force: 0, contacts: [] });
const where = new THREE.Vector3();

export class Sensor extends Part {
	static vpType = 'Sensor';

	constructor(visible, laserColor) {
		super(...forward(visible, laserColor, [visible, laserColor]));
	}

	// The latest reading (starting the watch on first use).
	reading() {
		if (!this.vp.watched) this.watch(true);
		return this.vp.session.mirror.readings.get(this.vp.id) ?? NOTHING;
	}

	watch(on = true) {
		this.vp.watched = on;
		this.call('watch', on);
	}

	senseDistance() {
		return this.reading().distance;
	}

	senseTouch() {
		return this.reading().touch;
	}

	sensePosition() {
		this.updateWorldMatrix(true, false);
		return this.getWorldPosition(where).toArray();
	}

	// Not in 1.0: newtons pressing on the sensor's part, from everything or from one other
	// object (a part or 'ground'): a fingertip's force on what it holds, not on the table
	// beside it (dynamic mode; else 0).
	senseForce(otherObject) {
		const reading = this.reading();
		if (otherObject === undefined || otherObject === null) return reading.force ?? 0;
		const id = typeof otherObject === 'string' ? otherObject : otherObject?.vp?.id;
		return (reading.contacts ?? []).find((force) => force.other === id)?.normal ?? 0;
	}

	// Not in 1.0: what presses on the sensor's part, body by body: [{other, normal,
	// friction}] with `other` the object itself (or its id, or 'ground'), forces in N.
	senseContacts() {
		return (this.reading().contacts ?? []).map((force) => ({
			...force, other: this.vp.session.resolve(force.other) }));
	}

	senseObjects() {
		return this.reading().objects.map((id) => this.vp.session.resolve(id));
	}

	senseCollision() {
		return this.reading().objects.length > 0;
	}

	senseObject(otherObject) {
		const id = typeof otherObject === 'string' ? otherObject : otherObject?.vp?.id;
		return this.reading().objects.includes(id);
	}
}
