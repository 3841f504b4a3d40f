// A heat map on the robots: each part glows red with the contact force pressing on it
// (the frames' `forces`, dynamic mode; full red at the largest force seen so far), and
// each sensor pad with its touch (0…1). Off until the plots panel turns it on.

export class Heat {
	// invalidate(): the picture must be drawn again
	constructor(tree, invalidate) {
		this.tree = tree;
		this.invalidate = invalidate;
		this.on = false;
		this.values = new Map();   // node id -> heat 0…1
		this.forces = new Map();   // part id -> newtons
		this.peak = 0;             // the largest force seen (N)
	}

	receive(message) {
		if (message.op === 'snapshot') {   // the forces pressing now; frames then change them
			this.forces.clear();
			this.values.clear();
			this.take(message);
			return this.paintAll();
		}
		if (message.op !== 'frame') return;
		const changed = this.take(message);
		for (const [sensor, reading] of Object.entries(message.sensors ?? {})) {
			if (typeof reading.touch === 'number') {
				this.values.set(sensor, reading.touch);
				changed.add(sensor);
			}
		}
		if (this.on && changed.size) {
			for (const id of changed) this.paint(id);
			this.invalidate();
		}
	}

	// The forces a message carries (0: ended); the ids whose heat changed.
	take(message) {
		const changed = new Set();
		for (const [id, newtons] of Object.entries(message.forces ?? {})) {
			if (newtons > 0) this.forces.set(id, newtons); else this.forces.delete(id);
			this.peak = Math.max(this.peak, newtons);
			changed.add(id);
		}
		for (const id of changed) this.values.set(id, (this.forces.get(id) ?? 0) / (this.peak || 1));
		return changed;
	}

	toggle(on) {
		this.on = on;
		this.paintAll();
	}

	paintAll() {
		for (const id of this.tree.objects.keys()) this.paint(id);
		this.invalidate();
	}

	// A node's own shape (not its children's) glows as hot as it is.
	paint(id) {
		const shape = this.tree.objects.get(id)?.children.find((child) => child.name === 'shape');
		const heat = this.on ? (this.values.get(id) ?? 0) : 0;
		shape?.traverse((mesh) => { if (mesh.isMesh && mesh.material.emissive) mesh.material.emissive.setRGB(heat, 0, 0); });
	}

	// The glow of a node now (0…1), as drawn.
	shown(id) {
		let found = null;
		this.tree.objects.get(id)?.children.find((child) => child.name === 'shape')
			?.traverse((mesh) => { if (found === null && mesh.isMesh && mesh.material.emissive) found = mesh.material.emissive.r; });
		return found;
	}
}
