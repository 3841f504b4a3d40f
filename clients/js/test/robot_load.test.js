// Robot.load: a URDF from a file's path, from bytes or a Blob becomes this client's robot,
// its motors named and limited as the file says, its mimic joint following.

import assert from 'node:assert/strict';
import { mkdtempSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';
import { FINGER_LIMITS, MIMIC, fingerUrdf } from './robot_files.js';

const URL_ = process.env.VP_URL;

test('Robot.load makes the robot a URDF describes, from a path, bytes or a Blob', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-load-${process.pid}` });
	try {
		const path = join(mkdtempSync(join(tmpdir(), 'vp-')), 'finger.urdf');
		writeFileSync(path, fingerUrdf());
		const robot = await Prosthetic.Robot.load(path, { position: [0.1, 0.2, 0] });
		assert.ok(robot instanceof Prosthetic.ImportedRobot);
		assert.deepEqual(robot.getPosition(), [0.1, 0.2, 0]);
		const motors = robot.getMotors();
		assert.deepEqual(motors.map((m) => [m.vp.session.mirror.nodes.get(m.vp.id).name, m.vp.session.mirror.nodes.get(m.vp.id).min]),
			[['knuckle', FINGER_LIMITS[0]], ['tip', FINGER_LIMITS[0]]]);
		robot.setAngles(1.2);
		await Prosthetic.sync();
		const angles = await robot.getAnglesExact?.() ?? robot.getAngles();
		assert.ok(Math.abs(angles[1] - (MIMIC[0] * 1.2 + MIMIC[1])) < 1e-9, `the tip follows: ${angles}`);
		const fromBlob = await Prosthetic.Robot.load(new Blob([fingerUrdf()]));
		assert.equal(fromBlob.getParts().length, robot.getParts().length);
		const bytes = new TextEncoder().encode(fingerUrdf().replace('type="revolute"', 'type="floating"'));
		await assert.rejects(Prosthetic.Robot.load(bytes), (error) => error.code === 'bad_asset' && /joint 'knuckle' is floating/.test(error.message));
	} finally {
		Prosthetic.close();
	}
});
