// What every method returns, as protocol/api.json says (1.0's returns: `this` where 1.0
// chained), and 1.0's leniency with coordinates left out.

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';
import { uploadedRobot } from './robot_files.js';

const URL_ = process.env.VP_URL;
const api = JSON.parse(readFileSync(new URL('../../../protocol/api.json', import.meta.url)));
const MESH = 'round-tip.glb';   // a bundled mesh, for the mesh parts
// how the client sends what a page writes to three.js properties, not methods of a page's
const SENT_BY_THE_CLIENT = new Set(['setQuaternion', 'setScale', 'setVisible', 'setTransforms']);

// An argument of each kind the table names (objects made fresh where one is needed).
const ARGUMENTS = {
	point: () => [0.1, 0.2, 0.3], number: () => 0.1, integer: () => 0, angle: () => 0.1,
	order: () => 'XYZ', quaternion: () => [0, 0, 0, 1], scale: () => [1, 1, 1], bool: () => true,
	string: () => 'named', slot: () => 0, color: () => 0x336699, rgb: () => [1, 0, 0],
	node: () => new Prosthetic.MotorZ(), part: () => new Prosthetic.Box(), motor: () => new Prosthetic.MotorZ(), axis: () => 'z',
	asset: () => MESH, geometry: () => ({ kind: 'box', size: [1, 1, 1] }),
	mass: () => 2, friction: () => 0.5, torque: () => 100, speed: () => 3, robotFile: () => robotFile,
};
let robotFile;   // an uploaded robot's file (robot_files.js), once connected

function lineage(name) {
	const names = [];
	for (let type = name; type; type = api.types[type].extends) names.push(type);
	return names;
}

function methodsOf(name) {
	const found = {};
	for (const type of lineage(name)) for (const [m, spec] of Object.entries(api.types[type].methods)) found[m] ??= spec;
	return found;
}

function make(name) {
	const args = api.types[name].params.map((p) => ('default' in p ? undefined : ARGUMENTS[p.kind]()));
	return new Prosthetic[name](...args);
}

const CHECK = {
	none: (result) => result === undefined,
	self: (result, object) => result === object,
	ref: (result) => typeof result?.vp?.id === 'string',   // one of this page's objects
};

test('every changing method returns what the table says, on every type', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-returns-${process.pid}` });
	try {
		robotFile = await uploadedRobot(URL_.replace(/^ws/, 'http'));
		const checked = [];
		for (const [name, type] of Object.entries(api.types)) {
			if (!type.creatable) continue;
			for (const [method, spec] of Object.entries(methodsOf(name))) {
				if (!spec.mutates || SENT_BY_THE_CLIENT.has(method)) continue;
				const object = make(name);
				const args = spec.params.map((p) => ARGUMENTS[p.kind]());
				assert.equal(typeof object[method], 'function', `${name}.${method}`);
				const result = object[method](...args);
				assert.ok(CHECK[spec.returns](result, object), `${name}.${method} returns ${spec.returns}, not ${result}`);
				checked.push(`${name}.${method}`);
			}
		}
		await Prosthetic.sync();   // and the server took every one of those calls
		assert.ok(checked.includes('EdgedHand.setRotation') && checked.includes('Motor.flip'), checked.join(' '));
	} finally {
		Prosthetic.close();
	}
});

test('1.0 hand pages chain setPosition and setRotation, and setPosition() takes a robot out', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const scene = `js-chain-${process.pid}`;
	await Prosthetic.connect({ url: URL_, scene });
	try {
		const A = new Prosthetic.EdgedHand(true).setPosition(-2, 0.5, 0).setRotation(-1, -1, 0);
		const B = new Prosthetic.RoundHand(false).setPosition(2, 0.5, 0).setRotation(1, 1, 0);
		assert.ok(A instanceof Prosthetic.EdgedHand && B instanceof Prosthetic.RoundHand);
		await Prosthetic.sync();
		assert.deepEqual(await A.getPositionExact(), [-2, 0.5, 0]);
		assert.equal(A.setPosition(), A);
		await Prosthetic.sync();
		assert.equal(A.visible, false);
		assert.equal(A.vp.session.mirror.nodes.get(A.vp.id).visible, false);
		A.setPosition(-1, 0, 0);
		await Prosthetic.sync();
		assert.equal(A.vp.session.mirror.nodes.get(A.vp.id).visible, true);
		assert.deepEqual(await A.getPositionExact(), [-1, 0, 0]);
	} finally {
		Prosthetic.close();
	}
});

test('coordinates left out keep their values, with one warning per place in the page', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-lenient-${process.pid}` });
	const warnings = [];
	const warn = console.warn;
	console.warn = (text) => warnings.push(text);
	try {
		const robots = [];
		for (let k = 0; k < 3; k++) {   // one place in the code, three calls: one warning
			const C2 = new Prosthetic.Robot();
			C2.attachChain(new Prosthetic.MotorZ());
			C2.setPosition(1, 2, 3);
			C2.setRotation(0.5, 0.25, 0.125);
			C2.setRotation(0, Math.PI);
			C2.setPosition(-0.3);
			robots.push(C2);
		}
		await Prosthetic.sync();   // no error: the server got complete calls
		for (const robot of robots) {
			assert.deepEqual(await robot.getPositionExact(), [-0.3, 2, 3]);
			const node = robot.vp.session.mirror.nodes.get(robot.vp.id);
			const expected = new Prosthetic.Quaternion().setFromEuler(new Prosthetic.Euler(0, Math.PI, 0.125));
			assert.ok(new Prosthetic.Quaternion(...node.quaternion).angleTo(expected) < 1e-6, 'z kept');
		}
		const D = new Prosthetic.Robot();   // a value given but wrong is still refused
		D.setPosition('left', 0, 0);
		await assert.rejects(Prosthetic.sync(), /setPosition of c\d+\.\d+, argument 0/);
		D.setPosition(1, 1, 1);             // and nothing else is
		await Prosthetic.sync();
		assert.deepEqual(D.getPosition(), [1, 1, 1]);
		assert.equal(warnings.length, 2, warnings.join('\n'));
		assert.match(warnings[0], /setRotation left out z: kept as 0\.125 .*returns\.test\.js/);
		assert.match(warnings[1], /setPosition left out y, z: kept as 2, 3 /);
	} finally {
		console.warn = warn;
		Prosthetic.close();
	}
});
