// The index page: what the server runs, refreshed every few seconds.

const REFRESH = 3000;

function cell(row, text, className) {
	const td = row.insertCell();
	td.textContent = text;
	if (className) td.className = className;
	return td;
}

async function refresh() {
	const [health, scenes] = await Promise.all(
		['/api/health', '/api/scenes'].map((url) => fetch(url).then((r) => r.json())));
	document.getElementById('health').textContent =
		`version ${health.version}, protocol ${health.protocol}, up ${Math.round(health.uptime)} s`;
	const body = document.querySelector('#scenes tbody');
	body.replaceChildren();
	for (const scene of scenes) {
		const row = body.insertRow();
		cell(row, scene.name);
		for (const key of ['robots', 'objects', 'viewers', 'controllers']) cell(row, scene[key], 'number');
		cell(row, `${scene.time.toFixed(1)} s`, 'number');
		const links = row.insertCell();
		const name = encodeURIComponent(scene.name);
		links.innerHTML = `<a href="/view?scene=${name}">watch</a> · <a href="/view?scene=${name}&role=controller">control</a>`;
	}
}

refresh().catch(console.error);
setInterval(() => refresh().catch(console.error), REFRESH);
