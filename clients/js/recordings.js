// Not in 1.0: recordings of the scene, made by the server (MCAP: Foxglove opens them).
//   const rec = await startRecording();  …  await rec.stop();  await rec.save('trial.mcap');
// save writes the file in Node and downloads it in a browser. Starting is the scene call
// startRecording (stopRecording() stops the scene's recording, whoever started it); a
// Recording is stopped by its id and fetched over REST (/api/recordings/{id}…) with the
// session's token.

import { serverCall } from './rest.js';
import { SCENE_ID } from './runtime.js';
import { currentSession } from './session.js';

export class Recording {
	constructor(session, id) {
		this.session = session;
		this.id = id;
		this.summary = null;   // what it holds, once stopped
	}

	// Stop it (this client's earlier changes in it first); what it holds: bytes, seconds,
	// ticks, requests, readings, and why it stopped.
	async stop() {
		await this.session.sync();
		this.summary = await (await serverCall(this.session.http, this.session.token, `/api/recordings/${this.id}/stop`,
			'stopRecording', { method: 'POST' })).json();
		return this.summary;
	}

	// The MCAP file's bytes (stopping the recording first if it runs).
	async bytes() {
		if (!this.summary) await this.stop();
		const answer = await serverCall(this.session.http, this.session.token, `/api/recordings/${this.id}`, 'saveRecording');
		return new Uint8Array(await answer.arrayBuffer());
	}

	// Node: the file at `path`; a browser: a download named `path`.
	async save(path = `${this.id}.mcap`) {
		const data = await this.bytes();
		if (globalThis.document) {
			const link = Object.assign(document.createElement('a'), {
				href: URL.createObjectURL(new Blob([data])), download: path });
			link.click();
			setTimeout(() => URL.revokeObjectURL(link.href), 0);
		} else {
			const { writeFile } = await import('node:fs/promises');
			await writeFile(path, data);
		}
		return path;
	}
}

// Start recording the current scene: every frame, request and watched reading from now
// (after this client's earlier requests).
export async function startRecording(session = currentSession()) {
	return new Recording(session, await session.call(SCENE_ID, 'startRecording', [], { wait: true }));
}

// Stop the scene's recording, whoever started it; what it holds.
export async function stopRecording(session = currentSession()) {
	return session.call(SCENE_ID, 'stopRecording', [], { wait: true });
}
