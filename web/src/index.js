// The index page: what the server runs, refreshed every few seconds.

const REFRESH = 3000;
// A token in this page's URL (a server that asks for one) goes on to the pages it links.
const TOKEN = new URLSearchParams(location.search).get('token');

function withToken(href) {
	if (!TOKEN) return href;
	const url = new URL(href, location.href);
	url.searchParams.set('token', TOKEN);
	return url.pathname + url.search;
}

function passTokenOn(root) {
	for (const link of root.querySelectorAll('a[href^="/view"], a[href^="/examples/"], a[href^="/api/"]')) {
		link.setAttribute('href', withToken(link.getAttribute('href')));
	}
}

function cell(row, text, className) {
	const td = row.insertCell();
	td.textContent = text;
	if (className) td.className = className;
	return td;
}

async function refresh() {
	const headers = TOKEN ? { Authorization: `Bearer ${TOKEN}` } : {};
	const [health, scenes] = await Promise.all(
		['/api/health', '/api/scenes?saved=true'].map((url) => fetch(url, { headers }).then((r) => r.json())));
	const problems = health.problems?.length ? ` · ${health.status}: ${health.problems.join('; ')}` : '';
	document.getElementById('health').textContent =
		`version ${health.version}, protocol ${health.protocol}, up ${Math.round(health.uptime)} s${problems}`;
	const body = document.querySelector('#scenes tbody');
	body.replaceChildren();
	for (const scene of scenes) {
		const row = body.insertRow();
		// a saved scene that is not running, or one that failed or is silent, says so
		cell(row, scene.state === 'running' ? scene.name : `${scene.name} (${scene.state})`);
		for (const key of ['robots', 'objects', 'viewers', 'controllers']) cell(row, scene[key] ?? '–', 'number');
		cell(row, scene.time === undefined ? '–' : `${scene.time.toFixed(1)} s`, 'number');
		const links = row.insertCell();
		const name = encodeURIComponent(scene.name);
		links.innerHTML = `<a href="/view?scene=${name}">watch</a> · <a href="/view?scene=${name}&role=controller">control</a>`
			+ ` · <a href="/api/scenes/${name}/export" download="${name}.json">export</a>`;
		passTokenOn(links);
	}
}

// The commands shown name this server: the address the page came from (the README's
// 8000 is only the default port)
for (const url of document.querySelectorAll('.ws-url')) {
	url.textContent = `${location.protocol === 'https:' ? 'wss' : 'ws'}://${location.host}`;
}
passTokenOn(document);
refresh().catch(console.error);
setInterval(() => refresh().catch(console.error), REFRESH);
