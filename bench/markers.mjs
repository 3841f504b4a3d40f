// How many markers a script can move every frame at 60 Hz: N small spheres added to
// getScene() (shared as SceneMeshes), all moved every step of setAnimation(loop, 60), for
// SECONDS each. Reports, per N: steps the client ran per second, server ticks per second
// and tick time (/api/metrics), and how far the scene's marker lags the script (its last
// placed step as the server holds it, sampled).
//
//   VP_URL=ws://127.0.0.1:8000 node bench/markers.mjs [100,250,500,1000] [seconds=6]

import * as Prosthetic from '../clients/js/virtual-prosthetics.js';

const counts = (process.argv[2] ?? '100,250,500,1000').split(',').map(Number);
const seconds = Number(process.argv[3] ?? 6);
const http = (process.env.VP_URL ?? 'ws://127.0.0.1:8000').replace(/^ws/, 'http');

async function metrics(scene) {
	const all = await (await fetch(`${http}/api/metrics`)).json();
	return all.scenes[scene];
}

async function run(count) {
	const scene = `markers-${count}-${process.pid}`;
	await Prosthetic.connect({ scene });
	const geometry = new Prosthetic.SphereGeometry(0.02, 8, 4);
	const markers = Array.from({ length: count }, () => new Prosthetic.Mesh(geometry));
	Prosthetic.getScene().add(...markers);
	await Prosthetic.sync();
	let steps = 0;
	Prosthetic.setAnimation((t) => {
		steps++;
		markers.forEach((m, k) => m.position.set(Math.cos(k + t), 0.5 + 0.1 * Math.sin(t), Math.sin(k + t)));
		markers[0].position.y = steps;   // the step number, to see how far the server lags
	}, 60);
	await new Promise((r) => setTimeout(r, 1000));
	const before = await metrics(scene), stepsBefore = steps, started = performance.now();
	const lags = [];
	while (performance.now() - started < seconds * 1000) {
		await new Promise((r) => setTimeout(r, 500));
		const held = (await (await fetch(`${http}/api/scenes/${scene}/snapshot`)).json()).nodes
			.find((n) => n.type === 'SceneMesh' && n.position[1] >= 1);
		if (held) lags.push(steps - held.position[1]);
	}
	const elapsed = (performance.now() - started) / 1000;
	const after = await metrics(scene);
	Prosthetic.setAnimation(() => {}, 1);
	Prosthetic.getScene().clear();
	Prosthetic.close();
	lags.sort((a, b) => a - b);
	return { markers: count, clientStepsPerS: +((steps - stepsBefore) / elapsed).toFixed(1),
		serverTicksPerS: +((after.ticks - before.ticks) / elapsed).toFixed(1),
		tickMsP50: after.tickMsP50, tickMsP95: after.tickMsP95, tickMsMax: after.tickMsMax,
		lagStepsMedian: lags[lags.length >> 1] ?? null, lagStepsMax: lags.at(-1) ?? null };
}

const results = [];
for (const count of counts) results.push(await run(count));
console.log(JSON.stringify(results, null, 1));
process.exit(0);
