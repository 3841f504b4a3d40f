// The shared protocol vectors replayed from Node against a real server (VP_URL): each
// step's text is sent as it is, and the answers must match the vector's pattern. What the
// client predicts of each step (prediction.js: new nodes, attachments, motor order,
// clamped angles) must be what the server's answers say.

import assert from 'node:assert/strict';
import { readFileSync, readdirSync } from 'node:fs';
import test from 'node:test';
import WebSocket from 'ws';
import { Mirror } from '../mirror.js';
import { Prediction } from '../prediction.js';
import { CLASSES } from '../runtime.js';

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
	return { socket, client: hello.client, slots: hello.slots, next };
}

// The requests of a step's text (those inside a batch too), each with the id it is
// answered under.
function requests(text) {
	let sent;
	try {
		sent = JSON.parse(text);
	} catch {
		return [];
	}
	const out = [];
	for (const message of [sent].flat()) {
		if (message?.op === 'batch') out.push(...(message.ops ?? []).map((op) => ({ ...op, id: message.id })));
		else if (message?.id != null) out.push(message);
	}
	return out;
}

// A mirror as `truth` is now, with what the client would predict of `messages` held in it.
function predicted(truth, slots, messages) {
	const guess = new Mirror();
	for (const [id, node] of truth.nodes) guess.nodes.set(id, structuredClone(node));
	const prediction = new Prediction(guess, { slots, classes: CLASSES });
	for (const message of messages) prediction.request(message, message.id);
	return guess;
}

// Every field the guess predicted, against the server's.
function comparePredictions(guess, truth, number) {
	for (const [id, hold] of guess.held) {
		for (const field of hold.fields) {
			assert.deepEqual(guess.nodes.get(id)?.[field], truth.nodes.get(id)?.[field], `step ${number}: ${id}.${field} predicted`);
		}
	}
}

for (const file of files) {
	test(`vectors ${file} from Node`, { skip: !URL_ && 'needs VP_URL' }, async () => {
		const { socket, client, slots, next } = await open(`js-vectors-${file.replace('.json', '')}-${process.pid}`);
		const truth = new Mirror();   // what the server's answers say
		try {
			const { steps } = JSON.parse(readFileSync(new URL(file, DIR)));
			for (const [number, step] of steps.entries()) {
				const text = (step.sendText ?? JSON.stringify(step.send)).replaceAll('{client}', client);
				const guess = predicted(truth, slots, requests(text));
				const pingId = 10000 + number;
				socket.send(text);
				socket.send(JSON.stringify({ op: 'ping', id: pingId }));
				const answers = [];
				for (let answer = await next(); !(answer.op === 'ok' && answer.id === pingId); answer = await next()) answers.push(answer);
				const problem = mismatch(substitute(step.expect, client), answers);
				assert.equal(problem, null, `step ${number}: ${problem}`);
				for (const answer of answers) if (answer.changes) truth.applyChanges(answer.changes);
				if (answers.every((answer) => answer.op === 'ok')) comparePredictions(guess, truth, number);
			}
		} finally {
			socket.close();
		}
	});
}
