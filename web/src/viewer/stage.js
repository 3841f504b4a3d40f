// The picture around the robots (parts.md, "Scene"): background and fog, the ground disc,
// a shadow-casting directional light and a hemisphere light, the 30° camera with orbit
// controls, and the render loop at the display's rate. A picture is drawn only when
// something changed (invalidate), so an idle viewer costs no CPU or battery, at the
// level the quality controller chose (quality.js), so that messages keep flowing on
// software WebGL, and there no more than SOFTWARE_FPS a second (or ?fps=).

import * as THREE from 'three';
import { OrbitControls } from 'three/addons/controls/OrbitControls.js';
import { Quality, softwareWebGL } from './quality.js';
import { setMeshDetail } from './meshes.js';

const BACKGROUND = 'gainsboro';
// Pictures a second at most where WebGL draws in software, unless the page's ?fps= says
// otherwise (0: the display's rate): SwiftShader draws on every core, and a viewer of an
// empty scene (its logo spinning) took 1.7 cores drawing 29 pictures a second.
export const SOFTWARE_FPS = 15;
const FRAME_MARGIN = 1.15;   // frame(): room around what is framed

export class Stage {
	// quality: a level's name to hold (quality.js), or null to adapt
	constructor(container = document.body, fps = null, quality = null) {
		const software = this.software = softwareWebGL();
		const most = fps ?? (software ? SOFTWARE_FPS : 0);
		this.gapMs = most > 0 ? 1000 / most : 0;  // between the starts of two pictures
		// antialiasing is fixed when the context is made: software draws every sample
		const renderer = this.renderer = new THREE.WebGLRenderer({ antialias: !software });
		container.appendChild(renderer.domElement);

		const scene = this.scene = new THREE.Scene();
		scene.background = new THREE.Color(BACKGROUND);
		scene.fog = new THREE.Fog(BACKGROUND, 100, 400);
		this.sun = this.light();
		scene.add(this.sun, new THREE.HemisphereLight('white', 'cornsilk', 0.6 * Math.PI));
		scene.add(this.ground());

		this.camera = new THREE.PerspectiveCamera(30, 1, 0.1, 1000);
		this.camera.position.set(4, 4, 7);
		this.controls = new OrbitControls(this.camera, renderer.domElement);
		this.controls.target.set(0, 1, 0);
		this.controls.update();
		this.controls.addEventListener('change', () => this.invalidate());
		this.placed = true;     // the scene's camera was set by a script (else: camera.placed false)
		this.orbited = false;   // a person moved this page's camera
		this.controls.addEventListener('start', () => { this.orbited = true; });

		this.beforeRender = [];
		this.afterRender = [];
		this.needsRender = true;
		this.wantedAt = performance.now();  // since when a picture is wanted
		this.nextAt = 0;                    // no picture starts before this (gapMs)
		this.pictures = 0;                 // drawn so far (the status line counts them)
		this.quality = new Quality(software, (level) => this.applyLevel(level), quality);
		this.applyLevel(this.quality.level);
		window.addEventListener('resize', () => this.resize());
		renderer.setAnimationLoop((time) => this.draw(time));
	}

	light() {
		// three.js now measures light physically; π × the 1.0 intensities gives 1.0's look
		const light = new THREE.DirectionalLight('white', 0.4 * Math.PI);
		light.position.set(5, 18, 3);
		light.castShadow = true;
		light.shadow.mapSize.set(1024, 1024);
		light.shadow.blurSamples = 10;
		light.shadow.radius = 2;
		light.shadow.bias = -0.00001;
		Object.assign(light.shadow.camera, { left: -10, right: 10, top: 10, bottom: -10 });
		return light;
	}

	ground() {
		const ground = new THREE.Mesh(new THREE.CircleGeometry(2000, 64),
			new THREE.MeshLambertMaterial({ color: 'lightgray' }));
		ground.rotation.x = -Math.PI / 2;
		ground.receiveShadow = true;
		ground.name = 'ground';
		return ground;
	}

	applyLevel(level) {
		const { renderer, sun } = this;
		renderer.setPixelRatio(level.pixelRatio ?? window.devicePixelRatio);
		renderer.shadowMap.enabled = level.shadows !== null;
		if (level.shadows !== null) {
			renderer.shadowMap.type = level.shadows;
			sun.shadow.mapSize.set(level.map, level.map);
			sun.shadow.map?.dispose();
			sun.shadow.map = null;            // made again at the new size and type
		}
		renderer.shadowMap.needsUpdate = true;
		setMeshDetail(this.scene, level.reduced);
		this.scene.traverse((object) => { if (object.material) [].concat(object.material).forEach((m) => { m.needsUpdate = true; }); });
		this.resize();
	}

	resize() {
		const width = window.innerWidth, height = window.innerHeight;
		this.camera.aspect = width / height;
		this.camera.updateProjectionMatrix();
		this.renderer.setSize(width, height, false);
		this.invalidate();
	}

	invalidate() {
		if (!this.needsRender) this.wantedAt = performance.now();
		this.needsRender = true;
	}

	// The scene's camera, as a script set it (setCameraPosition / setCameraTarget), or the
	// default one nobody placed (`placed: false`).
	setCamera({ position, target, placed = true }) {
		this.placed = placed;
		this.controls.target.set(...target);
		this.camera.position.set(...position);
		this.camera.lookAt(this.controls.target);
		this.controls.update();
		this.invalidate();
	}

	// Frame all: the camera backs off along its line of sight, or comes closer, until
	// ``object`` (what the scene holds) fills the view, centred; a page's own view of it,
	// not the scene's camera (the next setCameraPosition moves it again).
	frame(object) {
		const box = new THREE.Box3().setFromObject(object);
		if (box.isEmpty()) return false;
		const sphere = box.getBoundingSphere(new THREE.Sphere());
		const { camera, controls } = this;
		const half = THREE.MathUtils.degToRad(camera.fov / 2);
		const fitting = Math.min(half, Math.atan(Math.tan(half) * camera.aspect));  // the narrower
		const distance = Math.max(sphere.radius, 0.01) / Math.sin(fitting) * FRAME_MARGIN;
		const towards = camera.position.clone().sub(controls.target).normalize();
		controls.target.copy(sphere.center);
		camera.position.copy(sphere.center).addScaledVector(towards, distance);
		camera.lookAt(controls.target);
		controls.update();
		this.invalidate();
		return true;
	}

	// On its own, a viewer frames `object` when part of it lies out of view, as long as
	// no script placed the scene's camera and nobody here moved it.
	frameIfCut(object) {
		if (this.placed || this.orbited) return false;
		const box = new THREE.Box3().setFromObject(object);
		if (box.isEmpty() || this.sees(box)) return false;
		return this.frame(object);
	}

	sees(box) {
		const { camera } = this;
		camera.updateMatrixWorld();
		const frustum = new THREE.Frustum().setFromProjectionMatrix(
			new THREE.Matrix4().multiplyMatrices(camera.projectionMatrix, camera.matrixWorldInverse));
		const corner = new THREE.Vector3();
		for (let k = 0; k < 8; k++) {
			corner.set(k & 1 ? box.max.x : box.min.x, k & 2 ? box.max.y : box.min.y, k & 4 ? box.max.z : box.min.z);
			if (!frustum.containsPoint(corner)) return false;
		}
		return true;
	}

	draw(time) {
		for (const step of this.beforeRender) step(time);
		const started = performance.now();
		if (!this.needsRender || started < this.nextAt) return;  // (still wanted: a later frame)
		this.needsRender = false;
		this.renderer.render(this.scene, this.camera);
		this.renderMs = performance.now() - started;
		this.pictures++;
		// the quality judges the wait it causes, not the one the cap asked for
		this.quality.drawn(Math.max(this.wantedAt, this.nextAt), started);
		this.nextAt = started + this.gapMs;
		for (const step of this.afterRender) step(time);
	}
}
