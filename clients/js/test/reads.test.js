// Reads after writes, one read kind at a time: what a script reads right after it wrote
// is what it wrote, at once from the mirror (sync reads) or from the server (async reads),
// and it equals what the server then answers (the exact form), on a real server (VP_URL).

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;
const SKIP = { skip: !URL_ && 'needs VP_URL' };

async function inScene(name, body) {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-reads-${name}-${process.pid}` });
	try {
		await body(session);
	} finally {
		Prosthetic.close();
	}
}

// write() then read() at once; then read() and exact() after the server has answered
async function readsItsWrite({ write, read, exact, expected }) {
	write();
	assert.deepEqual(await read(), expected, 'read at once');
	await Prosthetic.sync();
	assert.deepEqual(await read(), expected, 'read once answered');
	assert.deepEqual(await exact(), expected, "the server's answer");
}

test('a motor reads its angle, name, torque and speed bounds right after they are set', SKIP, () => inScene('motor', async () => {
	const robot = new Prosthetic.Robot();
	const motor = new Prosthetic.MotorZ(-1, 1);
	robot.attachChain(motor, new Prosthetic.EdgedFinger());
	await readsItsWrite({ write: () => motor.setAngle(5), read: () => motor.getAngle(),
		exact: () => motor.getAngleExact(), expected: 1 });
	await readsItsWrite({ write: () => robot.setAngles(-0.25), read: () => robot.getAngles(),
		exact: () => robot.getAnglesExact(), expected: [-0.25] });
	await readsItsWrite({ write: () => motor.setName('Index'), read: () => motor.getName(),
		exact: () => motor.getNameExact(), expected: 'Index' });
	await readsItsWrite({ write: () => motor.setMaxTorque(0.4), read: () => motor.getMaxTorque(),
		exact: () => motor.getMaxTorqueExact(), expected: 0.4 });
	await readsItsWrite({ write: () => motor.setMaxSpeed(2.5), read: () => motor.getMaxSpeed(),
		exact: () => motor.getMaxSpeedExact(), expected: 2.5 });
	await readsItsWrite({ write: () => motor.setMaxSpeed(Infinity), read: () => motor.getMaxSpeed(),
		exact: () => motor.getMaxSpeedExact(), expected: Infinity });
	motor.setMaxTorque(-1);                          // refused: the read comes back
	await assert.rejects(Prosthetic.sync(), (error) => error.code === 'out_of_range');
	assert.equal(motor.getMaxTorque(), 0.4);
}));

test('a robot reads its position, parts and motors right after they change', SKIP, () => inScene('tree', async () => {
	const robot = new Prosthetic.Robot();
	const motor = new Prosthetic.MotorX();
	await readsItsWrite({ write: () => robot.setPosition(1, 2, 3), read: () => robot.getPosition(),
		exact: async () => (await robot.getPositionExact()), expected: [1, 2, 3] });
	await readsItsWrite({ write: () => robot.attachChain(motor), read: () => robot.getMotors(),
		exact: () => robot.getMotorsExact(), expected: [motor] });
	const part = new Prosthetic.Part();
	await readsItsWrite({ write: () => part.attachToSlot(motor), read: () => robot.getParts().includes(part),
		exact: async () => (await robot.getPartsExact()).includes(part), expected: true });
}));

test('a part reads its mass right after it is set', SKIP, () => inScene('mass', async () => {
	const part = new Prosthetic.Box(0.5);
	await readsItsWrite({ write: () => part.setMass(0.25), read: () => part.getMass(),
		exact: () => part.getMassExact(), expected: 0.25 });
}));

test("the physics reads right after setPhysics what the server makes of it (the hello's defaults)", SKIP, () => inScene('physics', async (session) => {
	const exact = () => session.call('scene', 'getPhysics', [], { wait: true });
	await readsItsWrite({ write: () => Prosthetic.setPhysics('dynamic', { gravity: 3, substeps: 4 }),
		read: () => Prosthetic.getPhysics(), exact, expected: await predictedBy(exact, 'dynamic', { gravity: 3, substeps: 4 }) });
	// options left out go back to their defaults, not to the scene's last values
	await readsItsWrite({ write: () => Prosthetic.setPhysics('dynamic', { friction: 0.5 }),
		read: () => Prosthetic.getPhysics(), exact, expected: await predictedBy(exact, 'dynamic', { friction: 0.5 }) });
	assert.equal(Prosthetic.getPhysics().gravity, session.hello.physics.gravity);
	await readsItsWrite({ write: () => Prosthetic.setPhysics('kinematic'), read: () => Prosthetic.getPhysics(),
		exact, expected: { ...session.hello.physics, mode: 'kinematic' } });
	Prosthetic.setPhysics('dynamic', { gravity: 1e9 });   // refused: the read comes back
	await assert.rejects(Prosthetic.sync(), (error) => error.code === 'out_of_range');
	assert.equal(Prosthetic.getPhysics().mode, 'kinematic');
}));

// What the client predicts for setPhysics(mode, options), checked here against the server
// itself: the prediction is read before the server answers, the server's answer after.
async function predictedBy(exact, mode, options) {
	Prosthetic.setPhysics(mode, options);
	const predicted = Prosthetic.getPhysics();
	assert.deepEqual(await exact(), predicted, "the prediction is the server's physics");
	return predicted;
}
