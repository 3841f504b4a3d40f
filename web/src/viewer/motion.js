// Smooth motion between frames: a new motor angle or pose is reached over one tick
// period, so the picture moves at the display's rate while frames come at the tick rate.

import * as THREE from 'three';

export class Motion {
	constructor(tree) {
		this.tree = tree;
		this.period = 1 / 60;       // seconds; the hello's tick rate replaces it
		this.angles = new Map();   // id -> {object, from, to, start}
		this.poses = new Map();    // id -> {object, from: [position, quaternion], to, start}
	}

	angle(id, to, now) {
		const object = this.tree.objects.get(id);
		if (!object) return;
		object.userData.node.angle = to;
		this.angles.set(id, { object, from: object.userData.shownAngle ?? to, to, start: now });
	}

	pose(id, pose, now) {
		const object = this.tree.objects.get(id);
		if (!object) return;
		const from = [object.position.clone(), object.userData.base.clone()];
		const to = [new THREE.Vector3(pose[0], pose[1], pose[2]),
			new THREE.Quaternion(pose[3], pose[4], pose[5], pose[6])];
		this.poses.set(id, { object, from, to, start: now });
	}

	get busy() {
		return this.angles.size > 0 || this.poses.size > 0;
	}

	// Move everything towards its latest state; called before every render. True when
	// something moved.
	step(now) {
		const moved = this.busy;
		for (const [id, move] of this.poses) {
			const k = this.progress(move, now);
			move.object.position.lerpVectors(move.from[0], move.to[0], k);
			move.object.userData.base.slerpQuaternions(move.from[1], move.to[1], k);
			this.tree.setAngle(move.object, move.object.userData.shownAngle ?? 0);
			if (k >= 1) this.poses.delete(id);
		}
		for (const [id, move] of this.angles) {
			const k = this.progress(move, now);
			this.tree.setAngle(move.object, move.from + (move.to - move.from) * k);
			if (k >= 1) this.angles.delete(id);
		}
		return moved;
	}

	progress(move, now) {
		return Math.min(1, Math.max(0, (now - move.start) / this.period));
	}

	// Jump to the latest state (a new snapshot).
	clear() {
		this.angles.clear();
		this.poses.clear();
	}
}
