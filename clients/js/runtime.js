// The manual's scene functions and the connection they run on: connect, setAnimation,
// getTime, getScene, setCameraPosition, setCameraTarget.

import * as THREE from 'three';
import { addExactReads } from './exact.js';
import { ConnectionLost } from './errors.js';
import * as objects from './objects.js';
import * as robots from './robot.js';
import { Sensor } from './sensor.js';
import { currentSession, setCurrentSession } from './session.js';
import { meshFilesFor } from './mesh_files.js';
import { PageMeshes } from './meshes.js';
import { openSession } from './transport.js';
import { waitSeconds } from './waiting.js';

export const VERSION = '0.1.0';   // this client's (package.json; a test keeps them equal)
export const IN_BROWSER = typeof window !== 'undefined' && typeof document !== 'undefined';
const STARTED = performance.now();
export const SCENE_ID = 'scene';   // the id scene calls are made on

export const CLASSES = Object.freeze({
	Slot: objects.Slot, Part: objects.Part, Motor: objects.Motor, Slider: objects.Slider, MotorX: objects.MotorX,
	MotorY: objects.MotorY, MotorZ: objects.MotorZ, Ball: objects.Ball, Box: objects.Box,
	EdgedFinger: objects.EdgedFinger, EdgedTip: objects.EdgedTip, EdgedPalm: objects.EdgedPalm,
	GLTFPart: objects.GLTFPart, RoundFinger: objects.RoundFinger, RoundPalm: objects.RoundPalm,
	AnthroPalm: objects.AnthroPalm, AnthroThumb: objects.AnthroThumb, Sensor,
	Robot: robots.Robot, EdgedHand: robots.EdgedHand, RoundHand: robots.RoundHand,
	AnthroHand: robots.AnthroHand, SceneMesh: objects.SceneMesh, ImportedRobot: robots.ImportedRobot,
});
addExactReads(...Object.values(CLASSES));

let scene = new THREE.Scene();   // the viewer's, once one is mounted (browser)
let animation = null;            // {stop}
let holding = null;              // this script paused the scene: {at, scene} times then
let skew = 0;                    // s: getTime() past the wall clock, from steps while paused
let keeper = null;               // flushes directly written transforms without an animation

// The WebSocket address of a scene: `url` is the server (ws://host:port) or already /ws.
export function sceneUrl(url, { scene: name = 'default', role = 'controller', token = null, keep = false } = {}) {
	const base = url.replace(/\/+$/, '');
	const query = new URLSearchParams({ scene: name, role });
	if (token) query.set('token', token);
	if (keep) query.set('keep', 'true');
	return `${/\/ws$/.test(base) ? base : `${base}/ws`}?${query}`;
}

// Connect to a scene of a server and make it the one new objects go to.
// Node: connect({url, scene, role, token, keep, timeout}) or the VP_URL, VP_TOKEN and
// VP_TIMEOUT environment variables; keep: what this script makes stays in the scene after
// it ends; timeout: seconds to wait for the scene and for each answer (default 60).
export async function connect({ url, scene: name = 'default', role = 'controller', token, keep = false, onMessage, timeout } = {}) {
	const server = url ?? globalThis.process?.env?.VP_URL ?? 'ws://127.0.0.1:8000';
	const key = token ?? globalThis.process?.env?.VP_TOKEN ?? null;
	const session = await openSession(sceneUrl(server, { scene: name, role, token: key, keep }), CLASSES,
		{ onMessage, timeout: waitSeconds(timeout) });
	session.meshes = new PageMeshes(session, () => [scene, session.root]);
	session.http = server.replace(/^ws/, 'http');   // its REST side (recordings, mesh files)
	session.token = key;
	session.meshFiles = meshFilesFor(session.http, key);
	setCurrentSession(session);
	keepSyncing(session);
	if (!IN_BROWSER) {
		closeOnSignals();
		// a script in a terminal says where it runs and where to watch it (a page shows it)
		console.log(`Virtual Prosthetics: scene ${name} on ${server}; watch at ${watchUrl(session.http, name)}`);
	}
	return session;
}

// Where a browser watches a scene of the server at `http` (http://host:port).
export function watchUrl(http, scene) {
	return new URL(`/view?scene=${encodeURIComponent(scene)}`, http).href;
}

// Ctrl-C (or a TERM) closes the connection properly and ends the process with 0.
function closeOnSignals() {
	for (const signal of ['SIGINT', 'SIGTERM']) {
		if (process.listenerCount(signal) > 0) continue;   // the script handles it itself
		process.once(signal, () => {
			close();
			setTimeout(() => process.exit(0), 1000).unref();
		});
	}
}

// Stop the animation and close the connection (the server removes what this client made).
export function close() {
	animation?.stop();
	animation = null;
	holding = null;
	clearInterval(keeper);
	keeper = null;
	let session;
	try {
		session = currentSession();
	} catch {
		return;
	}
	session.flush();
	session.closing = true;   // not a loss: the transport does not connect again
	session.socket.close(1000, 'closed by the client');
	setCurrentSession(null);
}

// Resolves once the server has answered every request sent so far.
export function sync() {
	return currentSession().sync();
}

function keepSyncing(session) {
	if (IN_BROWSER) {
		const frame = () => { if (!session.closed) { session.flush(); requestAnimationFrame(frame); } };
		requestAnimationFrame(frame);
	} else {
		keeper = setInterval(() => { if (!session.closed) session.flush(); }, 1000 / 60);
		keeper.unref?.();
	}
}

// Manual setAnimation(func, fps=30): func(time, dTime) fps times a second, seconds since
// the import. Everything it sets leaves as one batch per step (applied as one, answered
// once; a refused call undoes the step's others and the next call throws it). In a scene this script
// paused (pause()), each step is followed by the ticks of one period (step()), and the
// next waits for them: the animation comes out the same on every run, as fast as the
// server computes it in Node, never ahead of the wall clock in a page. Not in 1.0:
// setAnimation(null) stops it.
export function setAnimation(func, fps = 30) {
	animation?.stop();
	animation = null;
	if (func === null) return;
	const period = 1000 / fps;
	let last = getTime();
	const animate = () => {
		const time = getTime();
		gathered(() => func(time, time - last));
		last = time;
		try {
			currentSession().flush();
		} catch (error) {
			if (!(error instanceof ConnectionLost)) throw error;
		}
	};
	const free = IN_BROWSER ? browserLoop(animate, period) : intervalLoop(animate, period);
	const held = heldLoop(animate, period, free);
	animation = { stop: () => { free.stop(); held.stop(); } };
}

// A step run so that what it sends leaves as one batch (as it is, not connected).
function gathered(step) {
	let session;
	try {
		session = currentSession();
	} catch (error) {
		if (!(error instanceof ConnectionLost)) throw error;
		return step();
	}
	return session.gathering(step);
}

// Each step timed from when it is due: Node truncates a timer's delay to whole milliseconds,
// and setInterval(step, 1000 / 60) ran 62.5 steps a second (the server's CPU with them). A
// late step is not made up for with a burst, as in a page.
function intervalLoop(step, period) {
	let running = true, due = performance.now() + period, timer;
	const next = () => {
		if (!holding) step();
		if (!running) return;   // (stopped by the step itself: setAnimation(null))
		due = Math.max(due + period, performance.now() + period / 2);
		timer = setTimeout(next, Math.max(0, due - performance.now()));
	};
	timer = setTimeout(next, period);
	return { stop: () => { running = false; clearTimeout(timer); } };
}

function browserLoop(step, period) {
	let running = true, due = performance.now();
	const frame = (now) => {
		if (!running) return;
		if (!holding && now >= due - 1) {
			step();
			due = Math.max(due + period, now + period / 2);
		}
		requestAnimationFrame(frame);
	};
	requestAnimationFrame(frame);
	return { stop: () => { running = false; } };
}

// While this script holds the clock: a step, then its period's ticks, then the next.
function heldLoop(animate, period, free) {
	let running = true;
	(async () => {
		while (running) {
			if (!holding) { await new Promise((wake) => setTimeout(wake, period)); continue; }
			const wall = performance.now();
			animate();
			const ticks = Math.max(1, Math.round(period / 1000 * currentSession().hello.tickRate));
			let wait = 0;
			try {
				await step(ticks);
			} catch (error) {
				if (error.code === 'not_paused') release();   // the pause is gone (a server restart)
				else if (error instanceof ConnectionLost) wait = period;   // until it is back
				else { running = false; free.stop(); throw error; }
			}
			if (IN_BROWSER) wait = Math.max(wait, wall + period - performance.now());
			if (wait > 0) await new Promise((wake) => setTimeout(wake, wait));
		}
	})();
	return { stop: () => { running = false; } };
}

// Manual getTime(): seconds since the library was imported. While this script holds the
// scene's clock, time moves only with its steps (the scene's ticks).
export function getTime() {
	if (holding) return holding.at + currentSession().mirror.time - holding.scene;
	return (performance.now() - STARTED) / 1000 + skew;
}

// Manual getScene(): the THREE.Scene that is drawn (in Node, one kept here).
export function getScene() {
	return scene;
}

export function useScene(drawn) {
	scene = drawn;
}

export function setCameraPosition(...position) {
	currentSession().call(SCENE_ID, 'setCameraPosition', position);
}

export function setCameraTarget(...target) {
	currentSession().call(SCENE_ID, 'setCameraTarget', target);
}

// Not in 1.0: words every viewer shows in a corner (a task's name, trial, time and score;
// at most 200 characters, lines split at \n); '' hides them.
export function setCaption(text) {
	currentSession().call(SCENE_ID, 'setCaption', [text]);
}

// Not in 1.0: setPhysics('dynamic', {unit, gravity, substeps, solverIterations,
// solverTolerance, friction, density, warmStart}) (options left out take their defaults; unit: metres
// per scene unit, masses, forces and torques are SI) or setPhysics('kinematic').
export function setPhysics(mode, options) {
	currentSession().call(SCENE_ID, 'setPhysics', options === undefined ? [mode] : [mode, options]);
}

// Not in 1.0: the scene's clock held by this script. pause() stops it (nothing moves,
// whatever the server's load, until resume() or until this client leaves); await
// step(ticks = 1) advances it by whole ticks (1 to 60) after what was sent before and
// resolves once they are taken and their frames are in the mirror.
export async function pause() {
	currentSession().call(SCENE_ID, 'pause', []);
	await currentSession().sync();
	holding = { at: getTime(), scene: currentSession().mirror.time };
}

export async function resume() {
	currentSession().call(SCENE_ID, 'resume', []);
	await currentSession().sync();
	release();
}

function release() {
	const at = getTime();
	holding = null;
	skew += at - getTime();   // time goes on from where the steps took it
}

export async function step(ticks = 1) {
	currentSession().call(SCENE_ID, 'step', [ticks]);
	await currentSession().sync();
	return currentSession().mirror.time;
}

// Not in 1.0: the scene's state kept by the server and put back. await saveState() gives
// its id; await restoreState(id) puts the scene back as it was then, every body at rest in
// a fresh physics world (the same steps after it give the same world), and resolves once
// the mirror holds it (only the scene's keeper, only while every object in it is this
// client's); forgetState(id) frees it.
export async function saveState() {
	return currentSession().call(SCENE_ID, 'saveState', [], { wait: true });
}

export async function restoreState(state) {
	await currentSession().call(SCENE_ID, 'restoreState', [state], { wait: true });
	await currentSession().sync();
}

export function forgetState(state) {
	currentSession().call(SCENE_ID, 'forgetState', [state]);
}

// The scene's physics as the mirror has it: {mode, gravity, substeps, …}.
export function getPhysics() {
	return { ...currentSession().mirror.physics };
}
