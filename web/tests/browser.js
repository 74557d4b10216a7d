// What the page's browser tests share: their settings, the page served from the build by a small
// local server, and the page opened in a fresh Chromium (playwright-core) that fails the check on
// any console error, page error, failed request or request that leaves the page's own place.
// Settings from the environment (CTest sets them; the defaults suit a run from the source folder):
// WHATNEXT_WEB_DIR, WHATNEXT_CLI, WHATNEXT_SOURCE_DIR, WHATNEXT_CHROMIUM.
'use strict';
const assert = require('assert/strict');
const fs = require('fs');
const http = require('http');
const os = require('os');
const path = require('path');

const env = (name, fallback) => process.env[name] || fallback;
const sourceDir = path.resolve(env('WHATNEXT_SOURCE_DIR', '.'));
const webDir = path.resolve(env('WHATNEXT_WEB_DIR', path.join(sourceDir, 'build/web')));
const cliPath = path.resolve(env('WHATNEXT_CLI', path.join(sourceDir, 'build/whatnext')));
const chromiumPath = env('WHATNEXT_CHROMIUM', '/usr/bin/chromium');
const { chromium } = require(require.resolve('playwright-core', {
  paths: [...(process.env.NODE_PATH || '').split(':').filter(Boolean), path.join(sourceDir, 'build/web-npm/node_modules')],
}));

// Chromium as root in a container on a closed network: no sandbox, no GPU, and none of its own
// connections (they would be refused); a fresh profile every time.
const kChromiumFlags = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
                        '--disable-background-networking', '--disable-component-update', '--disable-sync'];

// The folder dir on 127.0.0.1 at a free port: { url, close }.
function serve(dir) {
  const types = { '.html': 'text/html', '.js': 'text/javascript', '.css': 'text/css', '.svg': 'image/svg+xml',
                  '.txt': 'text/plain' };
  const server = http.createServer((req, res) => {
    const file = path.join(dir, decodeURIComponent(new URL(req.url, 'http://x').pathname).replace(/\/$/, '/index.html'));
    if (!file.startsWith(dir) || !fs.existsSync(file)) {
      res.writeHead(404);
      res.end();
      return;
    }
    res.writeHead(200, { 'Content-Type': types[path.extname(file)] || 'application/octet-stream' });
    fs.createReadStream(file).pipe(res);
  });
  return new Promise((resolve) => server.listen(0, '127.0.0.1', () => {
    resolve({ url: `http://127.0.0.1:${server.address().port}/`, close: () => server.close() });
  }));
}

// Opens the page in a fresh browser and runs fn(page, tools); fails on any console error, page
// error, failed request or request that leaves the local server. options: base (the page from
// another place: the single file from the disk, or another server's address), hash, ready (the
// selector that says the page is ready), viewport, scale, locale, touch, reducedMotion, clipboard.
async function withPage(fn, options = {}) {
  const server = await serve(webDir);
  const base = options.base || server.url;
  const profile = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-chromium-'));
  const downloads = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-downloads-'));
  const context = await chromium.launchPersistentContext(profile, {
    executablePath: chromiumPath, headless: true, args: kChromiumFlags, acceptDownloads: true,
    viewport: options.viewport || { width: 1400, height: 900 }, deviceScaleFactor: options.scale || 1,
    locale: options.locale || 'en-GB', hasTouch: Boolean(options.touch), isMobile: Boolean(options.touch),
    reducedMotion: options.reducedMotion || 'no-preference',
  });
  if (options.clipboard) await context.grantPermissions(['clipboard-read', 'clipboard-write']);
  const problems = [];
  const watch = (page) => {
    page.on('console', (m) => { if (m.type() === 'error') problems.push(`console error: ${m.text()}`); });
    page.on('pageerror', (e) => problems.push(`page error: ${e.message}`));
    page.on('requestfailed', (r) => problems.push(`request failed: ${r.url()}`));
    page.on('request', (r) => {
      if (!r.url().startsWith(base) && !/^(data|blob):/.test(r.url())) problems.push(`network: ${r.url()}`);
    });
  };
  context.on('page', watch);
  // A page's WebAssembly is compiled before it is ready: up to a minute on a busy machine.
  const open = async (hash = '', waitFor = 'body[data-ready]') => {
    const page = await context.newPage();
    await page.goto(base + hash);
    await page.waitForSelector(waitFor, { timeout: 60000 });
    return page;
  };
  try {
    const page = await open(options.hash, options.ready);
    await fn(page, { open, downloads, server, context });
    assert.deepEqual(problems, [], 'the browser reported problems');
  } finally {
    await context.close();
    server.close();
    fs.rmSync(profile, { recursive: true, force: true });
    fs.rmSync(downloads, { recursive: true, force: true });
  }
}

module.exports = { env, sourceDir, webDir, cliPath, chromiumPath, chromium, kChromiumFlags, serve, withPage };
