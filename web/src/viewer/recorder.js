// The controller's record button (/view?scene=NAME&role=controller): Record starts a
// recording of the scene on the server, Stop ends it and offers it to replay here or to
// download (an MCAP file, which Foxglove opens). Viewers (role=viewer) have none.

const SHOW_EVERY = 500;   // ms between updates of the running time

export function mountRecorder(options) {
	const box = Object.assign(document.createElement('div'), { id: 'recorder', className: 'recorder' });
	const button = document.createElement('button');
	const note = document.createElement('span');
	box.append(button, note);
	document.body.append(box);
	let running = null;   // {id, since}
	const headers = options.token ? { Authorization: `Bearer ${options.token}` } : {};
	const call = async (path) => {
		const answer = await fetch(new URL(path, import.meta.url), { method: 'POST', headers });
		const body = await answer.json();
		if (!answer.ok) throw new Error(body.message ?? answer.statusText);
		return body;
	};
	const show = () => {
		button.textContent = running ? '■ Stop' : '● Record';
		if (running) note.textContent = ` recording · ${((performance.now() - running.since) / 1000).toFixed(1)} s`;
	};
	button.addEventListener('click', async () => {
		button.disabled = true;
		try {
			if (!running) {
				const { id } = await call(`/api/scenes/${encodeURIComponent(options.scene)}/recordings`);
				running = { id, since: performance.now() };
			} else {
				const { id, seconds, bytes } = await call(`/api/recordings/${encodeURIComponent(running.id)}/stop`);
				running = null;
				note.replaceChildren(` ${seconds.toFixed(1)} s, ${(bytes / 1e6).toFixed(1)} MB: `,
					link('replay', `/view?recording=${encodeURIComponent(id)}`),
					' · ', link('download', `/api/recordings/${encodeURIComponent(id)}`));
			}
		} catch (error) {
			note.textContent = ` ${error.message}`;
		} finally {
			button.disabled = false;
			show();
		}
	});
	setInterval(() => { if (running) show(); }, SHOW_EVERY);
	show();
	return box;
}

function link(text, href) {
	return Object.assign(document.createElement('a'), { textContent: text, href, target: '_blank' });
}
