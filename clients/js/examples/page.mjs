// An example page of web/examples run in Node, its script as it is but for the import line:
//
//   VP_URL=ws://127.0.0.1:8000 node clients/js/examples/page.mjs digger [scene]
//   node clients/js/examples/page.mjs "two-hands?hand=RoundHand"   (the page's own options)
//
// The pages are the manual's steps (simple-robot-1 … 4, digger) and the other examples,
// written once: here the page's `import … from "/client/virtual-prosthetics.js"` becomes
// this client and `await Prosthetic.connect(…)` (VP_URL, and the scene from the command
// line or VP_SCENE). A page that draws on its own (a panel, a plot) needs a browser.
import { readFile } from "node:fs/promises";

const PAGE_IMPORT = 'import * as Prosthetic from "/client/virtual-prosthetics.js";';
const [page, scene = process.env.VP_SCENE] = process.argv.slice(2);
const [, name, query] = /^([a-z0-9-]+)(\?.*)?$/.exec(page ?? "") ?? [];
if (!name) {
	console.error("usage: node clients/js/examples/page.mjs PAGE [SCENE]  (PAGE: digger, simple-robot-3, two-hands …)");
	process.exit(2);
}
const html = await readFile(new URL(`../../../web/examples/${name}.html`, import.meta.url), "utf8");
const script = html.match(/<script type="module">([\s\S]*?)<\/script>/)?.[1];
if (!script?.includes(PAGE_IMPORT))
	throw new Error(`web/examples/${name}.html has no module script importing the client as pages do`);
if (query) // what the page reads of its address (location.search), as in a browser
	globalThis.location = new URL(`http://localhost/examples/${name}.html${query}`);
const client = new URL("../virtual-prosthetics.js", import.meta.url).href;
const options = JSON.stringify({ url: process.env.VP_URL, scene });
// (a data: module may import absolute URLs only: the client by its file URL)
await import("data:text/javascript," + encodeURIComponent(script.replace(PAGE_IMPORT,
	`import * as Prosthetic from ${JSON.stringify(client)}; await Prosthetic.connect(${options});`)));
