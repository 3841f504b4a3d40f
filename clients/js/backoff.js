// How long to wait before connecting again after a loss: a pause doubling from 100 ms to
// at most 1 s. One policy for the client's transport and the viewer.

export const FIRST_PAUSE_MS = 100, LONGEST_PAUSE_MS = 1000;

export class Backoff {
	constructor() {
		this.pause = FIRST_PAUSE_MS;
	}

	// The pause before the next attempt (each one twice the last, up to the longest).
	next() {
		const pause = this.pause;
		this.pause = Math.min(LONGEST_PAUSE_MS, this.pause * 2);
		return pause;
	}

	// Connected again: the next loss starts from the first pause.
	reset() {
		this.pause = FIRST_PAUSE_MS;
	}
}
