// Numbers JSON cannot carry travel as strings (protocol/README.md): "Infinity",
// "-Infinity" and "NaN". The one place in JavaScript that turns them back and forth.

export const NON_FINITE = Object.freeze({ Infinity: Infinity, '-Infinity': -Infinity, NaN: NaN });

// A number as it travels: finite ones as they are, the others as their strings.
export function wireNumber(x) {
	if (Number.isFinite(x)) return x;
	if (Number.isNaN(x)) return 'NaN';
	return x > 0 ? 'Infinity' : '-Infinity';
}

// A number that arrived: a wire string back to its value; anything else unchanged.
export function fromWire(value) {
	return typeof value === 'string' && value in NON_FINITE ? NON_FINITE[value] : value;
}

// `value` with every non-finite number inside it (arrays, plain objects) as its string.
export function encodeNumbers(value) {
	if (typeof value === 'number') return wireNumber(value);
	if (Array.isArray(value)) return value.map(encodeNumbers);
	if (value !== null && typeof value === 'object' && Object.getPrototypeOf(value) === Object.prototype) {
		return Object.fromEntries(Object.entries(value).map(([k, v]) => [k, encodeNumbers(v)]));
	}
	return value;
}

// One message as the text the server takes.
export function encode(message) {
	return JSON.stringify(encodeNumbers(message));
}
