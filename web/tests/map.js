// The page's map and phase plots in Chromium (playwright-core), checked against the whatnext
// command line run by the test itself.
//   node web/tests/map.js CHECK     (CHECK: one of the names in `checks` below)
// Settings from the environment, as web/tests/browser.js takes them: WHATNEXT_WEB_DIR, WHATNEXT_CLI,
// WHATNEXT_SOURCE_DIR, WHATNEXT_CHROMIUM.
'use strict';
const assert = require('assert/strict');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawnSync } = require('child_process');

const { webDir, cliPath, withPage } = require('./browser');

// Fills the map's form and draws; returns when it is done (or stopped).
async function drawMap(page, x, y, value = 'outcome', stopAfter = null) {
  for (const [axis, r] of [['x', x], ['y', y]]) {
    await page.selectOption(`#map-${axis}-key`, r.key);
    await page.fill(`#map-${axis}-lo`, r.lo);
    await page.fill(`#map-${axis}-hi`, r.hi);
    await page.fill(`#map-${axis}-n`, String(r.n));
  }
  const before = await page.evaluate(() => document.body.dataset.mapDone || '');
  await page.click('#map-draw');
  if (stopAfter !== null) {
    await page.waitForFunction((n) => window.whatnextMap.state && window.whatnextMap.state.finished >= n, stopAfter);
    await page.click('#map-stop');
  }
  await page.waitForFunction((b) => (document.body.dataset.mapDone || '') !== b, before, { timeout: 120000 });
  if (value !== 'outcome') await page.selectOption('#map-value', value);
  return page.evaluate(() => window.whatnextMap.state);
}

function sweepCsv(args) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-map-'));
  try {
    const out = path.join(dir, 'map.csv');
    const p = spawnSync(cliPath, ['sweep', ...args, '--out', out], { encoding: 'utf8' });
    assert.equal(p.status, 0, p.stderr);
    return fs.readFileSync(out, 'utf8');
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
}

// The page's sweep CSV against the command's: the same bytes. Both builds compute with one maths
// library (musl's, cmake/maths.cmake), so every number is the command's to the last digit; the
// first row that differs is named.
function sameSweep(page, native) {
  const pageRows = page.split('\n'), nativeRows = native.split('\n');
  const k = nativeRows.findIndex((row, j) => row !== pageRows[j]);
  const i = k < 0 ? nativeRows.length : k;  // or the page has rows more
  assert.equal(page, native, `row ${i} of ${nativeRows.length - 1}: the page's ${pageRows[i]} against the command's ${nativeRows[i]}`);
}

// A small grid of example 2 that has more than one outcome and invalid machines (a negative height).
const kX = { key: 'geometry.rope_length', lo: '0.5', hi: '0.9', n: 9 };
const kY = { key: 'start.sandbag_height', lo: '-0.2', hi: '1.2', n: 8 };
const vary = (r) => ['--vary', `${r.key}=${r.lo}:${r.hi}:${r.n}`];

const checks = {
  // The download is `whatnext sweep`'s file, byte for byte, and the command shown is that command.
  async csv() {
    await withPage(async (page) => {
      const state = await drawMap(page, kX, kY);
      assert.equal(state.finished, kX.n * kY.n);
      const expected = sweepCsv(['--example', '2', ...vary(kX), ...vary(kY)]);
      assert.match(expected, /,invalid,/, 'the grid has invalid machines');
      const csv = await page.evaluate(() => window.whatnextMap.csv());
      sameSweep(csv, expected);
      const [download] = await Promise.all([page.waitForEvent('download'), page.click('#map-csv')]);
      assert.equal(fs.readFileSync(await download.path(), 'utf8'), csv);
      assert.equal(state.command, `whatnext sweep --example 2 --vary ${kX.key}=${kX.lo}:${kX.hi}:${kX.n} --vary ${kY.key}=${kY.lo}:${kY.hi}:${kY.n} --out map.csv`);
      assert.equal(await page.textContent('#map-command'), state.command);
    }, { hash: '#machine=example2' });
  },

  // The single-file page (whatnext.html, opened from the disk) runs its map in the same workers.
  async single_file() {
    await withPage(async (page) => {
      const state = await drawMap(page, kX, kY);
      assert.equal(state.finished, kX.n * kY.n);
      sameSweep(await page.evaluate(() => window.whatnextMap.csv()), sweepCsv(['--example', '2', ...vary(kX), ...vary(kY)]));
    }, { base: `file://${path.join(webDir, 'whatnext.html')}`, hash: '#machine=example2' });
  },

  // A map fills every cell, with the outcomes' colours, and marks the machine shown.
  async fills() {
    await withPage(async (page) => {
      const state = await drawMap(page, { key: 'geometry.rope_length', lo: '0.6', hi: '0.85', n: 40 },
                                  { key: 'start.sandbag_height', lo: '0.3', hi: '1.2', n: 30 });
      assert.equal(state.finished, 1200);
      assert.ok(state.workers >= 1);
      const marker = await page.evaluate(() => window.whatnextMap.marker());
      assert.ok(marker, 'example 2 lies inside the map and is marked');
      // Colours drawn: more than one outcome, and the legend names them with counts adding up.
      const legend = await page.textContent('#map-legend');
      const counts = [...legend.matchAll(/: ([\d,]+)/g)].map((m) => Number(m[1].replace(/,/g, '')));
      assert.equal(counts.reduce((a, b) => a + b, 0), 1200, legend);
      assert.ok(counts.length >= 2, legend);
      // The times of the lid's opening: a scale, and the cells where it never opened grey.
      await page.selectOption('#map-value', 'lid_open');
      assert.match(await page.textContent('#map-legend'), /s .* s/);
      // Another machine shown: the map says it is not that machine's, and marks nothing.
      const runs = await page.evaluate(() => Number(document.body.dataset.runs));
      await page.selectOption('#preset', 'example1');
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, runs);
      await page.waitForSelector('#map-stale:not([hidden])');
      assert.equal(await page.evaluate(() => window.whatnextMap.marker()), null);
    }, { hash: '#machine=example2' });
  },

  // Stop ends the map early; what ran is kept and its CSV is the command's rows for those machines.
  async stop() {
    await withPage(async (page) => {
      const state = await drawMap(page, { key: 'geometry.rope_length', lo: '0.6', hi: '0.85', n: 300 },
                                  { key: 'start.sandbag_height', lo: '0.3', hi: '1.2', n: 300 }, 'outcome', 500);
      assert.ok(state.finished >= 500 && state.finished < 90000, `finished ${state.finished}`);
      assert.match(await page.textContent('#map-status'), /^Stopped: /);
      const csv = await page.evaluate(() => window.whatnextMap.csv());
      assert.equal(csv.split('\n').length - 2, state.finished);
      assert.equal(await page.isDisabled('#map-draw'), false);
    }, { hash: '#machine=example2' });
  },

  // Pointing at a cell tells its machine; clicking loads it (and the link follows).
  async hover_click() {
    await withPage(async (page) => {
      await drawMap(page, kX, kY);
      const at = await page.evaluate(() => window.whatnextMap.cellPixel(3, 5));
      await page.hover('#map-canvas', { position: at });
      const tip = await page.textContent('#map-tip');
      assert.match(tip, /rope length|geometry\.rope_length/);
      assert.match(tip, /0\.65/);  // rope length 0.5 + 3 * 0.05
      await page.click('#map-canvas', { position: at });
      await page.waitForFunction(() => /rope_length=0\.65/.test(location.hash));
      const cli = spawnSync(cliPath, ['run', '--example', '2', '--set', 'geometry.rope_length=0.65', '--set', 'start.sandbag_height=1', '-q'], { encoding: 'utf8' });
      await page.waitForFunction(() => window.whatnext.run.values.given['geometry.rope_length'] !== undefined);
      const outcome = await page.textContent('#outcome');
      assert.ok(outcome.length > 0 && cli.status === 0);
      // The machine loaded is one of the map's, marked where it was clicked.
      assert.equal(await page.isHidden('#map-stale'), true);
      const mark = await page.evaluate(() => window.whatnextMap.marker());
      const canvas = await page.locator('#map-canvas').boundingBox(), box = await page.locator('#map-box').boundingBox();
      assert.ok(Math.abs(mark.x - at.x) < 1 && Math.abs(mark.y - at.y) < 1, JSON.stringify([mark, at, canvas, box]));
      // The tip said the outcome the loaded machine has.
      const event = await page.evaluate(() => window.whatnext.run.outcome.type.replace(/_/g, ' '));
      assert.match(tip, new RegExp(event));
      // An invalid machine says why.
      const bad = await page.evaluate(() => window.whatnextMap.cellPixel(0, 0));
      await page.hover('#map-canvas', { position: bad });
      assert.match(await page.textContent('#map-tip'), /invalid machine: .*sandbag/i);
    }, { hash: '#machine=example2' });
  },

  // Keyboard: the map takes the focus, the arrows move between machines, Enter loads one.
  async keyboard() {
    await withPage(async (page) => {
      await drawMap(page, kX, kY);
      await page.focus('#map-canvas');
      await page.keyboard.press('ArrowRight');
      await page.keyboard.press('ArrowUp');
      const here = await page.textContent('#map-here');
      // From the middle (4, 4), one right and one up: 0.5 + 5 * 0.05 and -0.2 + 5 * 0.2.
      assert.match(here, /^geometry\.rope_length = 0\.75, start\.sandbag_height = 0\.8: /, here);
      await page.keyboard.press('Enter');
      await page.waitForFunction(() => /rope_length=0\.75/.test(location.hash) && /sandbag_height=0\.8(&|$)/.test(location.hash));
    }, { hash: '#machine=example2' });
  },

  // The table alternative holds every machine's outcome.
  async table() {
    await withPage(async (page) => {
      await drawMap(page, kX, kY);
      await page.click('#map-table-box summary');
      await page.waitForSelector('#map-table caption');
      const shape = await page.evaluate(() => ({
        rows: document.querySelectorAll('#map-table tbody tr').length,
        cells: document.querySelectorAll('#map-table tbody td').length,
        caption: document.querySelector('#map-table caption').textContent,
      }));
      assert.deepEqual([shape.rows, shape.cells], [kY.n, kX.n * kY.n]);
      const csv = await page.evaluate(() => window.whatnextMap.csv());
      const lidOpen = csv.split('\n').slice(1).filter((l) => /^\d+,[^,]*,[^,]*,lid_open,/.test(l)).length;
      const cells = await page.evaluate(() => [...document.querySelectorAll('#map-table td')].filter((td) => td.textContent === 'lid open').length);
      assert.equal(cells, lidOpen);
    }, { hash: '#machine=example2' });
  },

  // German: decimal commas in, decimal commas shown, the same rows as the command.
  async german() {
    await withPage(async (page) => {
      assert.match(await page.inputValue('#map-x-lo'), /^\d+,\d+$/);
      const state = await drawMap(page, { ...kX, lo: '0,5', hi: '0,9' }, { ...kY, lo: '-0,2', hi: '1,2' });
      assert.equal(state.finished, kX.n * kY.n);
      sameSweep(await page.evaluate(() => window.whatnextMap.csv()), sweepCsv(['--example', '2', ...vary(kX), ...vary(kY)]));
      assert.match(await page.textContent('#map-status'), /Maschinen in \d+,\d+ s/);
      assert.match(await page.textContent('#map-title'), /Karte/);
    }, { hash: '#machine=example2&lang=de', locale: 'de-DE' });
  },

  // A range the command refuses is refused in its words, and nothing runs.
  async bad_range() {
    await withPage(async (page) => {
      await page.fill('#map-x-lo', '0.9');
      await page.fill('#map-x-hi', '0.5');
      await page.click('#map-draw');
      await page.waitForSelector('#map-problem:not([hidden])');
      const p = spawnSync(cliPath, ['sweep', '--example', '2', '--vary', `geometry.rope_length=0.9:0.5:100`, '--vary', 'start.sandbag_height=0.3:1.2:3', '--out', '-'], { encoding: 'utf8' });
      assert.equal(p.status, 2);
      assert.equal(await page.textContent('#map-problem'), p.stderr.trim().replace(/^whatnext: error: /, ''));
    }, { hash: '#machine=example2' });
  },

  // Any column against any other, from the CSV's columns, with the run's events marked.
  async phase() {
    await withPage(async (page) => {
      await page.waitForSelector('#phase-plot canvas');
      const header = spawnSync(cliPath, ['run', '--example', '2', '--csv', '-', '-q'], { encoding: 'utf8' }).stdout.split('\n')[0].split(',');
      const options = await page.evaluate(() => [...document.querySelectorAll('#phase-x option')].map((o) => o.value));
      for (const o of options) assert.ok(header.includes(o), `${o} is a column of whatnext run --csv`);
      assert.ok(options.includes('phi_l_deg') && options.includes('dr_m_per_s'));
      await page.click('[data-preset=angles]');
      let shown = await page.evaluate(() => window.whatnextPhase.shown);
      assert.equal(shown.x, 'phi_s_deg');
      const events = await page.evaluate(() => window.whatnext.run.events.length);
      const marked = (await page.textContent('#phase-events')).match(/\([^()]*; [^()]*\)/g).length;
      assert.equal(marked, events);
      await page.click('[data-preset=energy]');
      shown = await page.evaluate(() => window.whatnextPhase.shown);
      assert.equal(shown.x, 't_s');
      assert.equal(await page.inputValue('#phase-y'), 'energy');
      assert.ok(shown.series.some((s) => /^sandbag_kinetic_J/.test(s)) && shown.series.some((s) => /^lid_potential_J/.test(s)), shown.series.join());
      await page.selectOption('#phase-y', 'tension_N');
      shown = await page.evaluate(() => window.whatnextPhase.shown);
      assert.equal(shown.series[0], 'tension_N [N]');
    }, { hash: '#machine=example2' });
  },
};

const name = process.argv[2];
if (!checks[name]) {
  console.error(`usage: node map.js CHECK (one of ${Object.keys(checks).join(', ')})`);
  process.exit(2);
}
checks[name]().then(() => console.log(`map ${name}: ok`), (e) => { console.error(e); process.exit(1); });
