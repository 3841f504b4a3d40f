// The status line: connection state, scene, frames per second from the server (the scene's
// tick rate when all is well), pictures per second drawn here, and how many clients watch
// or drive the scene, and whether a script holds its clock (paused, stepping it).

const COUNT_EVERY = 2000;   // ms between asks for the scene's client count

export class StatusLine {
	// pictures(): how many pictures the viewer has drawn so far
	constructor(element, scene, watchLink = null, pictures = () => 0, recording = null) {
		this.element = element;
		this.scene = scene;
		this.recording = recording;   // the recording played, if one is
		this.watchLink = watchLink;   // a page's own scene: where others can watch it
		this.state = 'connecting';
		this.fps = null;   // until a second of frames has been counted
		this.pictures = pictures;
		this.pps = null;
		this.drawnBefore = 0;
		this.clients = null;
		this.frames = 0;
		this.since = null;   // counting starts with the first frame
		this.warning = null;   // the scene's last warning (changes not saved, replaced), if any
		this.mode = 'kinematic';   // the scene's physics (said only when dynamic)
		this.paused = false;   // a script holds the scene's clock (REST's pausedBy, asked with the count)
		setInterval(() => this.countClients(), COUNT_EVERY);
	}

	setState(state) {
		this.state = state;
		this.show();
	}

	// The scene's warning, shown until the next one (null: all is well again).
	warn(text) {
		this.warning = text;
		this.show();
	}

	// The scene's physics mode (kinematic or dynamic).
	physics(mode = 'kinematic') {
		this.mode = mode;
		this.show();
	}

	// Called for every frame from the server.
	frame() {
		const now = performance.now();
		if (this.since === null) this.since = now;
		this.frames++;
		if (now - this.since >= 1000) {
			this.fps = Math.round(this.frames * 1000 / (now - this.since));
			const drawn = this.pictures();
			this.pps = Math.round((drawn - this.drawnBefore) * 1000 / (now - this.since));
			this.drawnBefore = drawn;
			this.frames = 0;
			this.since = now;
			this.show();
		}
	}

	async countClients() {
		if (this.recording) return;   // a recording has no clients
		try {
			const response = await fetch(new URL(`/api/scenes/${encodeURIComponent(this.scene)}`, import.meta.url));
			if (response.ok) {
				const { viewers, controllers, pausedBy } = await response.json();
				this.clients = { viewers, controllers };
				this.paused = pausedBy != null;
			}
		} catch {
			this.clients = null;
		}
		this.show();
	}

	show() {
		const parts = [this.state, this.recording ? `recording ${this.recording}` : `scene ${this.scene}`,
			`${this.fps ?? '…'} frames/s`, `${this.pps ?? '…'} pictures/s`];
		if (this.mode === 'dynamic') parts.splice(2, 0, 'dynamic');
		if (this.paused) parts.splice(2, 0, 'paused by a script');
		if (this.clients) {
			const { viewers, controllers } = this.clients;
			parts.push(`${viewers} viewer${viewers === 1 ? '' : 's'}`);
			if (controllers) parts.push(`${controllers} controller${controllers === 1 ? '' : 's'}`);
		}
		if (this.warning) parts.push(`⚠ ${this.warning}`);
		this.element.textContent = parts.join(' · ');
		if (this.watchLink) {
			const link = Object.assign(document.createElement('a'), { href: this.watchLink, textContent: 'watch link', target: '_blank' });
			this.element.append(' · ', link);
		}
		this.element.classList.toggle('down', !['connected', 'replay'].includes(this.state));
	}
}
