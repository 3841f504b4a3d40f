// Recording from a script: it records its own trial, keeps the file, and a second
// recording of the same scene is refused with the server's code.

import assert from 'node:assert/strict';
import { mkdtemp, readFile, rm } from 'node:fs/promises';
import { tmpdir } from 'node:os';
import { join } from 'node:path';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;

test('a script records its trial and saves the MCAP file', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const folder = await mkdtemp(join(tmpdir(), 'vp-recordings-'));
	await Prosthetic.connect({ url: URL_, scene: `js-recordings-${process.pid}` });
	try {
		const hand = new Prosthetic.EdgedHand(true);
		const rec = await Prosthetic.startRecording();   // the scene call: no token, no REST
		await assert.rejects(Prosthetic.startRecording(), (error) => error.code === 'recording_busy' && error.serverMessage.includes(rec.id));
		for (let k = 0; k < 20; k++) {
			hand.flexFingers(k / 20);
			await Prosthetic.sync();
		}
		const summary = await rec.stop();
		assert.equal(summary.stopped, 'stopped');
		assert.ok(summary.requests >= 20 && summary.ticks > 0, JSON.stringify(summary));
		const path = await rec.save(join(folder, 'trial.mcap'));
		const data = await readFile(path);
		assert.deepEqual([...data.subarray(0, 8)], [0x89, 0x4d, 0x43, 0x41, 0x50, 0x30, 0x0d, 0x0a], 'MCAP magic');
		assert.equal(data.length, summary.bytes);
	} finally {
		Prosthetic.close();
		await rm(folder, { recursive: true });
	}
});
