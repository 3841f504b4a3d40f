// A Node script whose connection drops comes back as the same client with its robots,
// nothing made twice (the network cut by a real TCP proxy between it and the server).

import assert from 'node:assert/strict';
import net from 'node:net';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;

// Forwards TCP to the server; cut() drops every connection and keeps listening.
function cuttableProxy(target) {
	const open = [];
	let accepted = 0;
	const server = net.createServer((client) => {
		accepted += 1;
		const upstream = net.connect(target.port, target.hostname);
		open.push(client, upstream);
		client.pipe(upstream);
		upstream.pipe(client);
		for (const end of [client, upstream]) end.on('error', () => {});
		client.on('close', () => upstream.destroy());
		upstream.on('close', () => client.destroy());
	});
	return new Promise((resolve) => server.listen(0, '127.0.0.1', () => resolve({
		url: `ws://127.0.0.1:${server.address().port}`,
		get accepted() { return accepted; },
		cut() { for (const end of open.splice(0)) end.destroy(); },
		close() { this.cut(); server.close(); },
	})));
}

async function until(predicate, ms = 5000) {
	const deadline = Date.now() + ms;
	while (!predicate()) {
		assert.ok(Date.now() < deadline, 'never happened');
		await new Promise((resolve) => setTimeout(resolve, 10));
	}
}

test('a dropped script comes back with its robots and makes nothing twice', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const target = new URL(URL_);
	const proxy = await cuttableProxy(target);
	const scene = `js-reconnect-${process.pid}`;
	const session = await Prosthetic.connect({ url: proxy.url, scene });
	try {
		const me = session.clientId;
		const hand = new Prosthetic.EdgedHand(true);
		hand.flexFingers(0.3);
		await Prosthetic.sync();
		proxy.cut();
		await until(() => proxy.accepted === 2);
		hand.setAngle(1, -0.5);   // sent once the client is itself again
		await Prosthetic.sync();
		assert.equal(session.clientId, me);
		const rest = `http://${target.host}/api/scenes/${scene}/robots`;
		const robots = await (await fetch(rest)).json();
		assert.deepEqual(robots.map((r) => r.id), [hand.vp.id]);
		const motors = (await (await fetch(`${rest}/${hand.vp.id}`)).json()).motors;
		assert.equal(motors[1].angle, -0.5);
		assert.equal(hand.getAngle(1), -0.5);
		assert.equal(hand.getMotors().length, 20);   // the same objects, resynced
	} finally {
		Prosthetic.close();
		proxy.close();
	}
});

test('a script whose client connected again elsewhere (resume) stays closed, does not fight back', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const scene = `js-replaced-${process.pid}`;
	const session = await Prosthetic.connect({ url: URL_, scene });
	const { default: WebSocket } = await import('ws');
	const thief = new WebSocket(`${URL_}/ws?scene=${scene}&resume=${session.hello.resume}`);
	try {
		const reason = await session.ended;
		assert.match(reason, /replaced/);
		await new Promise((resolve) => setTimeout(resolve, 500));   // no reconnection meanwhile
		assert.equal(thief.readyState, WebSocket.OPEN);
	} finally {
		thief.close();
		Prosthetic.close();
	}
});
