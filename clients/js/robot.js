// The manual's Robot and hands. Getters read the mirror (motor order as the server lists
// it); setters turn the motors here at once and tell the server.

import { fromWire } from './codec.js';
import { SceneObject, forward, named } from './objects.js';
import { remember } from './page_transforms.js';
import { serverCall } from './rest.js';
import { currentSession } from './session.js';

export class Robot extends SceneObject {
	static vpType = 'Robot';

	constructor(...args) {
		super(...forward(args[0], args[1], []));
	}

	attachChain(...parts) {
		this.call('attachChain', ...parts);
		return parts.at(-1);
	}

	addChain(...parts) {
		this.call('addChain', ...parts);
		return parts.at(-1);
	}

	// As in 1.0: the robot is returned (pages chain these two), and setPosition() with no
	// argument takes the robot out of the scene until it is given a position again.
	setPosition(position, ...more) {
		if (position === undefined && !more.length) {
			this.visible = false;
			remember(this);
			this.call('setPosition');
			return this;
		}
		this.visible = true;
		super.setPosition(position, ...more);
		return this;
	}

	setRotation(x, y, z, order = 'XYZ') {
		super.setRotation(x, y, z, order);
		return this;
	}

	// In a browser, robot.gui is the lil-gui panel at once (the viewer fills in the sliders).
	// Not in 1.0: let other clients set this robot's motor angles and attach their own
	// parts to it (without it only this client changes the robot).
	share(on = true) {
		this.call('share', on);
		return this;
	}

	// Not in 1.0 either: leave the robot in the scene when this page's connection ends.
	keep(on = true) {
		this.call('keep', on);
		return this;
	}

	addGUI(title = 'Robot') {
		this.vp.session.makePanel?.(this, title);
		this.call('addGUI', title);
	}

	// The objects of the nodes select(mirror) gives: the robot as it is now, this client's
	// requests included (the mirror predicts them; prediction.js).
	listed(select) {
		return this.objectsOf(select(this.vp.session.mirror));
	}

	objectsOf(nodes) {
		return nodes.map((node) => this.vp.session.object(node.id));
	}

	getParts() {
		return this.listed((mirror) => mirror.parts(this.vp.id));
	}

	getMotors() {
		return this.listed((mirror) => mirror.motors(this.vp.id));
	}

	getSensors() {
		return this.listed((mirror) => mirror.parts(this.vp.id).filter((n) => n.type === 'Sensor'));
	}

	// Not in 1.0: the hand's digits, derived by the server from its kinematics (the
	// schema's gripMap): each digit's tip, the motors that close it ({motor, index, open,
	// closed}, palm first), whether it opposes the others and its preshape if it does.
	async getGripMap() {
		return this.vp.session.call(this.vp.id, 'getGripMap', [], { wait: true });
	}

	// Not in 1.0, dynamic mode: each motor's speed (rad/s) and the torque (N·m) it
	// drove with at the last step, in motor order (0 in kinematic mode).
	async getSpeeds() {
		return this.vp.session.call(this.vp.id, 'getSpeeds', [], { wait: true });
	}

	async getTorques() {
		return this.vp.session.call(this.vp.id, 'getTorques', [], { wait: true });
	}

	getPosition() {
		return this.position.toArray();
	}

	getAngle(index) {
		return this.getAngles()[index] ?? 0;
	}

	getAngles() {
		return this.vp.session.mirror.motors(this.vp.id).map((node) => fromWire(node.angle));
	}

	setAngle(index, angle) {
		this.call('setAngle', index, angle);
	}

	setAngles(...angles) {
		this.call('setAngles', ...angles);
	}

	// Not in 1.0: the robot a description makes (a URDF, or a zip of one with its meshes),
	// this client's own. `source`: a URL (fetched here; in Node also a file's path), a File
	// or Blob (a dropped file) or bytes; `position` [x, y, z] and `rotation` (Euler [x, y,
	// z]) place it, `file` names the description in a zip holding several. The server reads
	// it (meshes resolve inside the upload only); a refusal throws its ServerError.
	static async load(source, { position, rotation, file } = {}) {
		const session = currentSession();
		const query = file ? `?file=${encodeURIComponent(file)}` : '';
		const answer = await serverCall(session.http, session.token, `/api/robots${query}`, 'Robot.load',
			{ method: 'POST', body: await robotBytes(source), headers: { 'Content-Type': 'application/octet-stream' } });
		const robot = new ImportedRobot((await answer.json()).file);
		if (position) robot.setPosition(...position);
		if (rotation) robot.setRotation(...rotation);
		await session.sync();   // its links and motors are in the mirror
		return robot;
	}
}

// Not in 1.0: a robot from a robot file the server keeps (`file`: what POST /api/robots
// answered; Robot.load uploads one and makes the robot).
export class ImportedRobot extends Robot {
	static vpType = 'ImportedRobot';

	constructor(file, ...more) {
		super(...forward(file, more[0], [file]));
	}
}

// The bytes of a robot upload from what Robot.load was given.
async function robotBytes(source) {
	if (source instanceof Uint8Array || source instanceof ArrayBuffer) return source;
	if (typeof Blob !== 'undefined' && source instanceof Blob) return new Uint8Array(await source.arrayBuffer());
	const text = String(source);
	if (globalThis.document || /^https?:/.test(text)) {
		const answer = await fetch(new URL(text, globalThis.document?.baseURI));
		if (!answer.ok) throw new Error(`Robot.load: ${text} answered ${answer.status}`);
		return new Uint8Array(await answer.arrayBuffer());
	}
	const { readFile } = await import('node:fs/promises');
	return readFile(text);
}

// The hands' finger control (thumb 0, index 1, middle 2, ring 3, little 4).
function hand(type) {
	return named(type, class extends Robot {
		static vpType = type;

		constructor(isLeft, ...more) {
			super(...forward(isLeft, more[0], [isLeft]));
		}

		flexFinger(index, angle) {
			this.call('flexFinger', index, angle);
		}

		flexFingers(angle) {
			this.call('flexFingers', angle);
		}

		spreadFinger(index, angle) {
			this.call('spreadFinger', index, angle);
		}

		spreadFingers(angle, includeThumb) {
			this.call('spreadFingers', angle, includeThumb);
		}
	});
}

export const EdgedHand = hand('EdgedHand');
export const RoundHand = hand('RoundHand');
export const AnthroHand = hand('AnthroHand');
