// The fine checker of the sensor pads, drawn once on a canvas.

import * as THREE from 'three';

let checker = null;

export function sensorTexture() {
	if (checker) return checker;
	const size = 64, cells = 8, canvas = document.createElement('canvas');
	canvas.width = canvas.height = size;
	const context = canvas.getContext('2d');
	for (let i = 0; i < cells; i++) for (let j = 0; j < cells; j++) {
		context.fillStyle = (i + j) % 2 ? '#ffffff' : '#c8c8c8';
		context.fillRect(i * size / cells, j * size / cells, size / cells, size / cells);
	}
	checker = new THREE.CanvasTexture(canvas);
	checker.wrapS = checker.wrapT = THREE.RepeatWrapping;
	checker.repeat.set(4, 1);
	checker.colorSpace = THREE.SRGBColorSpace;
	return checker;
}
