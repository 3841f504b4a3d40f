// The manual's classes. Every object is a three.js Object3D standing for one node of the
// scene on the server: constructors and methods take the manual's arguments in the
// manual's order (undefined: the server's default), setters change the object here at
// once and tell the server, getters read the mirror at once. Each read also has an exact
// form, `await x.<read>Exact(…)`, answered by the server after every earlier request.

import * as THREE from 'three';
import { fromWire } from './codec.js';
import { filled } from './lenient.js';
import { deleteMessage } from './messages.js';
import { remember } from './page_transforms.js';
import { currentSession } from './session.js';

let adopting = null;   // {session, id, type} while an object is made for an existing node
const euler = new THREE.Euler();

// Built-in classes hand their creation arguments to their base as (ARGS, [...]); a
// class's own constructor keeps the manual's parameters (and so its arity).
const ARGS = Symbol('creation arguments');

function forward(first, second, own) {
	return first === ARGS ? [ARGS, second] : [ARGS, own];
}

// Base of every scene object: `vp` holds its id, type and session.
export { ARGS, forward, named };

export class SceneObject extends THREE.Object3D {
	static vpType = 'Part';

	constructor(tag, args) {
		super();
		if (adopting) {
			adopting.session.register(this, adopting.id, adopting.type);
		} else {
			currentSession().make(this, new.target.vpType, tag === ARGS ? args : []);
		}
	}
	// An object of this class for a node this client did not make.
	static adopt(session, id, type) {
		adopting = { session, id, type };
		try {
			return new this();
		} finally {
			adopting = null;
		}
	}

	get node() { return this.vp.session.mirror.nodes.get(this.vp.id); }

	call(method, ...args) {
		this.vp.session.call(this.vp.id, method, args);
	}

	// Remove the object (and what is attached below it) from the scene.
	delete() {
		this.vp.session.send(deleteMessage(this.vp.id));
	}

	// setPosition(x, y, z) or setPosition([x, y, z]); a coordinate left out keeps its value.
	setPosition(position, ...more) {
		const given = Array.isArray(position) ? position : [position, ...more];
		const point = filled(given, this.position.toArray(), `${this.vp.id}.setPosition`);
		if (point.every(Number.isFinite)) {   // else the server refuses it, naming this call
			this.position.fromArray(point);
			remember(this);
		}
		this.call('setPosition', point);
	}

	// Euler angles; an angle left out keeps its value (read in the order given).
	setRotation(x, y, z, order = 'XYZ') {
		const now = euler.setFromQuaternion(this.vp.base, order).toArray().slice(0, 3);
		const angles = filled([x, y, z], now, `${this.vp.id}.setRotation`);
		if (angles.every(Number.isFinite)) {
			this.vp.base.setFromEuler(euler.set(...angles, order));
			this.vp.session.turn(this);
		}
		this.call('setRotation', ...angles, order);
	}
}

export class Slot extends SceneObject {
	static vpType = 'Slot';

	constructor(position, ...more) {
		super(...forward(position, more[0],
			position === undefined ? [] : [Array.isArray(position) ? position : [position, ...more]]));
	}
}

export class Part extends SceneObject {
	static vpType = 'Part';

	constructor(...args) {
		super(...forward(args[0], args[1], []));
	}

	// Not in 1.0: leave the part (and what hangs below it) in the scene when this page's
	// connection ends (connect({keep: true}) keeps everything it makes).
	keep(on = true) {
		this.call('keep', on);
		return this;
	}

	// addSlot(x, y, z) or addSlot([x, y, z]); the slot is returned at once (its id is
	// the one the server gives it: <part>/s<count>, counts from hello).
	addSlot(position, ...more) {
		const point = Array.isArray(position) ? position : [position ?? 0, more[0] ?? 0, more[1] ?? 0];
		const session = this.vp.session;
		const id = `${this.vp.id}/s${this.vp.slots++}`;
		this.call('addSlot', point);
		const slot = Slot.adopt(session, id, 'Slot');
		slot.position.fromArray(point);
		remember(slot);
		this.add(slot);
		return slot;
	}

	attachToSlot(parent, slot = 0) {
		this.call('attachToSlot', parent, slot);
		return this;
	}

	// Not in 1.0, dynamic mode: the part's mass (kg), friction and whether it never moves.
	setMass(mass) {
		this.call('setMass', mass);
		return this;
	}

	// Asks the server (a mass from the volume depends on the scales above the part).
	async getMass() {
		return this.vp.session.call(this.vp.id, 'getMass', [], { wait: true });
	}

	setFriction(friction) {
		this.call('setFriction', friction);
		return this;
	}

	setStatic(on = true) {
		this.call('setStatic', on);
		return this;
	}

	// True when a subclass overrides beginContact or endContact (only then are this
	// part's contact changes kept for it).
	get hearsContacts() {
		return this.beginContact !== Part.prototype.beginContact || this.endContact !== Part.prototype.endContact;
	}

	beginContact(otherPart) {}

	endContact(otherPart) {}
}

export class Motor extends Part {
	static vpType = 'Motor';

	constructor(axis, min, max, def) {
		super(...forward(axis, min, [axis, min, max, def]));
	}

	setName(name) {
		this.name = name;
		this.call('setName', name);
		return this;
	}

	getAngle() {
		return this.node?.angle ?? this.vp.angle;
	}

	// The motor turns here at once (clamped, as the server will: prediction.js).
	setAngle(angle) {
		this.call('setAngle', angle);
	}

	flip(bool = true) {
		this.call('flip', bool);
		return this;
	}

	// Not in 1.0, dynamic mode: the most torque (N·m) the motor drives with.
	setMaxTorque(torque) {
		this.call('setMaxTorque', torque);
		return this;
	}

	getMaxTorque() {
		return this.node?.maxTorque;
	}

	// Not in 1.0: the name setName gave it (an imported joint's: the file's), or null.
	getName() {
		return this.node?.name ?? null;
	}

	// Not in 1.0, dynamic mode: the fastest the motor moves (rad/s; a slider's scene
	// units/s), as a servo's rated speed (Infinity, the default: no limit).
	setMaxSpeed(speed) {
		this.call('setMaxSpeed', speed);
		return this;
	}

	getMaxSpeed() {
		return fromWire(this.node?.maxSpeed ?? Infinity);
	}

	// Not in 1.0, dynamic mode: the torque (N·m; a slider's force, N) the motor drove
	// with in the last step, positive pushing its angle up (0 in kinematic mode).
	async getTorque() {
		return this.vp.session.call(this.vp.id, 'getTorque', [], { wait: true });
	}

	// Not in 1.0, dynamic mode: how fast it turned at the last step (rad/s; a
	// slider's units/s), positive turning its angle up (0 in kinematic mode).
	async getSpeed() {
		return this.vp.session.call(this.vp.id, 'getSpeed', [], { wait: true });
	}

	// Not in the manual: turn with the motor `leader` at ratio·leader +
	// offset, as a linkage or tendon couples joints; follow() frees it.
	follow(leader = null, ratio = 1, offset = 0) {
		this.call('follow', leader, ratio, offset);
		return this;
	}
}

// Not in 1.0: a motor that slides along its axis (a linear actuator, an imported prismatic
// joint). Its angle, min and max are lengths in scene units; setMaxTorque sets its force (N).
export class Slider extends Motor {
	static vpType = 'Slider';
}

// MotorX(min, max, def, width, height) and its Y and Z kin.
function named(type, Class) {
	return Object.defineProperty(Class, 'name', { value: type });
}

function axisMotor(type) {
	return named(type, class extends Motor {
		static vpType = type;

		constructor(min, max, def, width, height) {
			super(...forward(min, max, [min, max, def, width, height]));
		}
	});
}

export const MotorX = axisMotor('MotorX');
export const MotorY = axisMotor('MotorY');
export const MotorZ = axisMotor('MotorZ');

export class Ball extends Part {
	static vpType = 'Ball';

	constructor(radius, color) {
		super(...forward(radius, color, [radius, color]));
	}
}

export class Box extends Part {
	static vpType = 'Box';

	constructor(sizex, sizey, sizez, color) {
		super(...forward(sizex, sizey, [sizex, sizey, sizez, color]));
	}
}

// A mesh of its own geometry, as the server keeps the meshes a page adds to getScene()
// (not in the manual; pages just add three.js meshes, see meshes.js). geometry: a SceneMesh
// geometry of the protocol ({kind: 'box', size: [x, y, z]}, …).
export class SceneMesh extends Part {
	static vpType = 'SceneMesh';

	constructor(geometry, color) {
		super(...forward(geometry, color, [geometry, color]));
	}

	setColor(color) {
		this.call('setColor', color);
	}
}

export class EdgedFinger extends Part {
	static vpType = 'EdgedFinger';

	constructor(length, width, thickness) {
		super(...forward(length, width, [length, width, thickness]));
	}
}

export class EdgedTip extends EdgedFinger {
	static vpType = 'EdgedTip';
}

export class EdgedPalm extends Part {
	static vpType = 'EdgedPalm';

	constructor(left, length, width, thickness) {
		super(...forward(left, length, [left, length, width, thickness]));
	}
}

// A part shaped by a mesh file; callback(part) runs once the server has made it (as
// 1.0 ran it once the file had loaded).
export class GLTFPart extends Part {
	static vpType = 'GLTFPart';
	static vpFileArgument = 0;   // which creation argument names the mesh file (session.js)

	constructor(filename, length, callback) {
		super(...forward(filename, length, [filename, length]));
		if (filename !== ARGS) this.whenMade(callback);
	}

	// callback(part) once the server has answered the creation, if it made the part (a
	// refusal is thrown by the page's next call, as every other one).
	whenMade(callback) {
		if (typeof callback !== 'function') return;
		const { session, id } = this.vp;
		session.core.settle().then(() => { if (session.mirror.nodes.has(id)) callback(this); });
	}

	recolor(fromColor, toColor, eps) {
		this.call('recolor', fromColor, toColor, eps);
	}
}

export class RoundFinger extends GLTFPart {
	static vpType = 'RoundFinger';
}

// A mesh part made for a left or a right hand: (left, filename, length, callback).
function handedPart(type) {
	return named(type, class extends GLTFPart {
		static vpType = type;
		static vpFileArgument = 1;

		constructor(left, filename, length, callback) {
			super(...forward(left, filename, [left, filename, length]));
			if (left !== ARGS) this.whenMade(callback);
		}
	});
}

export const RoundPalm = handedPart('RoundPalm');
export const AnthroPalm = handedPart('AnthroPalm');
export const AnthroThumb = handedPart('AnthroThumb');
