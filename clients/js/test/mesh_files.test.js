// A script's own mesh files, as 1.0 pages named files next to them: uploaded by the client
// and used under the server's name; requests made after such a part wait for it, so the
// server takes them in order. Names the script's side does not have go as they are.

import assert from 'node:assert/strict';
import { copyFile, mkdtemp, rm, writeFile } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import test from 'node:test';
import { MeshFiles } from '../mesh_files.js';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;
const BUNDLED = new URL('../../../assets/gltf/round-finger-8.glb', import.meta.url);

test('a script\'s own mesh file is uploaded and its part is made from it, in order with the rest', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const folder = await mkdtemp(join(tmpdir(), 'vp-meshes-'));
	const start = process.cwd();
	await copyFile(BUNDLED, join(folder, 'gripper.glb'));
	process.chdir(folder);
	const session = await Prosthetic.connect({ url: URL_, scene: `js-mesh-files-${process.pid}` });
	try {
		const robot = new Prosthetic.Robot();
		const made = [];
		const own = new Prosthetic.RoundFinger('gripper.glb', 0.8, (part) => made.push(part));
		const bundled = new Prosthetic.RoundFinger('round-finger-8.glb', 0.8);
		robot.attachChain(new Prosthetic.MotorZ(-1, 1), own, new Prosthetic.MotorZ(-1, 1), bundled);
		robot.setAngles(0.5, -0.5);
		assert.equal(robot.getMotors().length, 2, 'read at once, before the upload is done');
		await Prosthetic.sync();
		assert.deepEqual(made, [own]);
		const [ownUrl, bundledUrl] = [own, bundled].map((part) => session.mirror.nodes.get(part.vp.id).geometry.url);
		assert.match(ownUrl, /^\/api\/assets\/[0-9a-f]+\.glb$/, 'made from the uploaded copy');
		assert.equal(bundledUrl, '/assets/gltf/round-finger-8.glb');
		assert.deepEqual(await robot.getAnglesExact(), [0.5, -0.5], 'the requests after it were applied after it');
		assert.equal(own.parent.parent, robot.getMotors()[0], 'attached where the chain put it');
	} finally {
		Prosthetic.close();
		process.chdir(start);
		await rm(folder, { recursive: true });
	}
});

test('a file the server refuses is named in a warning and the server\'s own error', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const folder = await mkdtemp(join(tmpdir(), 'vp-meshes-'));
	const start = process.cwd();
	await writeFile(join(folder, 'broken.glb'), 'not a mesh');
	process.chdir(folder);
	const warned = [];
	const warn = console.warn;
	console.warn = (text) => warned.push(text);
	await Prosthetic.connect({ url: URL_, scene: `js-mesh-files-bad-${process.pid}` });
	try {
		const part = new Prosthetic.GLTFPart('broken.glb', 1);
		await assert.rejects(Prosthetic.sync(), (error) => error.code === 'unknown_asset' && /broken\.glb/.test(error.message));
		assert.equal(part.parent, null);
		assert.equal(warned.length, 1);
		assert.match(warned[0], /broken\.glb could not be sent to the server \(bad_asset: /);
	} finally {
		console.warn = warn;
		Prosthetic.close();
		process.chdir(start);
		await rm(folder, { recursive: true });
	}
});

test('a file is read and uploaded once, however many parts are made from it', async () => {
	const reads = [], uploads = [];
	const files = new MeshFiles({
		read: async (name) => { reads.push(name); return name === 'mine.glb' ? new Uint8Array([1]) : null; },
		upload: async (bytes) => { uploads.push(bytes); return 'abc.glb'; },
	});
	const names = await Promise.all(['mine.glb', 'mine.glb', 'round-palm.glb'].map((name) => files.nameFor(name)));
	assert.deepEqual(names, ['abc.glb', 'abc.glb', 'round-palm.glb']);
	assert.deepEqual(reads, ['mine.glb', 'round-palm.glb']);
	assert.equal(uploads.length, 1);
});
