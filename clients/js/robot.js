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

	// In a browser, robot.gui is the lil-gui panel at once (the viewer fills in the sliders).
	addGUI(title = 'Robot') {
		this.vp.session.makePanel?.(this, title);
		this.call('addGUI', title);
	}

	objectsOf(nodes) {
		return nodes.map((node) => this.vp.session.object(node.id));
	}

	getParts() {
		return this.objectsOf(this.vp.session.mirror.parts(this.vp.id));
	}

	getMotors() {
		return this.objectsOf(this.vp.session.mirror.motors(this.vp.id));
	}

	getSensors() {
		return this.objectsOf(this.vp.session.mirror.parts(this.vp.id).filter((n) => n.type === 'Sensor'));
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
		this.getMotors()[index]?.turnHere(angle);
		this.call('setAngle', index, angle);
	}

	setAngles(...angles) {
		const motors = this.getMotors();
		angles.forEach((angle, index) => motors[index]?.turnHere(angle));
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
