// A robot's lists as 1.0 pages take them: right after building, in the same task.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;

test('lists taken right after building fill in once the server has built the robot', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-lists-${process.pid}` });
	try {
		const hand = new Prosthetic.EdgedHand(true);
		const motors = hand.getMotors();                 // the server has not answered yet
		const sensors = hand.getSensors();
		const robot = new Prosthetic.Robot();
		const base = new Prosthetic.MotorY(-1, 1);
		const sensor = new Prosthetic.Sensor();
		robot.attachChain(base, new Prosthetic.EdgedFinger(), new Prosthetic.MotorZ(), sensor);
		const parts = robot.getParts();
		const chain = robot.getMotors();
		await Prosthetic.sync();
		assert.equal(motors.length, 20);                  // 5 fingers × (spread + 3 flex)
		assert.ok(motors[0] instanceof Prosthetic.MotorX, 'the thumb spreads first');
		assert.deepEqual(motors, hand.getMotors());
		assert.deepEqual(sensors, []);
		assert.equal(parts.length, 4);
		assert.equal(parts[0], base);
		assert.equal(parts[3], sensor);
		assert.deepEqual(chain.map((m) => m.constructor.name), ['MotorY', 'MotorZ']);
		chain[1].setAngle(0.5);                          // the filled-in objects are the live ones
		assert.equal(robot.getAngle(1), 0.5);
		// a list taken once every request is answered is the robot as it is then
		await Prosthetic.sync();
		const now = robot.getMotors();
		new Prosthetic.MotorX().attachToSlot(sensor);
		await Prosthetic.sync();
		assert.equal(now.length, 2);
		assert.equal(robot.getMotors().length, 3);
	} finally {
		Prosthetic.close();
	}
});
