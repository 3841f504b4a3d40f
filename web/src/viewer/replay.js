// A recording played in the viewer (/view?recording=ID): the server reads the file
// (GET /api/recordings/ID/at and …/ticks); this page keeps its own timeline, so any number
// of viewers watch one recording, each at its own time. Play, pause, seek, speed ×0.1 to
// ×10, and a tick at a time forwards or back.

const AHEAD_SECONDS = 1;   // of recording time fetched ahead of the cursor (× speed)
export const SPEEDS = [0.1, 0.25, 0.5, 1, 2, 5, 10];
const TICK = 1 / 60;

export class Replay {
	// receive(message): the viewer's; changed(): the timeline shows the new state
	constructor(id, receive, changed = () => {}) {
		this.base = new URL(`/api/recordings/${encodeURIComponent(id)}/`, import.meta.url);
		this.receive = receive;
		this.changed = changed;
		this.time = 0;
		this.duration = 0;
		this.playing = false;
		this.speed = 1;
		this.buffer = [];        // [time, messages] of ticks after `time`, in order
		this.fetched = 0;        // ticks up to this time are in the buffer (or applied)
		this.fetching = null;
		this.generation = 0;     // a seek makes what is on its way stale
		this.last = null;        // the frame's clock when the cursor last moved
		this.origin = null;      // the scene's time when the recording started
	}

	// The scene's time where the player stands (what frames and plots count in).
	sceneTime() {
		return this.origin === null ? null : this.origin + this.time;
	}

	// The recording's [start, end] in the scene's time.
	span() {
		return this.origin === null ? null : [this.origin, this.origin + this.duration];
	}

	async open() {
		await this.seek(0);
		requestAnimationFrame((now) => this.loop(now));
	}

	async get(path) {
		const answer = await fetch(new URL(path, this.base));
		const body = await answer.json();
		if (!answer.ok) throw new Error(`${body.code}: ${body.message}`);
		return body;
	}

	// The scene as it was at `seconds`; playing goes on from there if it was playing.
	async seek(seconds) {
		const generation = ++this.generation;
		const found = await this.get(`at?time=${seconds}`);
		if (generation !== this.generation) return;
		this.duration = found.duration;
		if (found.time === 0) this.origin = found.messages[0].time;   // the snapshot it began with
		for (const message of found.messages) this.receive(message);
		this.time = this.fetched = found.time;
		this.buffer = [];
		this.changed();
	}

	play(on = !this.playing) {
		if (on && this.time >= this.duration) this.seek(0);
		this.playing = on;
		this.last = null;
		this.changed();
	}

	setSpeed(speed) {
		this.speed = speed;
		this.changed();
	}

	// One tick forwards or back: the next recorded tick, or the one before the tick shown,
	// however far (a scene whose process stalled, on a loaded machine, has gaps of seconds
	// between its ticks).
	async step(direction) {
		this.play(false);
		const generation = this.generation;
		if (direction < 0) {
			const earlier = await this.earlier();
			return generation === this.generation ? this.seek(earlier) : undefined;
		}
		await this.fill(this.time + TICK * 30);
		while (!this.buffer.length && this.fetched < this.duration && generation === this.generation) {
			await this.fill(this.fetched + 10);
		}
		const next = generation === this.generation && this.buffer.shift();
		if (!next) return;
		for (const message of next[1]) this.receive(message);
		this.time = next[0];
		this.changed();
	}

	// The time of the last tick before the one shown at the cursor (0: the start), read
	// backwards half a second and then 10 s at a time. Ticks of no time (a paused scene's
	// stands) share their time: the one before is the last of an earlier time.
	async earlier() {
		let shown = null;
		let span = TICK * 30;
		for (let until = this.time; until > 0; until -= span, span = 10) {
			const { ticks } = await this.get(`ticks?after=${Math.max(0, until - span)}&until=${until}`);
			for (const [time] of ticks.reverse()) {
				if (shown === null) shown = time;
				else if (time < shown) return time;
			}
		}
		return 0;
	}

	loop(now) {
		requestAnimationFrame((later) => this.loop(later));
		if (!this.playing) return;
		const dt = this.last === null ? 0 : (now - this.last) / 1000;
		this.last = now;
		const target = Math.min(this.duration, this.time + dt * this.speed);
		while (this.buffer.length && this.buffer[0][0] <= target) {
			for (const message of this.buffer.shift()[1]) this.receive(message);
		}
		if (target > this.fetched) return this.fill(target + AHEAD_SECONDS * this.speed);   // wait for it
		this.time = target;
		if (this.time >= this.duration) this.playing = false;
		this.fill(this.time + AHEAD_SECONDS * this.speed);
		this.changed();
	}

	// Every tick of the recording, 10 s at a time, handed to `take` (the plots), apart
	// from the player's own reading ahead.
	async readAll(take) {
		for (let from = 0; from < this.duration; from += 10) {
			take((await this.get(`ticks?after=${from}&until=${Math.min(from + 10, this.duration)}`)).ticks);
		}
	}

	// Fetch ticks until `until` (one request at a time; at most 10 s each).
	async fill(until) {
		until = Math.min(until, this.duration);
		if (this.fetching || until <= this.fetched) return this.fetching;
		const generation = this.generation;
		const from = this.fetched;
		const to = Math.min(until, from + 10);
		this.fetching = this.get(`ticks?after=${from}&until=${to}`).then(({ ticks }) => {
			if (generation !== this.generation) return;
			this.buffer.push(...ticks);
			this.fetched = to;
		}).finally(() => { this.fetching = null; });
		return this.fetching;
	}
}

// The timeline under the picture: a tick back, play/pause, a tick forwards, the time
// slider, the time, the speed (words and ‹ ›: headless fonts lack the media symbols).
export function mountTimeline(replay) {
	const bar = Object.assign(document.createElement('div'), { id: 'timeline', className: 'timeline' });
	const button = (text, title, action) => {
		const made = Object.assign(document.createElement('button'), { textContent: text, title });
		made.addEventListener('click', action);
		bar.append(made);
		return made;
	};
	button('‹ tick', 'a tick back', () => replay.step(-1));
	const play = button('Play', 'play / pause', () => replay.play());
	button('tick ›', 'a tick forwards', () => replay.step(1));
	const slider = Object.assign(document.createElement('input'), { type: 'range', min: 0, max: 1000, value: 0 });
	slider.addEventListener('input', () => replay.seek(slider.value / 1000 * replay.duration));
	const label = document.createElement('span');
	const speed = document.createElement('select');
	for (const value of SPEEDS) speed.append(new Option(`×${value}`, value, value === 1, value === 1));
	speed.addEventListener('change', () => replay.setSpeed(Number(speed.value)));
	bar.append(slider, label, speed);
	document.body.append(bar);
	replay.changed = () => {
		play.textContent = replay.playing ? 'Pause' : 'Play';
		if (document.activeElement !== slider) slider.value = replay.duration ? replay.time / replay.duration * 1000 : 0;
		label.textContent = `${replay.time.toFixed(2)} / ${replay.duration.toFixed(2)} s`;
	};
	return bar;
}
