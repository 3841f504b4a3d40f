// A page's own mesh files, as 1.0 loaded them. `new GLTFPart('gripper.glb')` in 1.0 read
// the file next to the page; the server cannot read the page's folder, so the client
// reads it (the page's site in a browser, the working folder in Node), uploads it
// (POST /api/assets) and creates the part with the name the server gives it. A name the
// page's side does not have goes to the server as it is: the bundled meshes
// ('round-palm.glb', 1.0's '../assets/gltf/round-palm.glb') and uploads' names.

import { serverCall } from './rest.js';

const WAIT_MS = 20000;   // longest a file may take to read and upload before it is given up

export class MeshFiles {
	// read(filename): its bytes, or null when the page's side has no such file;
	// upload(bytes): the server's name for them (throws the server's refusal).
	constructor({ read, upload, warn = (text) => console.warn(text) }) {
		this.read = read;
		this.upload = upload;
		this.warn = warn;
		this.names = new Map();   // filename -> Promise of the name to create the part with
	}

	// The name a part made from `filename` is created with (each file read and sent once).
	nameFor(filename) {
		if (!this.names.has(filename)) this.names.set(filename, this.lookUp(filename));
		return this.names.get(filename);
	}

	async lookUp(filename) {
		let timer;
		const late = new Promise((_, reject) => {
			timer = setTimeout(() => reject(new Error(`no answer in ${WAIT_MS / 1000} s`)), WAIT_MS);
		});
		try {
			const bytes = await Promise.race([this.read(filename), late]);
			return bytes ? await Promise.race([this.upload(bytes), late]) : filename;
		} catch (error) {
			this.warn(`Virtual Prosthetics: the mesh file ${filename} could not be sent to the server `
				+ `(${error.message}); the server is asked for a file of that name instead`);
			return filename;
		} finally {
			clearTimeout(timer);
		}
	}
}

// MeshFiles for a session of the server at `http` (http://host:port), in this runtime.
export function meshFilesFor(http, token) {
	const upload = async (bytes) => {
		const answer = await serverCall(http, token, '/api/assets', 'upload',
			{ method: 'POST', body: bytes, headers: { 'Content-Type': 'application/octet-stream' } });
		return (await answer.json()).name;
	};
	return new MeshFiles({ read: globalThis.document ? pageFile(http) : workingFolderFile, upload });
}

// In a browser: the file at the page's address for it, unless that is on the server
// itself (which has its own files).
function pageFile(http) {
	return async (filename) => {
		const address = new URL(filename, document.baseURI);
		if (address.origin === new URL(http).origin || !/^https?:$/.test(address.protocol)) return null;
		const answer = await fetch(address);
		return answer.ok ? new Uint8Array(await answer.arrayBuffer()) : null;
	};
}

// In Node: the file at that path from the working folder.
async function workingFolderFile(filename) {
	const { readFile } = await import('node:fs/promises');
	try {
		return await readFile(filename);
	} catch (error) {
		if (error.code === 'ENOENT' || error.code === 'EISDIR') return null;
		throw error;
	}
}
