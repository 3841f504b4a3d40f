// The viewer page: one page watching one scene of the server that served it.

import { Connection } from './connection.js';
import { readOptions, socketUrl } from './options.js';
import { mountViewer } from './viewer.js';

const options = readOptions();
let connection = null;
const viewer = mountViewer({ options, request: (message) => connection.request(message) });
connection = new Connection(socketUrl(options), {
	onMessage: (message) => viewer.receive(message),
	onState: (state) => viewer.setState(state),
});
