// Parts drawn from mesh files (GLTFPart and the round and anthropomorphic hand parts):
// each file is loaded once and shared; every part gets its own copy of the geometry's
// colours, so that recolor() on one part changes that part alone. Each file also comes
// simplified (simplify.js), which coarse drawing levels use.

import * as THREE from 'three';
import { GLTFLoader } from 'three/addons/loaders/GLTFLoader.js';
import { ConvexGeometry } from 'three/addons/geometries/ConvexGeometry.js';
import { simplified } from './simplify.js';

const REDUCED_SHARE = 0.06;  // of a file's triangles wanted at reduced detail
const REDUCE_ABOVE = 500;    // triangles; smaller geometry is drawn as it is

const loader = new GLTFLoader();
const files = new Map();  // url -> Promise of [[full, reduced] BufferGeometry] in the file's frame
let loading = 0;          // mesh parts still waiting for their file
let simple = false;       // whether mesh parts are drawn simplified now

// How many mesh parts are not drawn yet because their file is still loading.
export function meshesLoading() {
	return loading;
}

// Each mesh of a file as [full, reduced] geometries (the same one twice when small).
// The server's paths are read from the server, whoever served the page.
function load(url) {
	if (!files.has(url)) {
		files.set(url, loader.loadAsync(new URL(url, import.meta.url).href).then((gltf) => {
			const geometries = [];
			gltf.scene.updateMatrixWorld(true);
			gltf.scene.traverse((child) => {
				if (child.isMesh) geometries.push(child.geometry.clone().applyMatrix4(child.matrixWorld));
			});
			return Promise.all(geometries.map(async (full) => [full, await reduced(full)]));
		}));
	}
	return files.get(url);
}

function reduced(geometry) {
	const triangles = (geometry.index?.count ?? geometry.getAttribute('position').count) / 3;
	return triangles <= REDUCE_ABOVE ? geometry : simplified(geometry, REDUCED_SHARE);
}

// Draw every mesh part below `root` (and those made later) simplified or in full.
export function setMeshDetail(root, reduce) {
	simple = reduce;
	root.traverse((object) => {
		const forms = object.userData.forms;
		if (forms) object.geometry = forms[reduce ? forms.length - 1 : 0].geometry;
	});
}

// [r, g, b] are the file's own (linear) components, as 1.0's recolor took them; names
// and hex strings are CSS colours.
function toColor(value) {
	return Array.isArray(value) ? new THREE.Color().setRGB(...value) : new THREE.Color(value);
}

// Each vertex whose colour is within eps of `from` (every component) takes `to`.
function recolor(geometry, original, recolors) {
	const colors = geometry.getAttribute('color');
	if (!colors) return;
	colors.copy(original);
	for (const [from, to, eps] of recolors) {
		const a = toColor(from), b = toColor(to);
		for (let i = 0; i < colors.count; i++) {
			if (Math.abs(colors.getX(i) - a.r) <= eps && Math.abs(colors.getY(i) - a.g) <= eps &&
				Math.abs(colors.getZ(i) - a.b) <= eps) colors.setXYZ(i, b.r, b.g, b.b);
		}
	}
	colors.needsUpdate = true;
}

// The builder for geometry kind 'mesh': a group filled once the file has loaded.
export function mesh(g, node) {
	const holder = new THREE.Group();
	holder.position.set(...g.offset);
	if (g.mirror) holder.scale.x = -1;  // three.js turns the faces round for a mirrored mesh
	const parts = [];
	let recolors = node?.recolors ?? [];
	loading++;
	const ready = load(g.url).then((geometries) => {
		for (const sources of geometries) {
			// this part's own copy of each form, with the form's own original colours
			const forms = [...new Set(sources)].map((source) => ({
				geometry: source.clone(), original: source.getAttribute('color')?.clone() }));
			const material = new THREE.MeshPhongMaterial({ vertexColors: Boolean(forms[0].original), shininess: 40 });
			const part = new THREE.Mesh(forms[simple ? forms.length - 1 : 0].geometry, material);
			part.castShadow = part.receiveShadow = true;
			part.userData.forms = forms;
			parts.push(part);
			holder.add(part);
			for (const form of forms) recolor(form.geometry, form.original, recolors);
		}
	}).catch((error) => console.warn(`mesh ${g.url} did not load:`, error))
		.finally(() => { loading--; });
	return {
		meshes: [holder],
		ready,
		envelope: g.points ? () => new ConvexGeometry(g.points.map((p) => new THREE.Vector3(...p))) : null,
		recolor: (latest) => {
			recolors = latest;
			for (const part of parts) {
				for (const form of part.userData.forms) recolor(form.geometry, form.original, recolors);
			}
		},
	};
}
