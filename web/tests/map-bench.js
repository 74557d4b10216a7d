// The page's map beside the native sweep, in one run: the 100x100 map of example 2 drawn in
// Chromium (web/src/map.js, one worker per core) and `whatnext sweep` over the same grid, taken in
// turns; prints each one's median wall time, their ratio, and the longest the page's thread went
// without a frame while the map ran (how responsive it stayed). docs/performance.md, "The map in
// the page".
//   node web/tests/map-bench.js [RUNS]      (from the source folder, after a WHATNEXT_WEB build)
// Settings from the environment as web/tests/browser.js takes them.
'use strict';
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawnSync } = require('child_process');

const { cliPath, withPage } = require('./browser');
const runs = Number(process.argv[2] || 7);
const grid = [['geometry.rope_length', '0.64', '0.80', 100], ['start.sandbag_height', '0.3', '1.2', 100]];

const median = (a) => [...a].sort((x, y) => x - y)[Math.floor(a.length / 2)];

const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-bench-'));
const out = path.join(dir, 'native.csv');
withPage(async (page) => {
  for (const [i, [key, lo, hi, n]] of grid.entries()) {
    const axis = i === 0 ? 'x' : 'y';
    await page.selectOption(`#map-${axis}-key`, key);
    await page.fill(`#map-${axis}-lo`, lo);
    await page.fill(`#map-${axis}-hi`, hi);
    await page.fill(`#map-${axis}-n`, String(n));
  }
  const drawOnce = () => page.evaluate(() => new Promise((resolve) => {
    // The longest gap between frames while the map runs: the page's thread kept free or not.
    let last = performance.now(), worst = 0, on = true;
    const frame = (now) => { worst = Math.max(worst, now - last); last = now; if (on) requestAnimationFrame(frame); };
    requestAnimationFrame(frame);
    const before = document.body.dataset.mapDone;
    new MutationObserver((list, obs) => {
      if (document.body.dataset.mapDone === before) return;
      obs.disconnect();
      on = false;
      resolve({ ms: window.whatnextMap.state.ms, worst, workers: window.whatnextMap.state.workers, size: window.whatnextMap.state.size });
    }).observe(document.body, { attributes: true, attributeFilter: ['data-map-done'] });
    document.getElementById('map-draw').click();
  }));
  const first = await drawOnce();  // the workers have just started: their module may still be compiling
  const page_ = [], native = [], frames = [];
  const args = ['sweep', '--example', '2', ...grid.flatMap(([k, lo, hi, n]) => ['--vary', `${k}=${lo}:${hi}:${n}`]), '--out', out];
  for (let r = 0; r < runs; ++r) {
    const t0 = process.hrtime.bigint();
    const p = spawnSync(cliPath, args);
    if (p.status !== 0) throw new Error(String(p.stderr));
    native.push(Number(process.hrtime.bigint() - t0) / 1e6);
    const m = await drawOnce();
    page_.push(m.ms);
    frames.push(m.worst);
  }
  // The rows that are the native file's byte for byte: all of them, the two builds sharing one
  // maths library (cmake/maths.cmake; web/tests/map.js requires it).
  const pageRows = (await page.evaluate(() => window.whatnextMap.csv())).split('\n'), nativeRows = fs.readFileSync(out, 'utf8').split('\n');
  const same = nativeRows.filter((row, i) => row === pageRows[i]).length - 1;  // not the empty last
  const pm = median(page_), nm = median(native);
  console.log(`grid: ${grid.map(([k, lo, hi, n]) => `${k}=${lo}:${hi}:${n}`).join(' ')} (${first.size} machines), ${runs} runs each, in turns`);
  console.log(`page (Chromium, ${first.workers} workers): median ${pm.toFixed(0)} ms (runs ${page_.map((x) => x.toFixed(0)).join(' ')}); first map after the page opened ${first.ms.toFixed(0)} ms`);
  console.log(`native whatnext sweep (whole process): median ${nm.toFixed(0)} ms (runs ${native.map((x) => x.toFixed(0)).join(' ')})`);
  console.log(`ratio page / native: ${(pm / nm).toFixed(2)}; longest frame while the map ran: median ${median(frames).toFixed(0)} ms, worst ${Math.max(...frames).toFixed(0)} ms`);
  console.log(`rows of the page's CSV the same bytes as the native file's: ${same} of ${nativeRows.length - 1} (the header among them)`);
}, { hash: '#machine=example2' }).then(() => {
  fs.rmSync(dir, { recursive: true, force: true });
  process.exit(0);
}).catch((e) => { console.error(e); process.exit(1); });
