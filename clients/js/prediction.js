// What this client's requests will do to the scene's tree, worked out here before the
// server answers, so that a page reads its robot in the same task that built it, as in
// 1.0 (`new Robot().attachChain(…)` then `getMotors().length`). Sans-I/O: it writes
// predictions into the mirror, held until the request's answer (mirror.js).
//
// Each rule is the server's: the nodes a creation makes (slot counts from hello, motor
// limits as server/core/model/motor.py sets them, hands from skeletons.js, which the server
// generates), where attachToSlot puts a part (server/core/model/parts.py) and the motor order
// (depth first, server/core/model/robot.py). Tests compare every prediction with the server's
// answer, for the protocol vectors and every hand.

import { fromWire, wireNumber } from './codec.js';
import { SKELETONS } from './skeletons.js';

export class Prediction {
	// slots: type -> the numbered slots a new part has (hello); classes: type -> class.
	// physics: setPhysics's defaults (hello).
	constructor(mirror, { slots, classes, physics = {} }) {
		this.mirror = mirror;
		this.slots = slots;
		this.physics = physics;
		this.classes = classes;
		this.built = new Map();   // hand type -> id suffixes of the motors it is built with
	}

	isMotor(type) {
		const Class = this.classes[type], { Motor } = this.classes;
		return Boolean(Class && Motor && (Class === Motor || Class.prototype instanceof Motor));
	}

	// What request `until` (a create or call message, as it will be sent) does to the
	// tree and the motors' angles; other requests change nothing here.
	request(message, until) {
		const args = (message.args ?? []).map(plain);
		if (message.op === 'create') this.created(message.object, message.type, args, until);
		if (message.op !== 'call') return;
		const id = message.object;
		switch (message.method) {
			case 'attachToSlot': this.attached(id, args[0], args[1] ?? 0, until); break;
			case 'attachChain': this.chained([id, ...args], until); break;
			case 'addChain': this.chained(args, until); break;
			case 'setAngle': case 'setAngles':
				this.turn(this.angleTurns(id, message.method, args), until); break;
			case 'flexFinger': case 'flexFingers': case 'spreadFinger': case 'spreadFingers':
				this.turn(this.fingerTurns(id, message.method, args), until); break;
			case 'setName': case 'setMaxTorque': case 'setMaxSpeed':
				this.motorField(id, message.method, args[0], until); break;
			case 'setPhysics': this.physicsSet(args, until);
		}
	}

	// motor.setName(name), setMaxTorque(newtonMetres), setMaxSpeed(radPerS) as the
	// motor's fields (server/core/model/motor.py); a value the server refuses changes nothing.
	motorField(id, method, value, until) {
		if (this.mirror.nodes.get(id)?.axis === undefined) return;
		const number = typeof value === 'number' && value >= 0;
		const field = {
			setName: () => (typeof value === 'string' ? { name: value } : null),
			setMaxTorque: () => (number && Number.isFinite(value) ? { maxTorque: value } : null),
			setMaxSpeed: () => (number && value > 0 ? { maxSpeed: wireNumber(value) } : null),
		}[method]();
		if (field) this.mirror.predict(id, field, until);
	}

	// setPhysics(mode, options): the options left out take their defaults, not the
	// scene's earlier values (server/core/physics/dynamics.py, Physics.of).
	physicsSet([mode, options], until) {
		if (mode !== 'kinematic' && mode !== 'dynamic') return;
		if (options !== undefined && options !== null && typeof options !== 'object') return;
		this.mirror.predictPhysics({ ...this.physics, ...(options ?? {}), mode }, until);
	}

	// `new type(...args)` as object `id`, made by request `until`.
	created(id, type, args, until) {
		const nodes = SKELETONS[type] ? this.hand(id, type, args) : this.part(id, type, args);
		for (const node of nodes) this.mirror.predict(node.id, node, until);
		if (SKELETONS[type]) this.mirror.predict(id, { motors: this.motorOrder(id) }, until);
	}

	part(id, type, args) {
		const slots = Array.from({ length: this.slots[type] ?? 0 }, (_, k) => `${id}/s${k}`);
		const node = { type, parent: null, children: slots, ...(type === 'Robot' ? { motors: [] } : {}) };
		if (this.isMotor(type)) Object.assign(node, motorFields(type, args));
		return [{ id, ...node }, ...slots.map((slot) => ({ id: slot, type: 'Slot', parent: id, children: [] }))];
	}

	// motor.setAngle(angle), robot.setAngle(index, angle), robot.setAngles(a0, a1, …):
	// [[motor id, angle], …].
	angleTurns(id, method, args) {
		const motors = this.mirror.nodes.get(id)?.motors;
		if (motors === undefined) return method === 'setAngle' ? [[id, args[0]]] : [];
		return method === 'setAngle' ? [[motors[args[0]], args[1]]] : args.map((angle, index) => [motors[index], angle]);
	}

	// [[motor id, angle], …]: each motor to its angle, clamped; null and NaN are left out.
	turn(turns, until) {
		for (const [motorId, angle] of turns) {
			const motor = this.mirror.nodes.get(motorId);
			if (!motor || motor.axis === undefined || typeof angle !== 'number' || Number.isNaN(angle)) continue;
			this.mirror.predict(motorId, { angle: Math.min(fromWire(motor.max), Math.max(fromWire(motor.min), angle)) }, until);
		}
	}

	// A hand's finger method (thumb 0 … little 4): the motors the hand was built with, those
	// still in it, each to minus its angle (server/core/model/hands.py). A finger index the
	// server refuses turns nothing.
	fingerTurns(id, method, [first, second]) {
		const node = this.mirror.nodes.get(id), hand = SKELETONS[node?.type];
		if (!hand) return [];
		const { spread, flex, thumb: [offset, scale], shares } = hand.fingers;
		const finger = Number.isInteger(first) && first >= 0 && first < flex.length;
		const turns = {
			flexFinger: () => (finger ? flex[first].map((index) => [index, second]) : []),
			flexFingers: () => flex.flat().map((index) => [index, first]),
			spreadFinger: () => (finger ? [[spread[first], second]] : []),
			spreadFingers: () => (typeof first !== 'number' ? [] : [...(second ? [[spread[0], offset + scale * first]] : []),
				...shares.map((share, k) => [spread[k + 1], share * first])]),
		}[method]();
		const built = this.builtMotors(node.type).map((suffix) => id + suffix);
		return turns.filter(([index]) => this.root(built[index]) === id)
			.map(([index, angle]) => [built[index], typeof angle === 'number' ? -angle : null]);
	}

	builtMotors(type) {
		if (!this.built.has(type)) {
			this.built.set(type, SKELETONS[type].left.filter(([, kind]) => this.isMotor(kind)).map(([suffix]) => suffix));
		}
		return this.built.get(type);
	}

	// A hand and its parts; isLeft is true unless given as false (the server's default).
	hand(id, type, [isLeft]) {
		const made = new Map([[id, { id, type, parent: null, children: [], motors: [] }]]);
		for (const [suffix, kind, parent, fields] of SKELETONS[type][isLeft === false ? 'right' : 'left']) {
			const node = { id: id + suffix, type: kind, parent: id + parent, children: [], ...fields };
			made.get(node.parent).children.push(node.id);
			made.set(node.id, node);
		}
		return [...made.values()];
	}

	// part.attachToSlot(parent, slot) by request `until`: slot is an index or a Slot's id.
	attached(partId, parentId, slot, until) {
		const { nodes } = this.mirror;
		if (!nodes.has(partId) || !nodes.has(parentId)) return;
		let target = parentId;
		if (nodes.get(slot)?.type === 'Slot') {
			target = slot;
			if (nodes.get(slot).parent !== parentId && !this.below(parentId, slot)) this.link(slot, parentId, until);
		} else if (Number.isInteger(slot)) {
			target = this.numberedSlots(parentId)[slot] ?? parentId;
		} else {
			return;   // the server refuses it
		}
		if (target === partId || this.below(target, partId)) return;   // the server refuses a cycle
		this.link(partId, target, until);
	}

	// robot.addChain(a, b, …) (attachChain is addChain(robot, a, b, …)): each to slot 0
	// of the one before.
	chained(ids, until) {
		for (let k = 1; k < ids.length; k++) this.attached(ids[k], ids[k - 1], 0, until);
	}

	// Node `id` moved to the end of `parentId`'s children; the robots above its old and
	// new places list their motors again.
	link(id, parentId, until) {
		const { nodes } = this.mirror;
		const node = nodes.get(id), old = node.parent, roots = new Set();
		if (old !== null && nodes.has(old)) {
			this.mirror.predict(old, { children: nodes.get(old).children.filter((child) => child !== id) }, until);
			roots.add(this.root(old));
		}
		this.mirror.predict(parentId, { children: [...nodes.get(parentId).children.filter((c) => c !== id), id] }, until);
		this.mirror.predict(id, { parent: parentId }, until);
		roots.add(this.root(parentId));
		for (const root of roots) {
			if (nodes.get(root)?.motors !== undefined) this.mirror.predict(root, { motors: this.motorOrder(root) }, until);
		}
	}

	// The server's rule: a robot's motors are the motors below it, depth first, pre-order.
	motorOrder(robotId) {
		return [...this.mirror.walk(robotId)].filter((node) => this.isMotor(node.type)).map((node) => node.id);
	}

	// A part's numbered slots: the slots it was made with or given (ids <part>/s<k>)
	// that still hang on it.
	numberedSlots(id) {
		const prefix = `${id}/s`;
		return this.mirror.nodes.get(id).children.filter((child) => child.startsWith(prefix)
			&& this.mirror.nodes.get(child)?.type === 'Slot');
	}

	// True when node `id` lies below node `above` (or is it).
	below(id, above) {
		for (let node = this.mirror.nodes.get(id); node; node = this.mirror.nodes.get(node.parent)) {
			if (node.id === above) return true;
		}
		return false;
	}

	root(id) {
		let node = this.mirror.nodes.get(id);
		while (node?.parent && this.mirror.nodes.has(node.parent)) node = this.mirror.nodes.get(node.parent);
		return node?.id;
	}
}

// A new motor's axis, limits and angle, as server/core/model/motor.py sets them: limits given
// in reverse are swapped, the default angle is clamped into them (a Motor and a Slider take
// their axis first; MotorX and its kin have it in their names).
export function motorFields(type, args) {
	const [axis, ...rest] = type === 'Motor' || type === 'Slider' ? args : [type.at(-1).toLowerCase(), ...args];
	const [low = -Infinity, high = Infinity, start = 0] = rest.slice(0, 3).map((v) => (typeof v === 'number' ? v : undefined));
	const [min, max] = low <= high ? [low, high] : [high, low];
	return { axis, min: wireNumber(min), max: wireNumber(max), angle: Math.min(max, Math.max(min, start)), flipped: false,
		name: null, ...(type === 'Slider' ? { slides: true } : {}) };
}

// An argument as this module reads it: a reference as its id, a number that travels as
// a string as its number.
function plain(arg) {
	return arg?.ref ?? fromWire(arg);
}
