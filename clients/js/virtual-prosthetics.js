// Virtual Prosthetics 1.0's API against a Virtual Prosthetics server, in the browser and
// in Node. As 1.0 did, it also exports all of three.js and lil-gui's GUI.
//
//   Browser: import * as Prosthetic from "http://HOST:8000/client/virtual-prosthetics.js";
//            (connects to HOST, joins ?scene=NAME or a fresh scene, shows the viewer)
//   Node:    import * as Prosthetic from "virtual-prosthetics";
//            await Prosthetic.connect({ url: "ws://HOST:8000", scene: "NAME" });

export * from 'three';
export { GUI } from 'lil-gui';
export { AnthroPalm, AnthroThumb, Ball, Box, EdgedFinger, EdgedPalm, EdgedTip, GLTFPart, Motor, SceneMesh,
	MotorX, MotorY, MotorZ, Part, RoundFinger, RoundPalm, Slider, Slot } from './objects.js';
export { AnthroHand, EdgedHand, ImportedRobot, RoundHand, Robot } from './robot.js';
export { Sensor } from './sensor.js';
export { ConnectionLost, ProtocolError, ServerError, Timeout, VPError } from './errors.js';
export { Recording, startRecording, stopRecording } from './recordings.js';
export { VERSION, close, connect, getPhysics, getScene, getTime, pause, resume, setAnimation,
	setCameraPosition, setCameraTarget, setCaption, setPhysics, step, sync, saveState, restoreState, forgetState } from './runtime.js';

import { IN_BROWSER, VERSION } from './runtime.js';

console.log(`Virtual Prosthetics 1.0 (client ${VERSION})`);
if (IN_BROWSER) await (await import('./page.js')).startPage(import.meta.url);
