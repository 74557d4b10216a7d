// Writes the single-file page, whatnext.html, from the assembled page in DIR (node single.js DIR):
// index.html with its style sheets, scripts and icon inlined (the library, whatnext.js with its
// WebAssembly, among them), and worker.js as a text block the page starts as a blob worker.
// One file, nothing fetched: it works from a USB stick, file:// or any static host.
'use strict';
const fs = require('fs');
const path = require('path');

const dir = process.argv[2];
const read = (name) => fs.readFileSync(path.join(dir, name), 'utf8');
// Inside <script> and <style> only "</script" (or "</style") and "<!--" could end or confuse the
// block; in JavaScript "<\/" and "<\!--" inside strings mean the same, and neither can occur in
// code outside a string or a comment.
const safe = (text, tag) => text.replace(new RegExp(`</${tag}`, 'gi'), `<\\/${tag}`).replace(/<!--/g, '<\\!--');

let html = read('index.html');
html = html.replace(/<link rel="stylesheet" href="([^"]+)">/g, (m, name) => `<style>\n${safe(read(name), 'style')}\n</style>`);
html = html.replace(/<link rel="icon" href="([^"]+)" type="image\/svg\+xml">/,
                    (m, name) => `<link rel="icon" href="data:image/svg+xml;base64,${Buffer.from(read(name)).toString('base64')}">`);
// The library runs in the page (the drawing's geometry) and in the worker: one copy, which the page
// hands to the worker (app.js's makeWorker).
html = html.replace('<script src="whatnext.js"></script>',
                    () => `<script id="whatnext-module">\n${safe(read('whatnext.js'), 'script')}\n</script>`);
html = html.replace(/<script src="([^"]+)"><\/script>/g, (m, name) => `<script>\n${safe(read(name), 'script')}\n</script>`);
const worker = read('worker.js');
// The map's workers (map.js) likewise.
html = html.replace('<body>', () => `<body>\n<script type="text/plain" id="map-worker-source">\n${safe(read('map-worker.js'), 'script')}\n</script>`);
// Before the page's scripts, which look for it as they start.
html = html.replace('<body>', () => `<body>\n<script type="text/plain" id="worker-source">\n${safe(worker, 'script')}\n</script>`);
if (/<(script|link)[^>]+(src|href)="(?!data:)/.test(html)) {
  console.error('single.js: a file of the page was left out of whatnext.html');
  process.exit(1);
}
fs.writeFileSync(path.join(dir, 'whatnext.html.part'), html);
fs.renameSync(path.join(dir, 'whatnext.html.part'), path.join(dir, 'whatnext.html'));
