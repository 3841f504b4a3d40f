// 1.0's leniency with missing trailing coordinates, defined: three.js stored `undefined`
// for them (and went on); here they keep the object's current value, the server gets a
// complete call, and the page gets one console warning per call site saying so.

const LIBRARY = new RegExp(`${escape(new URL('.', import.meta.url).href)}[^/]+\\.js`);   // this client's own files
const warned = new Set();

// `values` with its missing (undefined) trailing entries, up to `length`, taken from
// `current`; `what` names the call for the warning (e.g. "c1.4.setRotation").
export function filled(values, current, what) {
	const missing = [];
	const complete = current.map((value, index) => {
		if (values[index] !== undefined) return values[index];
		missing.push(index);
		return value;
	});
	if (missing.length) warnOnce(`${what} left out ${missing.map((i) => 'xyz'[i]).join(', ')}: kept as ${missing.map((i) => round(current[i])).join(', ')} (1.0 kept undefined)`);
	return complete;
}

function round(value) {
	return Math.abs(value) < 1e-12 ? 0 : Number(value.toPrecision(6));
}

// One warning per place in the page's code (the first stack frame outside this library).
function warnOnce(text) {
	const frames = (new Error().stack ?? '').split('\n').slice(1).map((line) => line.trim());
	const site = frames.find((line) => !LIBRARY.test(line)) ?? '';
	if (warned.has(site)) return;
	warned.add(site);
	console.warn(`Virtual Prosthetics: ${text}${site ? ` (${site})` : ''}`);
}

function escape(text) {
	return text.replace(/[.*+?^${}()|[\]\\]/g, '\\$&');
}
