// The server's REST side, for what the WebSocket does not carry (mesh files going up,
// recordings): the same server and token as the session's socket.

import { ServerError } from './errors.js';

// The answer to `path` on the server at `http` (http://host:port); a refusal as the
// ServerError the WebSocket would give (`request` names the call).
export async function serverCall(http, token, path, request, { method = 'GET', body, headers = {} } = {}) {
	const auth = token ? { Authorization: `Bearer ${token}` } : {};
	const answer = await fetch(new URL(path, http), { method, body, headers: { ...headers, ...auth } });
	if (!answer.ok) {
		const refusal = await answer.json().catch(() => ({}));
		throw new ServerError(refusal.code ?? 'http_error', refusal.message ?? answer.statusText, request, refusal.details ?? {});
	}
	return answer;
}
