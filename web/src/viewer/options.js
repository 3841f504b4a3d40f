// The viewer's URL options: /view?scene=NAME&role=viewer|controller&touch-color=red
//   &debug-physics&show-slots&engine=NAME&token=TOKEN (a server that asks for one)
//   &physics=dynamic|kinematic (a page: the scene's physics once connected)
//   &fps=N (pictures a second at most; 0: the display's rate; left out: 15 where WebGL
//   draws in software, the display's rate elsewhere)
//   &quality=NAME (a drawing level of quality.js held, from full to rough; left out: the
//   viewer adapts its level to how long pictures take)
//   /view?recording=ID: a recording played (replay.js) instead of a live scene

export function readOptions(search = window.location.search) {
	const params = new URLSearchParams(search);
	const flag = (name) => params.has(name) && params.get(name) !== 'false';
	return {
		scene: params.get('scene') || 'default',
		role: params.get('role') === 'controller' ? 'controller' : 'viewer',
		touchColor: params.get('touch-color') || null,
		debugPhysics: flag('debug-physics'),
		showSlots: flag('show-slots'),
		engine: params.get('engine') || null,
		token: params.get('token') || null,
		physics: ['dynamic', 'kinematic'].includes(params.get('physics')) ? params.get('physics') : null,
		recording: params.get('recording') || null,   // play a recording instead of a scene
		fps: /^\d+(\.\d+)?$/.test(params.get('fps') ?? '') ? Number(params.get('fps')) : null,
		quality: params.get('quality') || null,   // a level's name (quality.js checks it)
	};
}

// The WebSocket address of a scene, on the server that served this page.
export function socketUrl(options, location = window.location) {
	const scheme = location.protocol === 'https:' ? 'wss:' : 'ws:';
	const query = new URLSearchParams({ scene: options.scene, role: options.role });
	if (options.engine) query.set('engine', options.engine);
	if (options.token) query.set('token', options.token);
	return `${scheme}//${location.host}/ws?${query}`;
}
