// A robot's reads as 1.0 pages make them: right after building, in the same task, with
// the answers 1.0 gave at once (the server agrees once it has answered).

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;

test('lists taken right after building are the robot at once', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-lists-${process.pid}` });
	try {
		const hand = new Prosthetic.EdgedHand(true);
		const motors = hand.getMotors();                 // the server has not answered yet
		assert.equal(motors.length, 20);                  // 5 fingers × (spread + 3 flex)
		assert.ok(motors[0] instanceof Prosthetic.MotorX, 'the thumb spreads first');
		assert.deepEqual(hand.getSensors(), []);
		hand.flexFingers(0.5);                            // the hand's own methods turn it at once too
		hand.spreadFinger(0, 2);
		assert.deepEqual(hand.getAngles().slice(0, 4), [-1, -0.5, -0.5, -0.5]);
		const robot = new Prosthetic.Robot();
		const base = new Prosthetic.MotorY(-1, 1);
		const sensor = new Prosthetic.Sensor();
		robot.attachChain(base, new Prosthetic.EdgedFinger(), new Prosthetic.MotorZ(), sensor);
		const parts = robot.getParts();
		assert.equal(parts.length, 4);
		assert.equal(parts[0], base);
		assert.equal(parts[3], sensor);
		assert.deepEqual(robot.getMotors().map((m) => m.constructor.name), ['MotorY', 'MotorZ']);
		assert.deepEqual(robot.getSensors(), [sensor]);
		const grip = await hand.getGripMap();           // the server's, from the hand's kinematics
		assert.deepEqual(grip.digits.map((digit) => digit.motors.map((m) => m.index)),
			[[1, 2, 3], [5, 6, 7], [9, 10, 11], [13, 14, 15], [17, 18, 19]]);
		assert.equal(grip.digits[0].opposes, true);
		assert.equal((await hand.getGripMapExact()).digits.length, 5);
		assert.equal(base.getName(), null);
		base.setName('wrist');
		await Prosthetic.sync();
		assert.equal(base.getName(), 'wrist');
		new Prosthetic.MotorX().attachToSlot(sensor);
		assert.equal(robot.getMotors().length, 3);
		await Prosthetic.sync();
		assert.deepEqual(hand.getMotors(), motors);
		assert.deepEqual(robot.getParts().slice(0, 4), parts);
		assert.deepEqual((await robot.getMotorsExact()).map((m) => m.vp.id), robot.getMotors().map((m) => m.vp.id));
	} finally {
		Prosthetic.close();
	}
});

// A robot of the manual's Step 5: three motors of these ranges, a finger after each.
class Digger extends Prosthetic.Robot {
	constructor() {
		super();
		for (const [min, max] of [[-0.7, 0.7], [-1.6, 0], [-1.6, 0]]) {
			this.addChain(this.getParts().at(-1) ?? this, new Prosthetic.MotorZ(min, max), new Prosthetic.EdgedFinger());
		}
	}
}

test('angles set right after building read back clamped at once, as the server clamps them', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-angles-${process.pid}` });
	try {
		const robot = new Digger();
		assert.equal(robot.getMotors().length, 3);
		robot.setAngles(5, 5, 5);
		assert.equal(robot.getAngle(0), 0.7);
		assert.deepEqual(robot.getAngles(), [0.7, 0, 0]);
		robot.setAngle(1, -9);
		robot.getMotors()[2].setAngle(-0.5);
		robot.setAngles(null, undefined, NaN);            // left as they are
		assert.deepEqual(robot.getAngles(), [0.7, -1.6, -0.5]);
		await Prosthetic.sync();
		assert.deepEqual(robot.getAngles(), [0.7, -1.6, -0.5]);
		assert.deepEqual(await robot.getAnglesExact(), [0.7, -1.6, -0.5]);
	} finally {
		Prosthetic.close();
	}
});
