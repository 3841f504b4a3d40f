// How long the client waits for the server: the scene's first snapshot, each answer a
// script waits for (exact reads, sync). One figure for all, chosen by the user:
// connect({timeout: S}) in seconds, or VP_TIMEOUT=S in Node's environment; otherwise
// DEFAULT_SECONDS. A timeout guards against a server that will never answer; it is not a
// budget, so the default holds on a server whose cores are busy with a dozen scenes.
// (The Python client's waiting.py says the same; a test keeps the defaults equal.)

import { Timeout } from './errors.js';

export const DEFAULT_SECONDS = 60;
export const ENVIRONMENT = 'VP_TIMEOUT';

// The seconds to wait: `given`, else VP_TIMEOUT (Node), else the default. Infinity waits
// for ever; anything but a positive number throws a RangeError naming where it came from.
export function waitSeconds(given) {
	let source = 'timeout';
	if (given === undefined || given === null) {
		const text = globalThis.process?.env?.[ENVIRONMENT];
		if (text === undefined || text.trim() === '') return DEFAULT_SECONDS;
		source = ENVIRONMENT;
		given = Number(text);
	}
	if (typeof given !== 'number' || Number.isNaN(given) || given <= 0) {
		throw new RangeError(`${source} must be a positive number of seconds, got ${JSON.stringify(given) ?? String(given)}`);
	}
	return given;
}

// `promise`, or a Timeout naming `what` once `seconds` have passed without it settling.
export function within(promise, seconds, what) {
	if (seconds === Infinity) return promise;
	let timer;
	const late = new Promise((_, reject) => {
		timer = setTimeout(() => reject(new Timeout(what(), seconds)), seconds * 1000);
	});
	return Promise.race([promise, late]).finally(() => clearTimeout(timer));
}
