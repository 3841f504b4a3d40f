// How finely the viewer draws, adapted to what pictures cost on this machine. Software
// WebGL (SwiftShader, llvmpipe) draws on the CPU, slowly: a wanted picture then waits
// long for the browser's next frame. Levels go from the full picture (soft shadows, the
// screen's pixel ratio, antialiasing on hardware, mesh files in full) down to a small,
// unshadowed one with simplified mesh files (meshes.js); the
// viewer steps down while wanted pictures wait longer than SLOW_MS (fewer than about 20
// pictures a second) and back up when they have come quickly for a while.

import * as THREE from 'three';

export const LEVELS = [
	{ name: 'full', pixelRatio: null, shadows: THREE.VSMShadowMap, map: 1024, reduced: false },
	{ name: 'high', pixelRatio: 1, shadows: THREE.PCFShadowMap, map: 1024, reduced: false },
	{ name: 'medium', pixelRatio: 1, shadows: THREE.PCFShadowMap, map: 512, reduced: true },
	{ name: 'low', pixelRatio: 0.75, shadows: THREE.BasicShadowMap, map: 512, reduced: true },
	{ name: 'lower', pixelRatio: 0.6, shadows: null, reduced: true },
	{ name: 'lowest', pixelRatio: 0.45, shadows: null, reduced: true },
	{ name: 'rough', pixelRatio: 0.3, shadows: null, reduced: true },
];
const SLOW_MS = 45;          // wanted pictures waiting longer than this (median): step down
const QUICK_MS = 22;         // waiting less than this for UP_AFTER ms: step up
const UP_AFTER = 5000;
const RETRY_AFTER = 10000;   // ms before a step down that did not help is tried again
const SAMPLES = 9;           // pictures judged together (the median)

// True when WebGL draws in software on this machine.
export function softwareWebGL() {
	const gl = document.createElement('canvas').getContext('webgl2');
	if (!gl) return true;
	const info = gl.getExtension('WEBGL_debug_renderer_info');
	const renderer = info ? gl.getParameter(info.UNMASKED_RENDERER_WEBGL) : '';
	gl.getExtension('WEBGL_lose_context')?.loseContext();
	return /swiftshader|llvmpipe|software/i.test(renderer);
}

export class Quality {
	// held: a level's name (?quality=): drawn at that level always, nothing adapts
	constructor(software, apply, held = null) {
		this.apply = apply;               // (level) → the renderer and light take it
		const heldIndex = LEVELS.findIndex((level) => level.name === held);
		this.held = heldIndex >= 0;
		this.index = this.held ? heldIndex : software ? 2 : 0;
		if (held !== null && !this.held) {
			console.warn(`quality=${held}: no such level (${LEVELS.map((l) => l.name).join(', ')}); the viewer adapts`);
		}
		this.waits = [];
		this.quickSince = null;
		this.floor = LEVELS.length - 1;   // the lowest level that still helped
		this.floorSince = 0;              // when it was found (pictures that share a GPU
		                                  // with other pages' vary: it is tried again)
		this.before = null;               // the wait that made the last step down
	}

	get level() { return LEVELS[this.index]; }

	// A picture wanted since `wanted` (ms) was drawn at `now`.
	drawn(wanted, now) {
		if (this.held) return;
		this.waits.push(now - wanted);
		if (this.waits.length < SAMPLES) return;
		const wait = [...this.waits].sort((a, b) => a - b)[SAMPLES >> 1];
		this.waits = [];
		if (this.before !== null && wait >= this.before) {
			// a coarser picture came no sooner: the time goes elsewhere (compositing, a
			// shared GPU process), so keep the finer one
			this.floor = this.index - 1;
			this.floorSince = now;
			this.before = null;
			this.step(-1);
			return;
		}
		this.before = null;
		if (now - this.floorSince > RETRY_AFTER) this.floor = LEVELS.length - 1;
		if (wait > SLOW_MS && this.index < this.floor) {
			this.before = wait;
			this.step(1);
		}
		else if (wait < QUICK_MS) {
			this.quickSince ??= now;
			if (now - this.quickSince > UP_AFTER && this.index > 0) this.step(-1);
		} else this.quickSince = null;
	}

	step(by) {
		this.index += by;
		this.quickSince = null;
		this.apply(this.level);
	}
}
