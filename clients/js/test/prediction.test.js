// What the client predicts of its own requests is what the server then does: every hand
// of every side node by node, and a prediction the server refuses gives way.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;
// what a skeleton leaves out (generate/skeletons.py)
const DEFAULTS = { position: [0, 0, 0], quaternion: [0, 0, 0, 1], flipped: false };
const FIELDS = ['type', 'parent', 'children', 'motors', 'position', 'quaternion', 'axis', 'min', 'max', 'angle', 'flipped', 'name', 'slides'];

// The nodes of a robot's tree as the session's mirror has them now.
function tree(session, id) {
	return [...session.mirror.walk(id)].map((node) => Object.fromEntries(
		FIELDS.filter((field) => node[field] !== undefined && node[field] !== null).map((field) => [field, structuredClone(node[field])])
			.concat([['id', node.id]])));
}

test('every hand, left and right, is in the mirror at once as the server then makes it', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-predicted-hands-${process.pid}` });
	try {
		const predicted = [];
		for (const Hand of [Prosthetic.EdgedHand, Prosthetic.RoundHand, Prosthetic.AnthroHand]) {
			for (const isLeft of [true, false]) {
				const hand = new Hand(isLeft);
				predicted.push([hand, tree(session, hand.vp.id)]);
			}
		}
		await Prosthetic.sync();
		for (const [hand, nodes] of predicted) {
			assert.ok(nodes.length > 30, `${hand.vp.type} has its parts at once`);
			const made = tree(session, hand.vp.id);
			for (const node of made) {
				const guess = nodes.find((n) => n.id === node.id);
				assert.ok(guess, `${node.id} (${node.type}) predicted`);
				for (const field of FIELDS) {
					assert.deepEqual(guess[field] ?? DEFAULTS[field], node[field] ?? DEFAULTS[field], `${node.id}.${field}`);
				}
			}
			assert.equal(made.length, nodes.length);
		}
	} finally {
		Prosthetic.close();
	}
});

test('motors and sliders made by hand are in the mirror at once as the server then makes them', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-predicted-motors-${process.pid}` });
	try {
		const made = [new Prosthetic.Slider([0, 0.6, 0.8], 0.5, -0.25, 9), new Prosthetic.Slider('x'),
			new Prosthetic.Motor('y', 1, -1), new Prosthetic.MotorX(-0.5, 0.5, 0.2)];
		const predicted = made.map((motor) => tree(session, motor.vp.id));
		await Prosthetic.sync();
		made.forEach((motor, k) => {
			const [node] = tree(session, motor.vp.id), [guess] = predicted[k];
			for (const field of FIELDS) {
				assert.deepEqual(guess[field] ?? DEFAULTS[field], node[field] ?? DEFAULTS[field], `${motor.vp.type}.${field}`);
			}
		});
		assert.equal(predicted[0][0].slides, true);
		assert.equal(predicted[0][0].max, 0.5);   // limits swapped, the default clamped
	} finally {
		Prosthetic.close();
	}
});

test('a creation the server refuses leaves the robot as the server has it', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-predicted-refused-${process.pid}` });
	try {
		const robot = new Prosthetic.Robot();
		const good = new Prosthetic.MotorZ(0, 1);
		const bad = new Prosthetic.MotorZ('wide');        // the server refuses a string limit
		robot.attachChain(good, new Prosthetic.EdgedFinger(), bad);
		assert.equal(robot.getMotors().length, 2);        // what 1.0 would have built
		await assert.rejects(Prosthetic.sync(), /wide|min/);
		// the chain named a motor that was never made, so the server refused it whole
		await assert.rejects(Prosthetic.sync(), /unknown_object/);
		assert.deepEqual(robot.getMotors(), []);
		assert.deepEqual(await robot.getMotorsExact(), []);
		assert.equal(good.getAngle(), 0);
		assert.notEqual(good.parent, robot, 'the page tree shows the server\'s too');
		assert.equal(bad.parent, null, 'the refused motor is not in the page tree');
	} finally {
		Prosthetic.close();
	}
});
