// The manual's Robot and hands. Getters read the mirror (motor order as the server lists
// it); setters turn the motors here at once and tell the server.

import { fromWire } from './codec.js';
import { SceneObject, forward, named } from './objects.js';

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
			this.vp.session.remember(this);
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
