// Parts' callbacks: contacts, as the manual's `class MyPart extends Part` example overrides
// them (each runs once per contact change, in order, with the other part's object), and
// a mesh part's callback once it is made.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;

class Recorder extends Prosthetic.Box {
	log = [];

	beginContact(otherPart) {
		this.log.push(['begin', otherPart]);
	}

	endContact(otherPart) {
		this.log.push(['end', otherPart]);
	}
}

// Let the animation run for `seconds` (callbacks run between its steps).
function run(seconds) {
	return new Promise((resolve) => setTimeout(resolve, seconds * 1000));
}

async function until(test, seconds = 5) {
	const end = Date.now() + seconds * 1000;
	while (!test() && Date.now() < end) await run(0.02);
	return test();
}

test('beginContact and endContact run once per contact change, in order', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-contacts-${process.pid}` });
	try {
		const finger = new Prosthetic.EdgedFinger();
		finger.setPosition(0, 1, 0);
		const box = new Recorder(1, 0.1, 0.1);           // at the origin, half in the ground
		const quiet = new Prosthetic.Box(0.2, 0.2, 0.2); // a part that does not listen
		quiet.setPosition(5, 0, 0);                      // on the ground, alone
		Prosthetic.setAnimation(() => {});
		assert.ok(await until(() => box.log.length === 1), JSON.stringify(box.log));
		assert.deepEqual(box.log, [['begin', 'ground']]);
		box.setPosition(0, 1.5, 0);                      // across the finger, off the ground
		assert.ok(await until(() => box.log.length === 3));
		assert.deepEqual(box.log.slice(1), [['begin', finger], ['end', 'ground']]);
		box.position.y = 3;                              // a three.js write ends it too
		assert.ok(await until(() => box.log.length === 4));
		assert.deepEqual(box.log[3], ['end', finger]);
		await run(0.3);
		assert.equal(box.log.length, 4, 'nothing more changed');
		assert.equal(finger.hearsContacts, false);
		assert.equal(quiet.hearsContacts, false);
	} finally {
		Prosthetic.close();
	}
});

test('a mesh part\'s callback runs once it is made, and not for a file the server refuses', { skip: !URL_ && 'needs VP_URL' }, async () => {
	await Prosthetic.connect({ url: URL_, scene: `js-mesh-callback-${process.pid}` });
	try {
		const made = [];
		const bad = new Prosthetic.GLTFPart('models/mine.glb', 1, (part) => made.push(part));
		const good = new Prosthetic.RoundFinger('round-finger-8.glb', 0.8, (part) => made.push(part));
		assert.ok(await until(() => made.length === 1));
		assert.deepEqual(made, [good]);
		await run(0.2);
		assert.deepEqual(made, [good]);
		// the refusal is the page's next call's error, not an unhandled rejection
		await assert.rejects(Prosthetic.sync(), (error) => error.code === 'forbidden' && /models\/mine.glb/.test(error.message));
		assert.equal(bad.parent, null);
	} finally {
		Prosthetic.close();
	}
});
