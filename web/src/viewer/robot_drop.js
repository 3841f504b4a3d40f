// A controller's drop of a robot file (/view?scene=NAME&role=controller): a URDF, an MJCF
// .xml or a zip of one with its meshes, dropped onto the picture, is placed in the scene
// where it lands on the ground (POST /api/scenes/{scene}/robots), shared so that every
// controller steers it. The note under the record button says what came of it.

import * as THREE from 'three';

const KINDS = /\.(urdf|xml|zip)$/i;

export function mountRobotDrop(options, camera, canvas) {
	const note = Object.assign(document.createElement('div'), { id: 'robot-drop', className: 'robot-drop' });
	document.body.append(note);
	const headers = { 'Content-Type': 'application/octet-stream',
		...(options.token ? { Authorization: `Bearer ${options.token}` } : {}) };
	canvas.addEventListener('dragover', (event) => {
		event.preventDefault();   // without it the browser opens the file instead
		event.dataTransfer.dropEffect = 'copy';
	});
	canvas.addEventListener('drop', async (event) => {
		event.preventDefault();
		const file = event.dataTransfer?.files?.[0];
		if (!file) return;
		if (!KINDS.test(file.name)) {
			note.textContent = `${file.name}: drop a .urdf, an MJCF .xml or a .zip of one with its meshes`;
			return;
		}
		note.textContent = `reading ${file.name}…`;
		const [x, , z] = groundPoint(event, camera, canvas);
		const path = `/api/scenes/${encodeURIComponent(options.scene)}/robots?position=${x},0,${z}`;
		try {
			const answer = await fetch(new URL(path, import.meta.url), { method: 'POST', headers, body: file });
			const body = await answer.json();
			if (!answer.ok) throw new Error(body.message ?? answer.statusText);
			note.textContent = `${file.name}: ${body.name} (${body.id}), ${body.motors.length} motors`;
		} catch (error) {
			note.textContent = `${file.name}: ${error.message}`;
		}
	});
	return note;
}

// Where the pointer's ray meets the ground (y = 0); the origin when it looks away from it.
function groundPoint(event, camera, canvas) {
	const box = canvas.getBoundingClientRect();
	const pointer = new THREE.Vector2(((event.clientX - box.left) / box.width) * 2 - 1,
		-((event.clientY - box.top) / box.height) * 2 + 1);
	const ray = new THREE.Raycaster();
	ray.setFromCamera(pointer, camera);
	const hit = ray.ray.intersectPlane(new THREE.Plane(new THREE.Vector3(0, 1, 0), 0), new THREE.Vector3());
	return hit ? hit.toArray().map((v) => Number(v.toFixed(4))) : [0, 0, 0];
}
