// The shared protocol vectors replayed from Node against a real server (VP_URL): each
// step's text is sent as it is, and the answers must match the vector's pattern.

import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import test from 'node:test';
import WebSocket from 'ws';

const DIR = new URL('../../../protocol/vectors/', import.meta.url);
const URL_ = process.env.VP_URL;
const files = readdirSync(DIR).filter((name) => name.endsWith('.json')).sort();

function substitute(value, client) {
	if (typeof value === 'string') return value.replaceAll('{client}', client);
	if (Array.isArray(value)) return value.map((v) => substitute(v, client));
	if (value && typeof value === 'object') {
		return Object.fromEntries(Object.entries(value).map(([k, v]) => [substitute(k, client), substitute(v, client)]));
	}
	return value;
}

// Where `actual` breaks the pattern `expected` (objects: a subset of keys; "$any").
function mismatch(expected, actual, where = 'answer') {
	if (expected === '$any') return null;
	if (Array.isArray(expected)) {
		if (!Array.isArray(actual) || actual.length !== expected.length) return `${where}: expected ${expected.length} items, got ${JSON.stringify(actual)}`;
		for (let i = 0; i < expected.length; i++) {
			const problem = mismatch(expected[i], actual[i], `${where}[${i}]`);
			if (problem) return problem;
		}
		return null;
	}
	if (expected && typeof expected === 'object') {
		if (!actual || typeof actual !== 'object') return `${where}: expected an object, got ${JSON.stringify(actual)}`;
		for (const [key, value] of Object.entries(expected)) {
			if (!(key in actual)) return `${where}: missing ${key} in ${JSON.stringify(actual)}`;
			const problem = mismatch(value, actual[key], `${where}.${key}`);
			if (problem) return problem;
		}
		return null;
	}
	if (typeof expected === 'number' && typeof actual === 'number') {
		return Math.abs(expected - actual) <= Math.max(1e-12, 1e-9 * Math.abs(expected)) ? null : `${where}: expected ${expected}, got ${actual}`;
	}
	return expected === actual ? null : `${where}: expected ${JSON.stringify(expected)}, got ${JSON.stringify(actual)}`;
}

// A socket whose answers (ok and error) are handed out in order, frames left aside.
async function open(scene) {
	const socket = new WebSocket(`${URL_}/ws?scene=${scene}&role=controller`);
	const answers = [], waiting = [];
	let hello;
	socket.on('message', (data) => {
		const message = JSON.parse(String(data));
		if (message.op === 'hello') hello = message;
		if (message.op !== 'ok' && message.op !== 'error') return;
		if (waiting.length) waiting.shift()(message); else answers.push(message);
	});
	await new Promise((resolve, reject) => { socket.once('open', resolve); socket.once('error', reject); });
	const next = () => (answers.length ? Promise.resolve(answers.shift()) : new Promise((resolve) => waiting.push(resolve)));
	while (!hello) await new Promise((resolve) => setTimeout(resolve, 5));
	return { socket, client: hello.client, next };
}

for (const file of files) {
	test(`vectors ${file} from Node`, { skip: !URL_ && 'needs VP_URL' }, async () => {
		const { socket, client, next } = await open(`js-vectors-${file.replace('.json', '')}-${process.pid}`);
		try {
			const { steps } = JSON.parse(readFileSync(new URL(file, DIR)));
			for (const [number, step] of steps.entries()) {
				const text = (step.sendText ?? JSON.stringify(step.send)).replaceAll('{client}', client);
				const pingId = 10000 + number;
				socket.send(text);
				socket.send(JSON.stringify({ op: 'ping', id: pingId }));
				const answers = [];
				for (let answer = await next(); !(answer.op === 'ok' && answer.id === pingId); answer = await next()) answers.push(answer);
				const problem = mismatch(substitute(step.expect, client), answers);
				assert.equal(problem, null, `step ${number}: ${problem}`);
			}
		} finally {
			socket.close();
		}
	});
}
