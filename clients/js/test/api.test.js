// Every manual name is exported with the manual's arity, as protocol/api.json lists them.

import assert from 'node:assert/strict';
import { readFileSync } from 'node:fs';
import test from 'node:test';
import * as Prosthetic from '../virtual-prosthetics.js';
import { READS } from '../exact.js';

const api = JSON.parse(readFileSync(new URL('../../../protocol/api.json', import.meta.url)));
const pkg = JSON.parse(readFileSync(new URL('../package.json', import.meta.url)));
const SCENE_FUNCTIONS = ['setAnimation', 'getTime', 'getScene', 'setCameraPosition', 'setCameraTarget', 'setCaption',
	'setPhysics', 'getPhysics', 'pause', 'resume', 'step', 'startRecording', 'stopRecording', 'saveState', 'restoreState', 'forgetState'];
// not manual methods: how the client sends what a page writes to `quaternion`/`rotation`,
// `scale` and `visible` (pages write the three.js properties)
const NOT_IN_THE_MANUAL = new Set(['setQuaternion', 'setScale', 'setVisible']);
const SENT_BY_THE_CLIENT = new Set(['setTransforms']);   // what a page moved, once a step

// How many parameters the table lists (a variadic one is a rest parameter in JavaScript).
function arity(params) {
	return params.filter((p) => !p.variadic).length;
}

// How many named parameters a function or class constructor declares (defaults included,
// the rest parameter not): Function.length stops at the first default.
function declared(fn) {
	const source = fn.toString();
	const match = source.startsWith('class') ? source.match(/constructor\s*\(([^)]*)\)/) : source.match(/^[^(]*\(([^)]*)\)/);
	if (!match) return declared(Object.getPrototypeOf(fn));   // an inherited constructor
	return match[1].split(',').map((p) => p.trim()).filter((p) => p && !p.startsWith('...')).length;
}

function lineage(name) {
	const names = [];
	for (let type = name; type; type = api.types[type].extends) names.push(type);
	return names;
}

test('every creatable type is a class taking the manual\'s arguments', () => {
	for (const [name, type] of Object.entries(api.types)) {
		if (!type.creatable) continue;
		const Class = Prosthetic[name];
		assert.equal(typeof Class, 'function', name);
		assert.equal(Class.name, name);
		const expected = arity(type.params) + (lineage(name).includes('GLTFPart') ? 1 : 0);  // + callback
		assert.equal(declared(Class), expected, `${name}(${type.params.map((p) => p.name)}${expected > arity(type.params) ? ', callback' : ''})`);
		if (type.extends) assert.ok(Class.prototype instanceof Prosthetic[type.extends], `${name} extends ${type.extends}`);
	}
});

test('every method of the table exists with the manual\'s arity', () => {
	for (const [name, type] of Object.entries(api.types)) {
		if (!type.creatable) continue;
		for (const [method, spec] of Object.entries(type.methods)) {
			if (NOT_IN_THE_MANUAL.has(method)) continue;
			const fn = Prosthetic[name].prototype[method];
			assert.equal(typeof fn, 'function', `${name}.${method}`);
			assert.equal(declared(fn), arity(spec.params), `${name}.${method}(${spec.params.map((p) => p.name)})`);
		}
	}
});

test('the scene functions are exported with the manual\'s arity', () => {
	for (const name of SCENE_FUNCTIONS) assert.equal(typeof Prosthetic[name], 'function', name);
	assert.equal(declared(Prosthetic.setAnimation), 2);   // (func, fps=30)
	assert.equal(declared(Prosthetic.getTime), 0);
	assert.equal(declared(Prosthetic.getScene), 0);
	for (const method of Object.keys(api.types.Scene.methods)) {
		if (!SENT_BY_THE_CLIENT.has(method)) assert.ok(SCENE_FUNCTIONS.includes(method), method);
	}
});

test('every read has an exact form, and the table of reads is the server\'s', () => {
	const reads = {};
	for (const type of Object.values(api.types)) {
		for (const [method, spec] of Object.entries(type.methods)) if (!spec.mutates && spec.returns !== 'none' && method !== 'getTime') reads[method] = spec.returns;
	}
	assert.deepEqual(READS, reads);
	for (const [name, type] of Object.entries(api.types)) {
		if (!type.creatable) continue;
		for (const method of Object.keys(type.methods)) {
			if (method in READS) assert.equal(typeof Prosthetic[name].prototype[`${method}Exact`], 'function', `${name}.${method}Exact`);
		}
	}
});

test('three.js and lil-gui are re-exported as in 1.0', () => {
	for (const name of ['Mesh', 'BoxGeometry', 'MeshLambertMaterial', 'MathUtils', 'Vector3', 'Object3D', 'GUI']) {
		assert.equal(typeof Prosthetic[name] === 'function' || typeof Prosthetic[name] === 'object', true, name);
	}
	assert.ok(new Prosthetic.Vector3(1, 2, 3).length() > 3);
});

test('the client version is the package\'s', () => {
	assert.equal(Prosthetic.VERSION, pkg.version);
});
