// Meshes a page adds to getScene() become SceneMeshes of the server's scene (real server,
// VP_URL): sensed, moved with the page, recoloured, hidden, scaled and removed with it.

import assert from 'node:assert/strict';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';

const URL_ = process.env.VP_URL;
const near = (a, b, eps = 1e-6) => Math.abs(a - b) < eps;

function serverNode(session, object) {
	const id = [...session.meshes.records.entries()].find(([mesh]) => mesh === object)?.[1].id;
	return { id, node: session.mirror.nodes.get(id) };
}

test('a page\'s meshes are shared, sensed and follow the page', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-meshes-${process.pid}` });
	try {
		const scene = Prosthetic.getScene();
		const box = new Prosthetic.Mesh(new Prosthetic.BoxGeometry(2, 0.5, 2), new Prosthetic.MeshLambertMaterial({ color: 'crimson' }));
		box.position.set(0, 1, 0);
		scene.add(box);
		scene.add(new Prosthetic.AmbientLight('white'));      // lights stay the page's
		const sensor = new Prosthetic.Sensor();
		sensor.setPosition(0, 3, 0);
		sensor.setRotation(Math.PI, 0, 0);
		await Prosthetic.sync();
		const { id, node } = serverNode(session, box);
		assert.equal(node.type, 'SceneMesh');
		assert.deepEqual(node.geometry, { kind: 'box', size: [2, 0.5, 2] });
		assert.equal(node.color, 0xdc143c);
		assert.equal([...session.mirror.nodes.values()].filter((n) => n.type === 'SceneMesh').length, 1);
		assert.ok(near(await sensor.senseDistanceExact(), 1.75), 'the box\'s top is at 1.25');

		box.position.y = 0.5;                                 // moved, scaled, recoloured, hidden
		box.scale.set(1, 2, 1);
		box.material.color.set('navy');
		box.visible = false;
		await Prosthetic.sync();
		const moved = session.mirror.nodes.get(id);
		assert.deepEqual(moved.position, [0, 0.5, 0]);
		assert.deepEqual(moved.scale, [1, 2, 1]);
		assert.equal(moved.color, 0x000080);
		assert.equal(moved.visible, false);
		assert.ok(near(await sensor.senseDistanceExact(), 2.0), 'top at 1.0, hidden but sensed as in 1.0');

		const group = new Prosthetic.Group();                 // a mesh inside a group: its world pose
		const knot = new Prosthetic.Mesh(new Prosthetic.TorusKnotGeometry(0.3, 0.1, 32, 6));
		group.add(knot);
		group.position.set(4, 1, 0);
		scene.add(group);
		await Prosthetic.sync();
		const shared = serverNode(session, knot).node;
		assert.equal(shared.geometry.kind, 'triangles');
		assert.deepEqual(shared.position, [4, 1, 0]);

		scene.remove(box);
		await Prosthetic.sync();
		assert.equal(session.mirror.nodes.has(id), false, 'removed from the page, removed from the scene');
		assert.ok(near(await sensor.senseDistanceExact(), 3.0), 'only the ground below now');
	} finally {
		Prosthetic.getScene().clear();
		Prosthetic.close();
	}
});

test('a hundred markers moved every step leave as one request', { skip: !URL_ && 'needs VP_URL' }, async () => {
	const session = await Prosthetic.connect({ url: URL_, scene: `js-markers-${process.pid}` });
	const sent = [];
	const transmit = session.transmit;
	session.transmit = (text) => { sent.push(text); transmit(text); };
	try {
		const geometry = new Prosthetic.SphereGeometry(0.02, 8, 4);
		const markers = Array.from({ length: 100 }, () => new Prosthetic.Mesh(geometry));
		Prosthetic.getScene().add(...markers);
		await Prosthetic.sync();
		sent.length = 0;
		markers.forEach((marker, k) => marker.position.set(k / 10, 1, 0));
		await Prosthetic.sync();
		const requests = sent.flatMap((text) => [].concat(JSON.parse(text)));
		assert.equal(requests.filter((r) => r.op === 'call').length, 1);
		assert.equal(Object.keys(requests[0].args[0]).length, 100);
		const placed = [...session.mirror.nodes.values()].filter((n) => n.type === 'SceneMesh');
		assert.deepEqual(placed.map((n) => n.position[0]).sort((a, b) => a - b), markers.map((_, k) => k / 10));
	} finally {
		Prosthetic.getScene().clear();
		Prosthetic.close();
	}
});
