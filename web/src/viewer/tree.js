// The viewer's copy of the server's transform tree: one Object3D per node (robot, part,
// slot, motor, sensor), parented as on the server, posed by the snapshot and the frames.
// A motor's object turns about its axis by its angle on top of its own pose, as on the
// server; nothing here recomputes physics.

import * as THREE from 'three';
import { scaleAbove, shownPosition, shownRotation } from '/client/pose.js';
import { buildShape, dispose, paint } from './shapes.js';

const ONE = [1, 1, 1];
const SCALE = new THREE.Vector3();  // the scales above a slider, while it is posed

export class SceneTree {
	// drawnElsewhere(id): true for shapes the page draws itself (its own meshes)
	constructor(root, drawnElsewhere = () => false) {
		this.root = root;              // the THREE.Group all nodes hang from
		this.drawnElsewhere = drawnElsewhere;
		this.objects = new Map();      // id -> Object3D (userData.node: the description)
		this.listeners = { added: [], removed: [], changed: [], loaded: [] };
	}

	on(event, listener) { this.listeners[event].push(listener); }

	// What a person calls a node: "robot · motor" below a robot (each by its name, else the
	// robot's id and the motor's index; a name shared by several motors with the index too),
	// else its name or id.
	named(id) {
		const node = this.objects.get(id)?.userData.node;
		if (!node) return id;
		let top = node;
		while (top.parent && this.objects.has(top.parent)) top = this.objects.get(top.parent).userData.node;
		if (top === node) return node.name ?? id;
		const robot = top.name ?? top.id;
		const index = top.motors?.indexOf(id) ?? -1;
		if (node.name == null) return `${robot} · ${index >= 0 ? index : id.slice(id.lastIndexOf('/') + 1)}`;
		// a name other motors of the robot share too (a hand's five "distal") takes the index
		const twins = (top.motors ?? []).filter((m) => this.objects.get(m)?.userData.node.name === node.name);
		return `${robot} · ${node.name}${twins.length > 1 && index >= 0 ? ` #${index}` : ''}`;
	}

	emit(event, ...args) { for (const listener of this.listeners[event]) listener(...args); }

	// Forget everything (a new snapshot follows); listeners hear of every removal.
	clear() {
		this.remove([...this.objects.keys()]);
	}

	// Add described nodes; parents may come after their children in the list.
	add(descriptions) {
		for (const node of descriptions) this.make(node);
		for (const node of descriptions) this.place(node.id, node.parent, node.children);
		for (const node of descriptions) this.emit('added', this.objects.get(node.id));
	}

	make(node) {
		if (this.objects.has(node.id)) this.drop(node.id);
		const object = new THREE.Group();
		object.name = node.id;
		object.userData.node = { ...node };
		object.userData.base = new THREE.Quaternion(...node.quaternion);
		object.userData.basePosition = new THREE.Vector3(...node.position);
		object.position.set(...node.position);
		object.scale.fromArray(node.scale ?? ONE);
		const drawn = node.geometry && !(node.type === 'SceneMesh' && this.drawnElsewhere(node.id));
		// a SceneMesh's colour travels beside its geometry (setColor sends it alone)
		const geometry = node.color === undefined ? node.geometry : { ...node.geometry, color: node.color };
		const shape = drawn ? buildShape(geometry, node.physical, node) : null;
		if (shape) object.add(shape);
		object.userData.shape = shape;
		// a mesh file arrives later: the picture must be drawn again then
		shape?.userData.ready?.then(() => this.emit('loaded', object));
		this.objects.set(node.id, object);
		this.applyVisibility(object);
		this.setAngle(object, node.angle ?? 0);
	}

	place(id, parentId, childIds) {
		const object = this.objects.get(id);
		(this.objects.get(parentId) ?? this.root).add(object);
		this.adopt(object, childIds);
		this.reposeSliders(object);
	}

	adopt(object, childIds) {
		for (const childId of childIds ?? []) {
			const child = this.objects.get(childId);
			if (child) object.add(child);
		}
	}

	// Sliders at and below `object` posed again: how far they move depends on the scales
	// above them.
	reposeSliders(object) {
		object.traverse((o) => o.userData.node?.slides && this.setAngle(o, o.userData.shownAngle ?? 0));
	}

	remove(ids) {
		for (const id of ids) {
			const object = this.objects.get(id);
			if (object) {
				this.emit('removed', object);
				this.drop(id);
			}
		}
	}

	// Remove one node's object; its own meshes and overlays (children that are not
	// nodes) are freed, its child nodes are removed by their own ids.
	drop(id) {
		const object = this.objects.get(id);
		this.objects.delete(id);
		object.removeFromParent();
		for (const child of [...object.children]) if (!child.userData.node) dispose(child);
	}

	// A local pose [px, py, pz, qx, qy, qz, qw] from a frame.
	setPose(id, pose) {
		const object = this.objects.get(id);
		if (!object) return;
		object.position.set(pose[0], pose[1], pose[2]);
		object.userData.basePosition.set(pose[0], pose[1], pose[2]);
		object.userData.base.set(pose[3], pose[4], pose[5], pose[6]);
		this.setAngle(object, object.userData.node.angle ?? 0);
	}

	// The pose a motor shows: its base pose, turned about its axis (the other way if flipped);
	// a slider's moved along it.
	setAngle(object, angle) {
		const { axis, flipped, slides } = object.userData.node;
		shownRotation(object.quaternion, object.userData.base, { axis, angle, flipped, slides });
		if (slides) {
			shownPosition(object.position, object.userData.basePosition, object.userData.base,
				{ axis, angle, flipped, slides }, scaleAbove(SCALE, object));
		}
		object.userData.shownAngle = angle;
	}

	// Other fields of a node from a frame's "updates".
	update(id, fields) {
		const object = this.objects.get(id);
		if (!object) return;
		Object.assign(object.userData.node, fields);
		if ('children' in fields) this.adopt(object, fields.children);
		if ('parent' in fields) {
			(this.objects.get(fields.parent) ?? this.root).add(object);
			this.reposeSliders(object);
		}
		if ('visible' in fields) this.applyVisibility(object);
		if ('scale' in fields) {
			object.scale.fromArray(fields.scale);
			this.reposeSliders(object);
		}
		if ('color' in fields && object.userData.shape) paint(object.userData.shape, fields.color);
		if ('flipped' in fields) this.setAngle(object, object.userData.shownAngle ?? 0);
		if ('recolors' in fields) object.userData.shape?.userData.recolor?.(fields.recolors);
		this.emit('changed', object, fields);
	}

	// A hidden object hides with all it carries, as in three.js; a hidden sensor hides
	// only its pad (what it carries stays).
	applyVisibility(object) {
		const node = object.userData.node, visible = node.visible ?? true;
		const shape = object.userData.shape;
		if (node.type === 'Sensor') { if (shape) shape.visible = visible; }
		else object.visible = visible;
	}
}
