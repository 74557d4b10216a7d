// The page in a real browser: Debian's Chromium driven by playwright-core, the page served from
// build/web by a small local server, every number checked against the whatnext command line run
// by the test itself.
//   node web/tests/page.js CHECK       (CHECK: one of the names in `checks` below, or "speed")
// Settings from the environment (CTest sets them; the defaults suit a run from the source folder):
// WHATNEXT_WEB_DIR, WHATNEXT_CLI, WHATNEXT_SOURCE_DIR, WHATNEXT_CHROMIUM, WHATNEXT_TEST_OUT.
'use strict';
const assert = require('assert/strict');
const fs = require('fs');
const os = require('os');
const path = require('path');
const { spawnSync } = require('child_process');

const { env, sourceDir, webDir, cliPath, withPage } = require('./browser');
const outDir = path.resolve(env('WHATNEXT_TEST_OUT', path.join(sourceDir, 'build/web-test')));
const kSandbagColour = [204, 127, 0];  // web/src/machine.js, as the animation draws it
const kSeesawColour = [153, 85, 51], kGroundColour = [224, 224, 224];  // the same

// ---- the command line --------------------------------------------------------------------------

function cli(...args) {
  const p = spawnSync(cliPath, args, { cwd: sourceDir, encoding: 'utf8' });
  return { status: p.status, stdout: p.stdout, stderr: p.stderr.trim() };
}
const sets = (list) => list.flatMap((s) => ['--set', s]);
function cliOutcome(args) {
  const r = cli('run', ...args, '-q');
  assert.equal(r.status, 0, `whatnext run ${args.join(' ')}: ${r.stderr}`);
  return r.stdout.trim();
}
function cliEvents(args) {
  const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-events-'));
  const file = path.join(dir, 'events.json');
  try {
    assert.equal(cli('run', ...args, '--events', file, '-q').status, 0);
    return JSON.parse(fs.readFileSync(file, 'utf8'));
  } finally {
    fs.rmSync(dir, { recursive: true, force: true });
  }
}
function cliError(args) {
  const r = cli('run', ...args, '-q');
  assert.equal(r.status, 2, `whatnext run ${args.join(' ')} should refuse the input`);
  assert.match(r.stderr, /^whatnext: error: /);
  return r.stderr.replace(/^whatnext: error: /, '');
}

// ---- the page ----------------------------------------------------------------------------------

const runs = (page) => page.evaluate(() => Number(document.body.dataset.runs));
// The library runs in a worker: after a change, wait until nothing is running or waiting.
const idle = (page) => page.waitForFunction(() => document.body.dataset.busy === 'false', null, { timeout: 60000 });
const outcomeText = (page) => page.textContent('#outcome');
const fieldId = (key) => `#field-${key.replace(/\./g, '-')}`;

// Types a value into a parameter's field and leaves it, as a user would; waits for the run.
async function setField(page, key, value) {
  const before = await runs(page);
  await page.fill(fieldId(key), value);
  await page.press(fieldId(key), 'Tab');
  await idle(page);
  return before;
}
async function setFieldAndRun(page, key, value) {
  const before = await setField(page, key, value);
  await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
}

// The timeline rows as the page shows them: the six columns of each event and its impact line.
function pageTimeline(page) {
  return page.$$eval('#timeline tbody tr', (rows) => {
    const out = [];
    for (const r of rows) {
      const cells = [...r.cells].map((c) => c.textContent);
      // An impact's energy line, without the page's note on negative energies.
      if (r.classList.contains('note')) out[out.length - 1].push(...r.cells[0].firstChild.textContent.split(' '));
      else out.push(cells);
    }
    return out;
  });
}
// The same rows from `whatnext run`'s stdout.
function cliTimeline(stdout) {
  const lines = stdout.trimEnd().split('\n');
  return { rows: lines.slice(2, -1).map((l) => l.trim().split(/\s+/)), outcome: lines[lines.length - 1] };
}

// Two outputs of the same run, one written in WebAssembly and one natively: the same bytes (one
// maths library in both builds, cmake/maths.cmake); the first line that differs is named.
function sameText(mine, theirs, what) {
  const a = mine.split('\n'), b = theirs.split('\n');
  const k = b.findIndex((line, j) => line !== a[j]);
  const i = k < 0 ? b.length : k;
  assert.equal(mine, theirs, `${what}: line ${i + 1} '${a[i]}' here, '${b[i]}' from the CLI`);
}

// Clicks an item of the header's menus (Share, Download), opening its menu first.
async function menuClick(page, button) {
  const menu = await page.evaluate((b) => { const d = document.querySelector(b).closest('details'); return d && !d.open ? d.id : null; }, button);
  if (menu) await page.click(`#${menu} > summary`);
  await page.click(button);
}

async function download(page, button, dir) {
  const [dl] = await Promise.all([page.waitForEvent('download'), menuClick(page, button)]);
  const file = path.join(dir, dl.suggestedFilename());
  await dl.saveAs(file);
  return file;
}

async function canvasColour(page, x, y) {
  return page.evaluate(([px, py]) => {
    const c = document.getElementById('machine');
    return [...c.getContext('2d').getImageData(Math.round(px), Math.round(py), 1, 1).data].slice(0, 3);
  }, [x, y]);
}
const near = (a, b, tol = 12) => a.every((v, i) => Math.abs(v - b[i]) <= tol);
// English words left in a text of the German page. Keys (geometry.rope_length), file names, the
// values as given (in German quotes), TOML sections and the library's names (adaptive, rope,
// true, ...) are the library's and stay.
const kEnglishWords = ['must', 'be', 'is', 'are', 'the', 'of', 'and', 'or', 'to', 'at', 'from', 'than', 'with', 'by',
  'for', 'not', 'no', 'its', 'it', 'this', 'that', 'which', 'use', 'give', 'given', 'needs', 'most', 'least', 'one', 'too',
  'never', 'apart', 'start', 'under', 'above', 'below', 'left', 'number', 'numbers', 'key', 'value', 'line', 'expected',
  'got', 'found', 'next', 'unknown', 'section', 'mean', 'did', 'pair', 'finite', 'range', 'made', 'steps', 'rows',
  'allowed', 'lid', 'rope', 'seesaw', 'sandbag', 'balloon', 'switch', 'hinge', 'pivot', 'box', 'edge', 'straight',
  'shorter', 'longer', 'distance', 'inertia', 'bar', 'uniform', 'lift', 'air', 'rises', 'error', 'while', 'parsing',
  'encountered', 'cannot', 'redefine', 'existing', 'quoted', 'without', 'quotes', 'write', 'point', 'decimal', 'comma',
  'holds', 'exactly', 'many', 'plain', 'units', 'stopped', 'failed', 'module', 'turned', 'motion', 'state', 'run',
  'file', 'machine', 'time', 'consistent', 'contacts', 'set', 'degenerate', 'contact', 'impact', 'mode', 'step',
  'loosen', 'shorten', 'advancing', 'same', 'instant', 'decided', 'again', 'may', 'fixed',
  'makes', 'centre', 'weight', 'acts', 'both', 'remove', 'enable', 'other', 'keys', 'puts', 'there', 'already', 'gives',
  'free', 'acceleration', 'about', 'more', 'far', 'too', 'stops', 'part', 'damps', 'unstable', 'shorter', 'would',
  'through', 'displaced', 'dot', 'does', 'make', 'name', 'after'];
function englishIn(text) {
  const rest = text.replace(/„[^“]*“|"[^"]*"|'[^']*'/g, ' ')
    .replace(/\[[^\]]*\]/g, ' ')
    .replace(/[\w-]+(\.[\w-]+)+|\w+_\w+/g, ' ')
    .replace(/\b(adaptive|euler|rk4|rope|angular-momentum-sum|kinetic-energy|linear-momentum|program|lagrangian|added-mass|true|false|deg|kg|rad|xs|phiS|r_[A-Z]|rho_\w+|com_offset|SCHLÜSSEL|WERT|TOML|M\d)\b/g, ' ');
  const words = rest.match(/[A-Za-zÄÖÜäöüß]+/g) || [];
  return [...new Set(words.filter((w) => kEnglishWords.includes(w.toLowerCase())))];
}
const kBalloonColour = [255, 42, 51];  // web/src/machine.js
// Pixels of a colour within 40 px of the picture's edges (below the caption band): an arrow to
// a part beyond the picture.
async function edgeHas(page, rgb) {
  return page.evaluate(([c]) => {
    const canvas = document.getElementById('machine'), band = Math.ceil(window.whatnext.pictureTop), w = canvas.width, h = canvas.height;
    const data = canvas.getContext('2d').getImageData(0, 0, w, h).data;
    let n = 0;
    for (let y = band; y < h; ++y) {
      for (let x = 0; x < w; ++x) {
        if (x >= 40 && x < w - 40 && y >= band + 40 && y < h - 40) continue;
        const i = 4 * (y * w + x);
        if (Math.abs(data[i] - c[0]) + Math.abs(data[i + 1] - c[1]) + Math.abs(data[i + 2] - c[2]) < 30) ++n;
      }
    }
    return n > 30;
  }, [rgb]);
}

async function scrubTo(page, t) {
  await page.evaluate((time) => {
    const s = document.getElementById('scrub');
    s.value = String(time);
    s.dispatchEvent(new Event('input', { bubbles: true }));
  }, t);
  assert.equal(await page.evaluate(() => window.whatnext.time), t);
}

// The timeline's columns whole: nothing to scroll sideways in its box.
async function checkTimelineWhole(page, name) {
  const [scroll, client] = await page.evaluate(() => { const b = document.querySelector('.table-box'); return [b.scrollWidth, b.clientWidth]; });
  assert.ok(scroll <= client, `${name}: the timeline is ${scroll} px wide in ${client} px`);
}

// ---- the checks --------------------------------------------------------------------------------

// axe-core in the page: no WCAG 2.1 A or AA violation, at the start, after playing to the end (the
// past rows greyed) with the forces drawn and the "why" open, in English and German.
async function axeCheck(name, viewport, options) {
  const axe = fs.readFileSync(require.resolve('axe-core/axe.min.js', {
    paths: [...(process.env.NODE_PATH || '').split(':').filter(Boolean), path.join(sourceDir, 'build/web-npm/node_modules')],
  }), 'utf8');
  for (const locale of ['en-GB', 'de-DE']) {
    await withPage(async (page) => {
      const check = async (when) => {
        await page.addScriptTag({ content: axe });
        const result = await page.evaluate(() => window.axe.run(document, {
          runOnly: { type: 'tag', values: ['wcag2a', 'wcag2aa', 'wcag21a', 'wcag21aa'] },
        }));
        const found = result.violations.map((v) => `${v.id}: ${v.help} (${v.nodes.slice(0, 3).map((n) => n.target.join(' ')).join('; ')})`);
        assert.deepEqual(found, [], `${name} ${locale}, ${when}: WCAG 2.1 A/AA violations`);
      };
      if (options.projector) {
        await page.keyboard.press('f');
        await page.waitForTimeout(300);
      }
      await check('at the start');
      await page.evaluate(() => window.whatnext.play());
      await page.evaluate(() => window.whatnext.seek(window.whatnext.run.tEnd));
      await page.evaluate(() => document.querySelector('#forces').click());
      await page.evaluate(() => { document.getElementById('why').open = true; });
      await page.waitForSelector('#why[data-ready]');
      await check('at the end, forces drawn, the why open');
      await page.selectOption('#compare', 'laws');
      await idle(page);
      await check('all four impact laws compared (their colours as text)');
      await page.screenshot({ path: path.join(outDir, `web-axe-${name}-${locale.slice(0, 2)}.png`) });
    }, { viewport, locale, touch: options.touch, scale: options.scale });
  }
}

const checks = {
  // Every shipped machine loads, plays and compares without an error in the console, and nothing
  // is fetched from outside the page's own folder.
  async console() {
    await withPage(async (page) => {
      const ids = await page.$$eval('#preset option', (os) => os.map((o) => o.value));
      assert.deepEqual(ids, ['example1', 'example2', 'example3', 'example4', 'radio', 'konstanz']);
      for (const id of ids) {
        const before = await runs(page);
        await page.selectOption('#preset', id);
        await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
        const expected = id === 'radio' ? cliOutcome(['examples/example1-radio.toml'])
          : cliOutcome(['--example', id === 'konstanz' ? id : id.slice(-1)]);
        assert.equal(await outcomeText(page), `Outcome: ${expected}.`, id);
        await page.click('#machine');
        await page.keyboard.press('Space');
        await page.waitForTimeout(250);
        await page.keyboard.press('Space');
        for (const mode of ['law', 'laws', 'euler', 'previous', 'none']) {
          await page.selectOption('#compare', mode);
          await idle(page);
        }
      }
    });
  },

  // Example 1's timeline, row by row, and its outcome as `whatnext run --example 1` prints them;
  // the outcome is the paper's 0.82 s.
  async timeline() {
    await withPage(async (page) => {
      const expected = cli('run', '--example', '1');
      assert.equal(expected.status, 0);
      const { rows, outcome } = cliTimeline(expected.stdout);
      assert.equal(outcome, 'Outcome: lid open at 0.820 s.');
      assert.deepEqual(await pageTimeline(page), rows);
      assert.equal(await outcomeText(page), outcome);
      assert.equal(await page.textContent('#cli-text'), expected.stdout);
      assert.equal(await page.textContent('#cli-command'), '$ whatnext run --example 1');
    });
  },

  // A longer and a shorter rope: the page's outcome is the command line's for that input.
  async rope_length() {
    await withPage(async (page) => {
      for (const length of ['0.95', '1.2', '0.8']) {
        await setFieldAndRun(page, 'geometry.rope_length', length);
        const args = ['--example', '1', ...sets([`geometry.rope_length=${length}`])];
        assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(args)}.`, `rope ${length} m`);
        assert.deepEqual(await pageTimeline(page), cliTimeline(cli('run', ...args).stdout).rows);
      }
    });
  },

  // A value the command line refuses: its message next to the field, and the last good run stays.
  async bad_value() {
    await withPage(async (page) => {
      await setFieldAndRun(page, 'geometry.rope_length', '0.95');
      const good = { outcome: await outcomeText(page), timeline: await pageTimeline(page), url: page.url() };
      for (const bad of ['0.2', 'abc', '-1']) {
        const before = await setField(page, 'geometry.rope_length', bad);
        // The command line's message, without its "--set KEY=VALUE: " (the page's words).
        const message = cliError(['--example', '1', ...sets([`geometry.rope_length=${bad}`])]).replace(`--set geometry.rope_length=${bad}: `, '');
        assert.doesNotMatch(message, /--set/);
        const shown = `${fieldId('geometry.rope_length')} >> xpath=ancestor::div[@data-key]//p[contains(@class,"error")]`;
        await page.waitForSelector(shown, { state: 'visible' });
        assert.equal(await page.textContent(shown), message);
        assert.ok((await page.textContent('#problem')).includes(message));
        assert.equal(await runs(page), before, 'no new run');
        assert.equal(await outcomeText(page), good.outcome);
        assert.deepEqual(await pageTimeline(page), good.timeline);
        assert.equal(page.url(), good.url, 'the link keeps the last good machine');
      }
      // A decimal comma is a decimal point.
      await setFieldAndRun(page, 'geometry.rope_length', '0,9');
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', 'geometry.rope_length=0.9'])}.`);
      assert.match(page.url(), /geometry\.rope_length=0\.9$/);
      await setField(page, 'geometry.rope_length', '-1');
      // A key the rule is about that is not the one edited: the message goes to both.
      const before = await setField(page, 'start.sandbag_height', '-5');
      await page.waitForSelector('#problem', { state: 'visible' });
      const message = cliError(['--example', '1', ...sets(['geometry.rope_length=-1', 'start.sandbag_height=-5'])]).replace(/^--set [^:]*: /, '');
      assert.ok((await page.textContent('#problem')).includes(message));
      assert.equal(await runs(page), before);
    });
  },

  // The sandbag is drawn where the command line's CSV puts it at the scrubbed time: its colour is
  // at that pixel, and not where it is at another time. The pivot and the lid's hinge are black
  // dots at their places, so the picture's scale is checked too.
  async sandbag_pixels() {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-csv-'));
    const csvFile = path.join(dir, 'example1.csv');
    assert.equal(cli('run', '--example', '1', '--csv', csvFile).status, 0);
    const [header, ...lines] = fs.readFileSync(csvFile, 'utf8').trim().split('\n');
    fs.rmSync(dir, { recursive: true, force: true });
    const col = Object.fromEntries(header.split(',').map((name, i) => [name, i]));
    const at = (t) => {
      const row = lines.map((l) => l.split(',')).find((r) => r[col.event] === '' && Number(r[col.t_s]) === t);
      return { x: Number(row[col.x_m]), h: Number(row[col.h_m]) };
    };
    await withPage(async (page) => {
      // (Later the sandbag slides beyond the picture, which frames the machine: drawing.)
      for (const [t, other] of [[0.3, 0.6], [0.6, 0.3], [0.55, 0.45]]) {
        await scrubTo(page, t);
        const here = at(t), there = at(other);
        const p = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [here.x, here.h]);
        const q = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [there.x, there.h]);
        assert.ok(Math.hypot(p.x - q.x, p.y - q.y) > 20, 'the two places are apart on the canvas');
        assert.ok(near(await canvasColour(page, p.x, p.y), kSandbagColour), `sandbag at t = ${t} s`);
        assert.ok(!near(await canvasColour(page, q.x, q.y), kSandbagColour), `no sandbag at the t = ${other} s place`);
      }
      const machine = await page.evaluate(() => window.whatnext.run.machine);
      for (const [name, point] of [['pivot', { x: 0, h: 0 }], ['hinge', machine.hinge]]) {
        const p = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [point.x, point.h]);
        assert.ok(near(await canvasColour(page, p.x, p.y), [0, 0, 0], 40), `${name} drawn at its place`);
      }
    }, { scale: 2 });
  },

  // A link reopens the same machine, comparison and all, in a new page.
  async shared_link() {
    await withPage(async (page, { open }) => {
      await setFieldAndRun(page, 'geometry.rope_length', '0.9');
      await page.selectOption(fieldId('run.impact_law'), 'kinetic-energy');
      await page.selectOption('#compare', 'law');
      await page.selectOption('#compare-law', 'linear-momentum');
      await idle(page);
      const url = new URL(page.url());
      const again = await open(url.hash);
      const look = (p) => p.evaluate(() => ({
        outcome: document.getElementById('outcome').textContent,
        compare: document.getElementById('compare-outcome').textContent,
        timeline: window.whatnext.run.timeline,
        rope: document.getElementById('field-geometry-rope_length').value,
        law: document.getElementById('field-run-impact_law').value,
      }));
      const first = await look(page), second = await look(again);
      assert.deepEqual(second, first);
      const args = ['--example', '1', ...sets(['geometry.rope_length=0.9', 'run.impact_law=kinetic-energy'])];
      assert.equal(second.outcome, `Outcome: ${cliOutcome(args)}.`);
      assert.equal(second.compare, `Dashed, impact law linear-momentum: ${cliOutcome([...args, '--set', 'run.impact_law=linear-momentum'])}.`);
    });
  },

  // The downloads are what the command line writes: the TOML runs in it to the page's outcome, the
  // events JSON and the CSV are `whatnext run --events/--csv` for that input, word for word.
  async downloads() {
    await withPage(async (page, { downloads: dir }) => {
      await setFieldAndRun(page, 'geometry.rope_length', '0.9');
      await setFieldAndRun(page, 'masses.lid', '0.4');
      const args = ['--example', '1', ...sets(['geometry.rope_length=0.9', 'masses.lid=0.4'])];
      const toml = await download(page, '#dl-toml', dir);
      assert.equal(`Outcome: ${cliOutcome([toml])}.`, await outcomeText(page));
      const json = await download(page, '#dl-json', dir), csv = await download(page, '#dl-csv', dir);
      const events = path.join(dir, 'cli.json'), rows = path.join(dir, 'cli.csv');
      assert.equal(cli('run', ...args, '--events', events, '--csv', rows, '-q').status, 0);
      sameText(fs.readFileSync(json, 'utf8'), fs.readFileSync(events, 'utf8'), 'events JSON');
      sameText(fs.readFileSync(csv, 'utf8'), fs.readFileSync(rows, 'utf8'), 'CSV');
    });
  },

  // Space plays and pauses, ] and PageDown go to the next event, [ back, End and Home to the ends,
  // the arrows step a millisecond; the event's frame says what happened, as the animation does.
  async keyboard() {
    await withPage(async (page) => {
      const events = cliEvents(['--example', '1']).events;
      const times = [...new Set(events.map((e) => e.t))];
      const time = () => page.evaluate(() => window.whatnext.time);
      const at = async (t) => assert.ok(Math.abs((await time()) - t) < 1e-9, `at ${await time()} s, not ${t} s`);
      await page.keyboard.press('Space');
      await page.waitForTimeout(400);
      await page.keyboard.press('Space');
      const played = await time();
      assert.ok(played > 0 && played < times[0], `played to ${played} s`);
      await page.waitForTimeout(200);
      assert.equal(await time(), played, 'paused');
      await page.keyboard.press(']');
      await at(times[0]);
      await page.keyboard.press('PageDown');
      await at(times[1]);
      assert.equal(await page.textContent('#timeline tr.now td:nth-child(2)'), 'rope_taut');
      await page.keyboard.press('[');
      await at(times[0]);
      await page.keyboard.press('End');
      await at(times[times.length - 1]);
      await page.keyboard.press('Home');
      await page.keyboard.press('ArrowRight');
      assert.equal(await time(), 1e-3);
      await page.keyboard.press('-');
      assert.equal(await page.inputValue('#speed'), '0.05');
      await page.click('#timeline tbody tr.event >> nth=4');
      await at(events[4].t);
    });
  },

  // The extensions set in the panel as a user would (a number typed and the next control clicked
  // at once, check boxes, a choice): a heavy seesaw with a finite arm, the radio, air drag and
  // another impact law give the command line's run, and the page names that command.
  async extensions() {
    await withPage(async (page) => {
      const before = await runs(page);
      await page.selectOption('#preset', 'example2');
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
      await page.click('details.group:last-of-type > summary');  // "Extensions beyond the paper"
      // Clicks move the mouse from a field to one further down, over the first one's help.
      await page.click(fieldId('balloon.drag'));
      await page.click(fieldId('radio.enabled'));
      await page.fill(fieldId('seesaw.left_arm'), '1.2');
      await page.click(fieldId('seesaw.mass'));
      await page.fill(fieldId('seesaw.mass'), '0.4');
      await page.click(fieldId('seesaw.com_offset'));
      await page.selectOption(fieldId('run.impact_law'), 'angular-momentum-sum');
      await idle(page);
      const set = ['balloon.drag=true', 'radio.enabled=true', 'seesaw.left_arm=1.2', 'seesaw.mass=0.4',
                   'run.impact_law=angular-momentum-sum'];
      for (const key of ['radio.enabled', 'balloon.drag']) assert.ok(await page.isChecked(fieldId(key)), key);
      const args = ['--example', '2', ...sets(set)];
      const expected = cli('run', ...args);
      assert.equal(expected.status, 0);
      assert.deepEqual(await pageTimeline(page), cliTimeline(expected.stdout).rows);
      assert.equal(await outcomeText(page), cliTimeline(expected.stdout).outcome);
      assert.equal(await page.textContent('#cli-command'), `$ whatnext run ${args.join(' ')}`);
      assert.equal(await page.textContent('#cli-text'), expected.stdout);
    });
  },

  // The built machine, the konstanz preset: the command line's timeline and outcome
  // (a real party balloon: the radio stays off); the floor across the picture with the ground below it and nothing of
  // the machine drawn under it, at the start (the seesaw's right end on the floor), at each event
  // and at the end (the seesaw's left end and the sandbag on the floor); the end stop drawn at the
  // left arm's end, and not once it is switched off. Each new key set in the panel gives the
  // command line's run, and the German page names the new events and impulses in German.
  async built() {
    const base = ['--example', 'konstanz'];
    const expected = cli('run', ...base);
    assert.equal(expected.status, 0);
    const { rows, outcome } = cliTimeline(expected.stdout);
    assert.match(outcome, /the radio stays off\.$/);
    const times = [0, ...new Set(cliEvents(base).events.map((e) => e.t))];
    assert.ok(rows.some((r) => r[1] === 'seesaw_on_floor') && rows.some((r) => r[1] === 'sandbag_at_stop'), 'the floor and the stop act');
    // A contact's impulse that is rounding noise (1e-16 N s in WebAssembly where the native build
    // gets 0, as at konstanz's sandbag_at_stop) is written "0.0000 N s" by one build and left out by
    // the other: such entries are left out of both timelines compared here.
    const noNoise = (list) => list.map((row) => row.join(' ').replace(/; impulse (.*?)(?=;|$)/, (all, items) => {
      const kept = items.split(', ').filter((item) => !/ -?0\.0000 N (m )?s$/.test(item));
      return kept.length ? `; impulse ${kept.join(', ')}` : '';
    }).split(' '));
    let page;
    // Below the floor line (2 px down, past its anti-aliased edge) and inside the red outline of an
    // event's frame (4 px): how many pixels of the ground's, the sandbag's and the seesaw's colours,
    // of how many.
    const below = () => page.evaluate(([colours]) => {
      const w = window.whatnext, m = w.run.machine, canvas = document.getElementById('machine');
      const y0 = Math.ceil(w.canvasPixel(0, m.hinge.h - 2 * m.lid_half_length).y) + 2, edge = Math.ceil(5 * devicePixelRatio);
      const data = canvas.getContext('2d').getImageData(edge, y0, canvas.width - 2 * edge, canvas.height - edge - y0).data;
      const n = colours.map(() => 0);
      for (let i = 0; i < data.length; i += 4) {
        colours.forEach((c, k) => { if (Math.abs(data[i] - c[0]) + Math.abs(data[i + 1] - c[1]) + Math.abs(data[i + 2] - c[2]) < 30) ++n[k]; });
      }
      return { ground: n[0], sandbag: n[1], seesaw: n[2], all: data.length / 4, rows: canvas.height - edge - y0 };
    }, [[kGroundColour, kSandbagColour, kSeesawColour]]);
    // The end stop's middle, 0.05 m off the arm's end at the left arm's side: the seesaw's colour.
    const stopPixel = async () => {
      const s = await page.evaluate(() => window.whatnext.stateAt(0)), m = await page.evaluate(() => window.whatnext.run.machine);
      const end = { x: -m.seesaw_left_arm * Math.cos(s.phi_s), h: -m.seesaw_left_arm * Math.sin(s.phi_s) };
      const mid = { x: end.x - 0.05 * Math.sin(s.phi_s), h: end.h + 0.05 * Math.cos(s.phi_s) };
      const p = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [mid.x, mid.h]);
      return canvasColour(page, p.x, p.y);
    };
    const timeline = async (list) => {
      const r = cli('run', ...base, ...sets(list));
      assert.equal(r.status, 0, r.stderr);
      const want = cliTimeline(r.stdout);
      assert.deepEqual(noNoise(await pageTimeline(page)), noNoise(want.rows), list.join(' '));
      assert.equal(await outcomeText(page), want.outcome, list.join(' '));
      return want;
    };
    await withPage(async (p) => {
      page = p;
      assert.deepEqual(noNoise(await pageTimeline(page)), noNoise(rows));
      assert.equal(await outcomeText(page), outcome);
      assert.equal(await page.textContent('#cli-command'), '$ whatnext run --example konstanz');
      for (const t of times) {
        await page.evaluate((x) => window.whatnext.seek(x), t);
        const b = await below();
        assert.ok(b.rows > 10, `t = ${t} s: ${b.rows} rows of ground in the picture`);
        assert.ok(b.ground > 0.9 * b.all, `t = ${t} s: ${b.ground} of ${b.all} pixels below the floor are ground`);
        assert.equal(b.sandbag, 0, `t = ${t} s: the sandbag below the floor`);
        assert.equal(b.seesaw, 0, `t = ${t} s: the seesaw below the floor`);
      }
      await page.evaluate(() => window.whatnext.seek(0));
      assert.ok(near(await stopPixel(), kSeesawColour), 'the end stop is drawn');
      await page.click('details.group:last-of-type > summary');  // "Extensions beyond the paper"
      await page.click(fieldId('seesaw.end_stop'));
      await idle(page);
      assert.ok(!(await page.isChecked(fieldId('seesaw.end_stop'))));
      assert.notDeepEqual((await timeline(['seesaw.end_stop=false'])).rows, rows);
      await page.evaluate(() => window.whatnext.seek(0));
      assert.ok(!near(await stopPixel(), kSeesawColour), 'no end stop drawn once it is off');
      await setFieldAndRun(page, 'floor.restitution', '0.5');
      await timeline(['seesaw.end_stop=false', 'floor.restitution=0.5']);
      await setFieldAndRun(page, 'radio.switch_force', '0.1');
      const off = await timeline(['seesaw.end_stop=false', 'floor.restitution=0.5', 'radio.switch_force=0.1']);
      assert.match(off.outcome, /the radio stays off\.$/);
      // floor.enabled through its check box, on example 1 with a finite arm (its sandbag slides off
      // onto the floor). Example 1 does not give geometry.rope_on_lid: its field is blank and
      // stands for the lid's free edge, 2 r_L, with its slider there (not at the far left).
      let before = await runs(page);
      await page.selectOption('#preset', 'example1');
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
      const knot = await page.$eval(fieldId('geometry.rope_on_lid'), (e) => [e.value, e.placeholder]);
      assert.deepEqual(knot, ['', '0.4'], 'the knot at the lid\'s free edge, 2 r_L = 0.4 m');
      const slider = await page.$eval(`[data-key="geometry.rope_on_lid"] input.slider`, (e) => Number(e.value));
      assert.ok(Math.abs(slider - 1000 * (0.4 - 0.02) / (1 - 0.02)) <= 1, `the knot's slider at ${slider}`);
      await setFieldAndRun(page, 'seesaw.left_arm', '1.2');
      before = await runs(page);
      await page.click(fieldId('floor.enabled'));
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
      await idle(page);
      const args = ['--example', '1', ...sets(['seesaw.left_arm=1.2', 'floor.enabled=true'])];
      const want = cliTimeline(cli('run', ...args).stdout);
      assert.ok(want.rows.some((r) => r[1] === 'sandbag_on_floor'));
      assert.deepEqual(noNoise(await pageTimeline(page)), noNoise(want.rows));
      assert.equal(await page.textContent('#cli-command'), `$ whatnext run ${args.join(' ')}`);
      await page.evaluate(() => window.whatnext.seek(0.7172));  // the sandbag on the floor
      const b = await below();
      assert.ok(b.ground > 0.9 * b.all && b.sandbag === 0 && b.seesaw === 0, JSON.stringify(b));
    }, { hash: '#machine=konstanz', scale: 2 });

    // In German: the new events, the impulses of the stop and the floor, the outcome.
    await withPage(async (p) => {
      page = p;
      const straight = cliOutcome(['--example', 'konstanz']).match(/straight at ([\d.]+) s/)[1].replace('.', ',');
      assert.equal(await outcomeText(page),
                   `Ergebnis: die Ballonschnur ist bei ${straight} s gestreckt, zieht aber schwächer als radio.switch_force: das Radio bleibt aus.`);
      const names = await page.$$eval('#timeline tbody tr.event td:nth-child(2)', (cells) => cells.map((c) => c.textContent));
      for (const name of ['Wippe hebt ab', 'Wippe auf dem Boden', 'Sandsack am Anschlag', 'Ballon entweicht', 'Schalter bleibt aus']) assert.ok(names.includes(name), `${name} in ${names}`);
      const notes = (await page.$$eval('#timeline tbody tr.note', (r) => r.map((x) => x.textContent))).join(' | ');
      // ... with the decimal comma of the German page.
      assert.match(notes, /Kraftstoß Sandsack 0,5479 N s, Boden auf Wippe 0,6474 N s/);
      assert.match(notes, /Anschlag 1,1980 N s/);
      assert.doesNotMatch(notes, /\d\.\d/);
      for (const name of names) assert.deepEqual(englishIn(name), [], name);
      assert.deepEqual(englishIn(notes.replace(/\d,\d+ N s|N s|J/g, '')), [], notes);
      await page.click('details.group:last-of-type > summary');
      // A switch the balloon can flip: the radio comes on when the string is straight.
      await setFieldAndRun(page, 'radio.switch_force', '0,01');
      const radioOn = cliOutcome(['--example', 'konstanz', '--set', 'radio.switch_force=0.01']).match(/t = ([\d.]+) s/)[1].replace('.', ',');
      assert.equal(await outcomeText(page), `Ergebnis: Radio an bei t = ${radioOn} s.`);
      const labels = await page.$$eval(['seesaw.end_stop', 'floor.enabled', 'floor.restitution', 'radio.switch_force']
        .map((k) => `[data-key="${k}"] .name`).join(','), (e) => e.map((x) => x.textContent));
      assert.deepEqual(labels, ['Schaltkraft', 'Anschlag', 'Boden', 'Stoßzahl']);
    }, { hash: '#machine=konstanz', locale: 'de-DE', viewport: { width: 1366, height: 768 } });

    // On the projector (1280x720) at the end, the string straight: the machine, from the seesaw's left end
    // at the start to the radio's switch, spans most of the drawing (it frames the machine);
    // writes web-konstanz.png.
    fs.mkdirSync(outDir, { recursive: true });
    await withPage(async (p) => {
      page = p;
      await page.keyboard.press('f');
      await page.keyboard.press('End');
      await page.waitForTimeout(300);
      const span = await page.evaluate(() => {
        const w = window.whatnext, m = w.run.machine, phi = m.start.seesaw_angle;
        const a = w.canvasPixel(-m.seesaw_left_arm * Math.cos(phi), 0), b = w.canvasPixel(m.radio_switch.x, 0);
        return (b.x - a.x) / document.getElementById('machine').width;
      });
      assert.ok(span > 0.75, `the machine spans ${span} of the drawing's width`);
      await page.screenshot({ path: path.join(outDir, 'web-konstanz.png') });
    }, { hash: '#machine=konstanz', viewport: { width: 1280, height: 720 } });
  },

  // The second run: another impact law, the paper's Euler method at a chosen step, and the
  // parameters before the last change; each one's outcome is the command line's.
  async compare() {
    await withPage(async (page) => {
      const compared = () => page.textContent('#compare-outcome');
      await page.selectOption('#compare', 'law');
      await page.selectOption('#compare-law', 'kinetic-energy');
      await idle(page);
      assert.equal(await compared(), `Dashed, impact law kinetic-energy: ${cliOutcome(['--example', '1', '--set', 'run.impact_law=kinetic-energy'])}.`);
      // The kinetic-energy law keeps the energy: after the pull the legend says nothing was lost
      // (not the rounding noise of the sum, -1.8e-15 J).
      await page.evaluate(() => window.whatnext.seek(0.7));
      const legend = await page.$$eval('#plot-energy .u-legend .u-series', (rows) => Object.fromEntries(
        rows.map((r) => [r.querySelector('.u-label').textContent, r.querySelector('.u-value').textContent])));
      assert.equal(legend['lost (impacts, damping), dashed'], '0');
      assert.notEqual(legend['lost (impacts, damping)'], '0');
      await page.selectOption('#compare', 'euler');
      await page.fill('#compare-step', '0.002');
      await idle(page);
      assert.equal(await compared(), `Dashed, Euler, step 0.002 s: ${cliOutcome(['--example', '1', ...sets(['run.integrator=euler', 'run.step=0.002'])])}.`);
      await page.selectOption('#compare', 'previous');
      await idle(page);
      await setFieldAndRun(page, 'geometry.rope_length', '0.95');
      assert.equal(await compared(), `Dashed, previous parameters: ${cliOutcome(['--example', '1'])}.`);
      // The ghost is in the drawing: the picture differs with and without it.
      await scrubTo(page, 0.7);
      const picture = () => page.evaluate(() => document.getElementById('machine').toDataURL());
      const withGhost = await picture();
      await page.selectOption('#compare', 'none');
      await idle(page);
      const plain = await picture();
      assert.notEqual(plain, withGhost);

      // All four impact laws at once: each one's outcome is the command line's, each is drawn,
      // and the plots have each law's curves; the link holds the comparison.
      await page.selectOption('#compare', 'laws');
      await idle(page);
      const lines = await page.$$eval('#compare-outcome .law-line', (ls) => ls.map((l) => l.textContent));
      const machine = ['--example', '1', '--set', 'geometry.rope_length=0.95'];
      assert.deepEqual(lines, ['rope', 'angular-momentum-sum', 'kinetic-energy', 'linear-momentum'].map(
        (law) => `${law}: ${cliOutcome([...machine, '--set', `run.impact_law=${law}`])}`));
      assert.notEqual(await picture(), plain);
      // The drawing shows one other law at a time, chosen in the legend (each law its colour).
      assert.deepEqual(await page.$$eval('#compare-legend button', (bs) => bs.map((b) => b.getAttribute('aria-pressed'))), ['true', 'false', 'false']);
      const firstGhost = await picture();
      await page.click('#compare-legend button:nth-of-type(2)');
      assert.equal(await page.getAttribute('#compare-legend button:nth-of-type(2)', 'aria-pressed'), 'true');
      assert.notEqual(await picture(), firstGhost);
      const labels = await page.$$eval('#plot-angles .u-legend .u-label', (ls) => ls.map((l) => l.textContent));
      for (const law of ['angular-momentum-sum', 'kinetic-energy', 'linear-momentum']) assert.ok(labels.includes(`φS seesaw, ${law}`), labels.join('; '));
      assert.match(page.url(), /compare=laws%3A$/);

      // An Euler step that does not run is named, and never goes into the link.
      await page.selectOption('#compare', 'euler');
      await page.fill('#compare-step', '-1');
      await idle(page);
      assert.match(await compared(), /^Nothing to compare with: run\.step must be > 0/);
      assert.doesNotMatch(page.url(), /compare=/);
    });
  },

  // A rope that stretches compared with the one that does not, and friction with none;
  // each run's outcome is the command line's, and the link holds the comparison.
  async stretch_friction() {
    await withPage(async (page, { open }) => {
      page = await open('#machine=example1&rope.stiffness=100000&compare=rigid:');
      await idle(page);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', 'rope.stiffness=100000'])}.`);
      assert.equal(await page.textContent('#compare-outcome'),
                   `Dashed, the rope that does not stretch: ${cliOutcome(['--example', '1'])}.`);
      assert.match(page.url(), /compare=rigid%3A/);
      page = await open('#machine=konstanz&friction.sandbag=0.3&compare=frictionless:');
      await idle(page);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', 'konstanz', '--set', 'friction.sandbag=0.3'])}.`);
      assert.equal(await page.textContent('#compare-outcome'), `Dashed, no friction: ${cliOutcome(['--example', 'konstanz'])}.`);
      // A machine without friction says so instead of comparing it with itself.
      page = await open('#machine=example1&compare=frictionless:');
      await idle(page);
      assert.match(await page.textContent('#compare-outcome'), /^This machine has no friction/);
    });
  },

  // The drawing as `whatnext animate` draws it: a slack rope never hangs through the closed lid
  // into the box (it lies on the lid and hangs from the hinge); a sandbag far out is an arrow with
  // its distance in the caption, not over the machine; a window too short for the picture still
  // gets one (it used to stop the page with a negative radius).
  async drawing() {
    const kRope = [51, 42, 51], kBagText = [153, 85, 0];  // web/src/machine.js, as the animation
    await withPage(async (page) => {
      // Example 1 at the start: the rope is slack by 0.4 m, the lid closed at 5 degrees.
      await scrubTo(page, 0);
      const m = await page.evaluate(() => window.whatnext.run.machine);
      assert.equal(await page.evaluate(() => window.whatnext.stateAt(0).rope_taut), 0);
      const rl = m.lid_half_length, ground = m.hinge.h - 2 * rl;
      // The box's inside, well clear of its walls and of the lid (which rises to the right).
      const a = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [m.hinge.x + 0.03, m.hinge.h - 0.03]);
      const b = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [m.hinge.x + 2 * rl - 0.03, ground + 0.03]);
      const inside = await page.evaluate(([x0, y0, x1, y1]) => {
        const c = document.getElementById('machine');
        return [...c.getContext('2d').getImageData(x0, y0, x1 - x0, y1 - y0).data];
      }, [a.x, a.y, b.x, b.y].map(Math.round));
      let rope = 0;
      for (let i = 0; i < inside.length; i += 4) if (near(inside.slice(i, i + 3), kRope, 30)) ++rope;
      assert.ok(inside.length > 4000, 'the box is on the canvas');
      assert.equal(rope, 0, 'rope-coloured pixels inside the closed box');

      // Example 3 after 10 s: the sandbag is hundreds of metres out (the CLI's CSV says how far).
      const captionHas = async (colour) => page.evaluate(([rgb]) => {
        const c = document.getElementById('machine'), band = c.getContext('2d').getImageData(0, 0, c.width, 40).data;
        for (let i = 0; i < band.length; i += 4) {
          if (Math.abs(band[i] - rgb[0]) + Math.abs(band[i + 1] - rgb[1]) + Math.abs(band[i + 2] - rgb[2]) < 30) return true;
        }
        return false;
      }, [colour]);
      assert.equal(await captionHas(kBagText), false, 'no distance while the sandbag is in the picture');
      const before = await runs(page);
      await page.selectOption('#preset', 'example3');
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
      await scrubTo(page, 10);
      const far = await page.evaluate(() => { const s = window.whatnext.stateAt(10); return Math.hypot(s.x, s.h); });
      assert.ok(far > 100, `the sandbag is ${far} m out`);
      assert.ok(await captionHas(kBagText), 'the distance of a sandbag far out is in the caption');
      assert.ok(await edgeHas(page, kSandbagColour), 'an arrow at the edge points to the sandbag');
    }, { scale: 1 });
    // The picture frames the machine: a balloon on a 3 m string rises out of it at the end; an
    // arrow at the top edge points to it and the caption says how high it is (as for the sandbag,
    // which has fallen off the seesaw by then).
    await withPage(async (page) => {
      await scrubTo(page, 1.6);
      const up = await page.evaluate(() => window.whatnext.stateAt(1.6).balloon_h);
      assert.ok(up > 2, `the balloon is ${up} m above the box`);
      assert.ok(await edgeHas(page, kBalloonColour), 'an arrow at the edge points to the balloon');
      const caption = await page.evaluate(() => window.whatnext.caption);
      assert.match(caption, /balloon \d\.\d+ m up/);
    }, { scale: 1, hash: '#machine=radio&radio.string_length=3' });
    // A window a hundred pixels high.
    await withPage(async (page) => {
      const box = await page.locator('#machine').boundingBox();
      assert.ok(box.height >= 180, `the drawing is ${box.height} px high`);
      assert.match(await outcomeText(page), /^Outcome: lid open at 0\.820 s\.$/);
    }, { viewport: { width: 800, height: 100 } });
  },

  // With the radio the lid latches at lid_open and the rope is let go for good; a heavy seesaw
  // swings on and carries its end farther from the lid's edge than the rope reaches (example 2
  // with a 0.4 kg seesaw and a 1.2 m arm, opened from its link). After the latch the rope is never
  // drawn longer than itself: it hangs from the lid's edge, and the line from the seesaw's end to
  // the lid's edge is not drawn. Once off the seesaw it stays off. Before the latch, and in example
  // 1 throughout, the rope is drawn as long as it is at every sample.
  async rope_let_go() {
    const changes = ['seesaw.mass=0.4', 'radio.enabled=true', 'seesaw.left_arm=1.2', 'damping.pivot=0.5'];
    await withPage(async (page) => {
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '2', ...sets(changes)])}.`);
      const latch = await page.evaluate(() => window.whatnext.run.events.find((e) => e.type === 'lid_open').t);
      assert.ok(Math.abs(latch - cliEvents(['--example', '2', ...sets(changes)]).events.find((e) => e.type === 'lid_open').t) < 1e-9);
      // The rope as the page draws it, at every sample and halfway between them.
      const lengths = await page.evaluate((tLatch) => {
        const M = window.whatnextMachine, run = window.whatnext.run, m = run.machine, ts = run.samples.t;
        const len = (pts) => pts.slice(1).reduce((sum, p, i) => sum + Math.hypot(p.x - pts[i].x, p.h - pts[i].h), 0);
        const out = { longest: 0, before: 0, hanging: 0, widest: 0, badHanging: [] };
        for (let i = 0; i < ts.length; ++i) {
          for (const t of [ts[i], i + 1 < ts.length ? 0.5 * (ts[i] + ts[i + 1]) : ts[i]]) {
            const s = M.stateAt(run.samples, t), path = M.ropePath(run, s), l = len(path);
            const r = { x: m.seesaw_right_arm * Math.cos(s.phi_s), h: m.seesaw_right_arm * Math.sin(s.phi_s) };
            const e = { x: m.hinge.x + 2 * m.lid_half_length * Math.cos(s.phi_l), h: m.hinge.h + 2 * m.lid_half_length * Math.sin(s.phi_l) };
            const span = Math.hypot(r.x - e.x, r.h - e.h);
            // Before the latch the ends are the model's (states between samples are interpolated).
            if (t <= tLatch && t === ts[i]) out.before = Math.max(out.before, Math.abs(l - m.rope_length));
            if (t < tLatch) continue;
            out.longest = Math.max(out.longest, l - m.rope_length);
            out.widest = Math.max(out.widest, span);
            if (span > m.rope_length + 1e-6) {
              out.hanging += 1;
              const off = path[0].x !== e.x || path[0].h !== e.h || Math.abs(l - m.rope_length) > 1e-9 ||
                          path.some((p) => Math.hypot(p.x - r.x, p.h - r.h) < 0.3);
              if (off) out.badHanging.push(t);
            }
          }
        }
        // Off for good: a later state with the seesaw swung back a little beyond its angle at the
        // latch, its end nearer the lid's edge than the rope is long.
        const back = { ...M.stateAt(run.samples, tLatch + 0.2), phi_s: M.stateAt(run.samples, tLatch).phi_s - 0.1 };
        out.backSpan = Math.hypot(m.seesaw_right_arm * Math.cos(back.phi_s) - m.hinge.x - 2 * m.lid_half_length * Math.cos(back.phi_l),
                                  m.seesaw_right_arm * Math.sin(back.phi_s) - m.hinge.h - 2 * m.lid_half_length * Math.sin(back.phi_l));
        out.backStart = M.ropePath(run, back)[0];
        out.edge = M.ropePath(run, M.stateAt(run.samples, tLatch + 0.2))[0];
        return out;
      }, latch);
      assert.ok(lengths.longest <= 1e-9, `after the latch the rope drawn ${lengths.longest} m longer than it is`);
      assert.ok(lengths.before <= 1e-9, `before the latch the rope drawn ${lengths.before} m off its length`);
      assert.ok(lengths.widest > 0.87, `the seesaw's end ${lengths.widest} m from the lid's edge at most`);
      assert.ok(lengths.hanging > 100, `${lengths.hanging} states with the rope let go`);
      assert.deepEqual(lengths.badHanging, [], 'let go, the rope hangs from the lid, all of it, clear of the seesaw');
      assert.ok(lengths.backSpan < 0.61, `swung back, the seesaw's end is ${lengths.backSpan} m from the lid's edge`);
      assert.deepEqual(lengths.backStart, lengths.edge, 'once let go the rope stays off the seesaw');

      // The picture 0.15 s after the latch: no rope on the line from the seesaw's end to the lid's
      // edge, the rope under the lid's edge.
      await scrubTo(page, Number((latch + 0.15).toFixed(3)));
      const s = await page.evaluate(() => window.whatnext.stateAt(window.whatnext.time));
      const m = await page.evaluate(() => window.whatnext.run.machine);
      const r = { x: m.seesaw_right_arm * Math.cos(s.phi_s), h: m.seesaw_right_arm * Math.sin(s.phi_s) };
      const e = { x: m.hinge.x + 2 * m.lid_half_length * Math.cos(s.phi_l), h: m.hinge.h + 2 * m.lid_half_length * Math.sin(s.phi_l) };
      fs.mkdirSync(outDir, { recursive: true });
      await page.locator('#machine').screenshot({ path: path.join(outDir, 'web-rope-let-go.png') });
      // The rope is drawn dark; the lid, walls and seesaw are not. It hangs a few millimetres from
      // the lid and the box's wall: a pixel either side is looked at too.
      const dark = (c) => c.every((v) => v < 120);
      const darkNear = async (p) => {
        const q = await page.evaluate(([x, h]) => window.whatnext.canvasPixel(x, h), [p.x, p.h]);
        for (const dx of [-1, 0, 1]) if (dark(await canvasColour(page, q.x + dx, q.y))) return true;
        return false;
      };
      let onChord = 0;
      for (let k = 20; k <= 80; k += 2) onChord += await darkNear({ x: r.x + k / 100 * (e.x - r.x), h: r.h + k / 100 * (e.h - r.h) });
      assert.equal(onChord, 0, 'rope-dark pixels on the line from the seesaw\'s end to the lid\'s edge');
      for (const below of [0.1, 0.3, 0.5]) assert.ok(await darkNear({ x: e.x, h: e.h - below }), `rope ${below} m below the lid's edge`);

      // Example 1 (no radio): the rope is drawn as long as it is, all through the run.
      const before = await runs(page);
      await page.selectOption('#preset', 'example1');
      await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
      const [off, straight] = await page.evaluate(() => {
        const M = window.whatnextMachine, run = window.whatnext.run;
        let worst = 0;
        const straightToLid = [];
        for (const t of run.samples.t) {
          const pts = M.ropePath(run, M.stateAt(run.samples, t));
          const l = pts.slice(1).reduce((sum, p, i) => sum + Math.hypot(p.x - pts[i].x, p.h - pts[i].h), 0);
          worst = Math.max(worst, Math.abs(l - run.machine.rope_length));
          // Three points: straight from the seesaw to a point on the lid, then along it (the slack
          // rope as if it hung into the box). Example 1's rope never does: from 0.6 s on, with the
          // lid high and 0.26 m to spare, it hangs free (it was drawn so at 0.767-0.809 s).
          if (t > 0.6 && pts.length === 3) straightToLid.push(t);
        }
        return [worst, straightToLid];
      });
      assert.ok(off <= 1e-9, `example 1's rope drawn ${off} m off its length`);
      assert.deepEqual(straight, [], 'example 1\'s slack rope drawn straight to the lid and along it');
    }, { hash: `#machine=example2&${changes.join('&')}`, scale: 2 });
  },

  // A change is shown at once without the browser laying out the page in between, and the link
  // follows it without being rewritten at every step of a slider (browsers limit how often a page
  // may rewrite its address; Safari throws after 100 times in 30 s); a link pasted into the tab
  // opens its machine.
  async changes() {
    await withPage(async (page) => {
      const cdp = await page.context().newCDPSession(page);
      await cdp.send('Performance.enable');
      const layouts = async () => (await cdp.send('Performance.getMetrics')).metrics.find((m) => m.name === 'LayoutCount').value;
      await page.evaluate(() => {
        const real = history.replaceState.bind(history);
        window.linkWrites = 0;
        history.replaceState = (...args) => { window.linkWrites += 1; return real(...args); };
      });
      const before = await runs(page), layoutsBefore = await layouts();
      // A slider dragged over 60 positions in one go, as fast as the events come. The worker runs
      // them one after the other; positions that come while one runs are overtaken by the newest,
      // so fewer runs than positions, and the last one shown.
      const t0 = Date.now();
      const last = await page.evaluate(() => {
        const slider = document.querySelector('[data-key="geometry.rope_length"] input.slider');
        for (let p = 400; p < 460; ++p) {
          slider.value = String(p);
          slider.dispatchEvent(new Event('input', { bubbles: true }));
        }
        return document.getElementById('field-geometry-rope_length').value;
      });
      await idle(page);
      const ms = Date.now() - t0;
      const shown = (await runs(page)) - before;
      assert.ok(shown >= 1 && shown < 60, `${shown} runs shown for 60 positions`);
      assert.equal(await page.evaluate(() => window.whatnext.run.machine.rope_length), Number(last), 'the last position is shown');
      const laidOut = (await layouts()) - layoutsBefore;
      assert.ok(laidOut <= 5 + 2 * shown, `${laidOut} layouts for ${shown} runs shown`);
      const writes = await page.evaluate(() => window.linkWrites);
      assert.ok(writes <= 1 + Math.ceil(ms / 250), `the link was written ${writes} times in ${ms} ms`);
      await page.evaluate(() => {
        document.querySelector('[data-key="geometry.rope_length"] input.slider').dispatchEvent(new Event('change', { bubbles: true }));
      });
      await idle(page);
      assert.equal(new URL(page.url()).hash, `#machine=example1&geometry.rope_length=${last}`);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', `geometry.rope_length=${last}`])}.`);

      // One key typed rewrites its own field, not the panel's 36 (each write costs the browser).
      const touched = await page.evaluate(() => new Promise((resolve) => {
        const records = [];
        const observer = new MutationObserver((list) => records.push(...list));
        observer.observe(document.getElementById('fields'), { attributes: true, subtree: true, childList: true });
        const input = document.getElementById('field-masses-lid');
        input.value = '0.45';
        input.dispatchEvent(new Event('input', { bubbles: true }));
        const done = setInterval(() => {  // once the run in the worker is shown
          if (document.body.dataset.busy !== 'false') return;
          clearInterval(done);
          observer.disconnect();
          // A field's own key; its section's summary (how many values changed) and the section.
          const owner = (r) => {
            const el = r.target.nodeType === 1 ? r.target : r.target.parentElement;
            const field = el.closest('[data-key]');
            return field ? field.dataset.key : el.closest('summary') ? 'summary' : el.matches('details') ? 'section' : el.tagName;
          };
          resolve(new Set(records.map(owner).filter((k) => k !== 'summary' && k !== 'section')));
        }, 5);
      }).then((keys) => [...keys]));
      assert.ok(touched.length <= 2, `a change of masses.lid rewrote ${touched.join(', ')}`);

      // Another machine's link pasted into the address bar of this tab.
      await page.evaluate(() => { location.hash = 'machine=example2&masses.sandbag=1.1'; });
      await page.waitForFunction(() => document.body.dataset.ready && window.whatnext.run.label.startsWith('example 2'));
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '2', '--set', 'masses.sandbag=1.1'])}.`);
      assert.equal(await page.inputValue(fieldId('masses.sandbag')), '1.1');
    });
  },

  // Phone and projector: nothing wider than the window, the machine and the outcome in view; the
  // screenshots for the README (build/web-test/).
  async layout() {
    fs.mkdirSync(outDir, { recursive: true });
    for (const [name, viewport, scale] of [['phone-390', { width: 390, height: 844 }, 3], ['wide', { width: 1920, height: 1080 }, 1],
                                           ['small-projector', { width: 1280, height: 720 }, 1],
                                           ['desktop', { width: 1400, height: 900 }, 1], ['desktop-1366', { width: 1366, height: 768 }, 1]]) {
      await withPage(async (page) => {
        // The timeline's columns whole, even with example 3's sandbag 1929.5922 m out.
        const before = await runs(page);
        await page.selectOption('#preset', 'example3');
        await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
        await checkTimelineWhole(page, name);
        // ... also with the last event's row highlighted (bold digits used to cut the last column).
        await page.keyboard.press('End');
        await checkTimelineWhole(page, `${name}, the last event highlighted`);
        await page.keyboard.press('Home');
        await page.selectOption('#preset', 'example1');
        await idle(page);
        const fits = await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth);
        assert.ok(fits, `${name}: the page is wider than the window`);
        const box = await page.locator('#machine').boundingBox();
        const least = name === 'phone-390' ? viewport.width - 60 : 500;
        assert.ok(box.width >= least, `${name}: the drawing is ${box.width} px wide`);
        assert.ok(await page.locator('#outcome').isVisible());
        if (viewport.width >= 1366) {
          // A laptop's screen and larger: the drawing, the outcome with the timeline and the first
          // plot in view without scrolling (at 1366x768 the plots were below the fold).
          for (const part of ['#machine', '#outcome', '#timeline', '#plot-angles']) {
            const r = await page.locator(part).boundingBox();
            assert.ok(r.y >= 0 && r.y + r.height <= viewport.height, `${name}: ${part} ends at ${r.y + r.height} px`);
          }
        }
        await page.keyboard.press(']');
        await page.keyboard.press(']');
        if (name === 'desktop') {  // the README's picture: the two laws part after the hard pull
          await page.selectOption('#compare', 'law');
          await page.selectOption('#compare-law', 'kinetic-energy');
          await idle(page);
          await page.evaluate(() => window.whatnext.seek(0.6));
        }
        if (name === 'desktop-1366') {  // all four laws after the hard pull
          await page.selectOption('#compare', 'laws');
          await idle(page);
          await page.evaluate(() => window.whatnext.seek(0.7));
        }
        await page.waitForSelector('body[data-checked]');  // the sliders' red stretches drawn
        await page.screenshot({ path: path.join(outDir, `web-${name}.png`) });
      }, { viewport, scale });
    }
  },

  // The library runs in a worker: a link of a 10^7-step Euler run (the most a
  // fixed-step run may take) asks before it starts; run anyway, it shows its progress while the page still answers, and Stop
  // ends it; the page then shows the link's machine without its changes and says why. Declined,
  // the same.
  async worker() {
    const link = '#machine=example3&run.integrator=euler&run.step=1e-6&run.t_max=10&run.output_step=0.01';
    const plain = `Outcome: ${cliOutcome(['--example', '3'])}.`;
    await withPage(async (first, { open }) => {
      const page = await open(link, '#budget[open]');
      assert.match(await page.textContent('#budget-text'), /1\.0e\+7 steps of the euler method/);
      await page.click('#budget-run');
      await page.waitForSelector('#progress', { state: 'visible' });
      await page.waitForTimeout(500);
      // The page answers while the worker works: a round trip and a click on the help.
      const t0 = Date.now();
      await page.evaluate(() => document.title);
      assert.ok(Date.now() - t0 < 1000, `the page took ${Date.now() - t0} ms to answer`);
      assert.match(await page.textContent('#progress-text'), /Running… .*s so far\./);
      await page.click('#stop');
      await page.waitForSelector('body[data-ready]');
      await idle(page);
      assert.equal(await outcomeText(page), plain);
      const problem = await page.textContent('#problem');
      assert.ok(problem.includes('Stopped before the run was done'), problem);
      assert.ok(problem.includes('This is Example 3 without the link\'s changes.'), problem);
      assert.equal(await page.isVisible('#progress'), false);
      // The restarted worker runs the next change.
      await setFieldAndRun(page, 'geometry.rope_length', '0.9');
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '3', '--set', 'geometry.rope_length=0.9'])}.`);

      const declined = await open(link, '#budget[open]');
      await declined.click('#budget-cancel');
      await declined.waitForSelector('body[data-ready]');
      assert.equal(await outcomeText(declined), plain);
      assert.match(await declined.textContent('#problem'), /not started \(1\.0e\+7 steps\)/);
    });
  },

  // Every part of a link the page cannot use is named, and what can be used is shown: an unknown
  // machine, comparison and part; a file that is not base64; a key the library does not know (the
  // command line's message). A link holding a file of the command line's largest size (1 MiB)
  // opens; one beyond it is refused with its size.
  async links() {
    await withPage(async (first, { open }) => {
      let page = await open('#machine=example9&compare=law:bogus&foo=1&geometry.rope_length=0.9');
      let problem = await page.textContent('#problem');
      for (const part of ['machine=example9 is not one of', 'compare=law:bogus is not a comparison', 'part "foo" is not a key']) {
        assert.ok(problem.includes(part), `"${part}" in: ${problem}`);
      }
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', 'geometry.rope_length=0.9'])}.`);
      page = await open('#file=a.toml&text=not*base64');
      assert.match(await page.textContent('#problem'), /The link's file \(text=\) cannot be read: it holds characters that are not URL-safe base64\./);
      page = await open('#file=a.toml&text=QUJD_');  // five characters: no whole byte at the end
      assert.match(await page.textContent('#problem'), /The link's file \(text=\) cannot be read: /);
      page = await open('#machine=example2&geometry.rope_lenght=1');
      // The command line's message without its "--set: " (the page's words).
      const message = cliError(['--example', '2', '--set', 'geometry.rope_lenght=1']).replace(/^--set: /, '');
      assert.match(message, /^unknown key/);
      problem = await page.textContent('#problem');
      assert.ok(problem.includes(message), `${message} in: ${problem}`);
      assert.ok(problem.includes('This is Example 2 without the link\'s changes.'), problem);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '2'])}.`);

      // 1 MiB less a little: example 1 and comment lines.
      const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-big-'));
      try {
        const example = fs.readFileSync(path.join(sourceDir, 'examples/example1.toml'), 'utf8');
        const filler = `# ${'ä'.repeat(60)}\n`;
        let text = example;
        while (Buffer.byteLength(text) + Buffer.byteLength(filler) <= (1 << 20)) text += filler;
        const file = path.join(dir, 'big.toml');
        fs.writeFileSync(file, text);
        const b64 = (t) => Buffer.from(t).toString('base64url');
        page = await open(`#file=big.toml&text=${b64(text)}`);
        assert.equal(await page.isVisible('#problem'), false);
        assert.equal(await outcomeText(page), `Outcome: ${cliOutcome([file])}.`);
        // The page writes the same link back (the file's text in slices of base64).
        assert.equal(new URL(page.url()).hash, `#file=big.toml&text=${b64(text)}`);
        page = await open(`#file=big.toml&text=${b64(text + filler)}`);
        assert.match(await page.textContent('#problem'), /cannot be read: it holds \d+ bytes, more than the 1048576/);
      } finally {
        fs.rmSync(dir, { recursive: true, force: true });
      }
    });
  },

  // The page in one file (build/web/whatnext.html) opened from the disk: it runs, plays and
  // changes with nothing fetched but itself; index.html from the disk says to use it.
  async single_file() {
    const file = path.join(webDir, 'whatnext.html');
    const html = fs.readFileSync(file, 'utf8');
    // The tags themselves: the inlined scripts' text is code (qrcode.js builds "<img src=" strings).
    const tags = html.replace(/(<(script|style)\b[^>]*>)[\s\S]*?<\/\2>/g, '$1');
    assert.doesNotMatch(tags, /<(script|link|img)[^>]+(src|href)="(?!data:)/, 'whatnext.html loads another file');
    const url = `file://${file}`;
    await withPage(async (page) => {
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1'])}.`);
      await setFieldAndRun(page, 'geometry.rope_length', '0.95');
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', 'geometry.rope_length=0.95'])}.`);
      // The key steps to the next event once the page is idle with its run (on a loaded machine the
      // run that the change started may still be settling when the first press comes).
      await idle(page);
      await page.evaluate(() => document.activeElement && document.activeElement.blur());
      for (let i = 0; i < 20 && !(await page.evaluate(() => window.whatnext.time) > 0); i++) {
        await page.keyboard.press(']');
        await page.waitForTimeout(100);
      }
      assert.ok(await page.evaluate(() => window.whatnext.time) > 0);
      assert.ok(page.url().startsWith(url + '#machine=example1&geometry.rope_length=0.95'), `${page.url()} ${await page.textContent('#problem')}`);
    }, { base: url });
    await withPage(async (page) => {
      assert.match(await outcomeText(page), /use whatnext\.html/);
    }, { base: `file://${webDir}/`, hash: 'index.html', ready: 'body[data-failed]' });
  },

  // ./run.sh web (web/serve.py): on this computer only unless --lan; with --lan the page is
  // reached at the printed address (with its QR code), and "Copy link" copies that address.
  async lan() {
    const { spawn } = require('child_process');
    const net = require('net');
    const freePort = () => new Promise((resolve) => {
      const s = net.createServer().listen(0, '127.0.0.1', () => { const p = s.address().port; s.close(() => resolve(p)); });
    });
    const reaches = (host, port) => new Promise((resolve) => {
      const c = net.connect({ host, port, timeout: 2000 }, () => { c.destroy(); resolve(true); });
      c.on('error', () => resolve(false));
      c.on('timeout', () => { c.destroy(); resolve(false); });
    });
    // A port found free may be taken by another process (a test running beside this one) before
    // the server binds it: then the server exits, and another free port is tried.
    const start = async (args) => {
      for (let attempt = 0; ; ++attempt) {
        const port = await freePort();
        const p = spawn('/usr/bin/python3', [path.join(sourceDir, 'web/serve.py'), webDir, ...args, '--port', String(port)]);
        let out = '', exited = false;
        p.stdout.on('data', (d) => { out += d; });
        p.on('exit', () => { exited = true; });
        // Served once its last line is out (with --lan the QR code comes after "Ctrl-C").
        const ready = args.includes('--lan') ? /whatnext\.html/ : /Ctrl-C/;
        for (let i = 0; i < 100 && !ready.test(out) && !exited; ++i) await new Promise((r) => setTimeout(r, 50));
        if (ready.test(out) || attempt >= 4) return { p, port, out: () => out };
        p.kill();
      }
    };
    // The address other machines reach this one by, as the server finds it.
    const lanHost = Object.values(os.networkInterfaces()).flat().find((a) => a.family === 'IPv4' && !a.internal);
    const local = await start([]);
    try {
      assert.match(local.out(), /the page is at http:\/\/localhost:\d+\//);
      assert.ok(await reaches('127.0.0.1', local.port));
      if (lanHost) assert.equal(await reaches(lanHost.address, local.port), false, 'without --lan only localhost');
    } finally {
      local.p.kill();
    }
    const bad = spawnSync('/usr/bin/python3', [path.join(sourceDir, 'web/serve.py'), webDir, '--lna'], { encoding: 'utf8' });
    assert.notEqual(bad.status, 0);
    assert.match(bad.stderr, /takes --lan and --port N, not '--lna'/);
    const lan = await start(['--lan']);
    try {
      const m = lan.out().match(/served to the local network at (http:\/\/[\d.]+:\d+\/)/);
      assert.ok(m, lan.out());
      assert.match(lan.out(), /█/, 'a QR code');
      if (!lanHost) return;  // a machine on no network: nothing more to reach
      assert.equal(m[1], `http://${lanHost.address}:${lan.port}/`);
      await withPage(async (page) => {
        assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1'])}.`);
        await menuClick(page, '#share');
        // Not secure (http on a LAN address): no clipboard API; the page copies all the same.
        await page.waitForSelector('.toast');
        assert.equal(await page.textContent('.toast code'), `${m[1]}#machine=example1`);
        assert.doesNotMatch(await page.textContent('.toast'), /this computer only/);
      }, { base: m[1] });
    } finally {
      lan.p.kill();
    }
  },

  // Konstanz's latch is an impact: at lid_open the timeline's row has the command line's energy
  // line (the lid's angular impulse in N m s), the energy it takes is what the ledger's
  // lost_impacts gains there, the rope's release follows at the same instant, and reaching it
  // plays the impact's click, says it to screen readers and flashes the latch's impulse: the
  // lid's angular impulse about its hinge as an impulse at its edge, 2 r_L from it.
  async latch() {
    const base = ['--example', 'konstanz'];
    const expected = cliTimeline(cli('run', ...base).stdout).rows;
    const cliRow = expected.find((r) => r[1] === 'lid_open');
    assert.ok(cliRow && cliRow.length > 6 && cliRow[6] === 'energy', `the command line's latch: ${cliRow}`);
    const events = cliEvents(base).events;
    const k = events.findIndex((e) => e.type === 'lid_open');
    const latch = events[k];
    assert.equal(events[k + 1].type, 'rope_slack');
    assert.equal(events[k + 1].t, latch.t);
    assert.ok(Math.abs((latch.energy_before - latch.energy_after) - (latch.ledger.lost_impacts - events[k - 1].ledger.lost_impacts)) < 1e-9,
              'the latch names the energy the ledger loses there');
    await withPage(async (page) => {
      const row = (await pageTimeline(page)).find((r) => r[1] === 'lid_open');
      assert.deepEqual(row, cliRow, 'the latch\'s row and its energy line as the command line prints them');
      const shown = await page.evaluate(() => window.whatnext.run.events.find((e) => e.type === 'lid_open'));
      assert.equal(shown.impact, true);
      assert.ok(Math.abs(shown.energy_after - latch.energy_after) < 1e-9 && Math.abs(shown.impulses.lid_N_m_s - latch.impulses.lid_N_m_s) < 1e-9);
      // ] from just before it: a key is a gesture, so the click plays.
      // (WebAssembly's times agree with the native build's to rounding, not to the bit.)
      await page.evaluate((t) => window.whatnext.seek(t - 0.005), shown.t);
      await page.keyboard.press('v');
      await page.keyboard.press(']');
      assert.equal(await page.evaluate(() => window.whatnext.time), shown.t);
      const heard = await page.evaluate(() => window.whatnext.sounds.map((x) => `${x.kind}: ${x.what}`));
      assert.equal(heard[heard.length - 1], 'impact: played', heard.join('; '));
      assert.match(await page.textContent('#announce'), /lid open \(impact, 3\.21 J -> -0\.68 J\) \+ rope slack/);
      const flash = await page.evaluate(() => window.whatnext.forces);
      const m = await page.evaluate(() => window.whatnext.run.machine);
      const arrow = flash.arrows.find((a) => a.what === 'impulse_latch_on_lid');
      assert.ok(arrow && arrow.unit === 'N s', `the latch's impulse flashes: ${JSON.stringify(flash.arrows)}`);
      const atEdge = latch.impulses.lid_N_m_s / (2 * m.lid_half_length);
      assert.ok(Math.abs(arrow.value - atEdge) <= 1e-9 * atEdge, `${arrow.value} N s, not ${atEdge}`);
      assert.match(await page.textContent('#force-scale'), /impulse of the latch on the lid \(at its edge\)/);
      fs.mkdirSync(outDir, { recursive: true });
      await page.screenshot({ path: path.join(outDir, 'web-latch.png') });
    }, { hash: '#machine=konstanz', viewport: { width: 1400, height: 900 } });
  },

  // prefers-reduced-motion: the page knows it, plays nothing by itself, holds each event's frame
  // twice as long (2 s, not 1 s) and scrolls to the "why" at once, not smoothly.
  async reduced_motion() {
    await withPage(async (page) => {
      assert.equal(await page.evaluate(() => matchMedia('(prefers-reduced-motion: reduce)').matches), true);
      await page.waitForTimeout(500);
      assert.equal(await page.evaluate(() => window.whatnext.time), 0, 'nothing plays by itself');
      const first = await page.evaluate(() => window.whatnext.run.groups[0].t);
      // How long playback stays on the first event's frame (measured at each animation frame).
      const held = await page.evaluate((t) => new Promise((done) => {
        let since = null;
        const look = (now) => {
          const at = window.whatnext.time;
          if (since === null && at === t) since = now;
          if (since !== null && at !== t) return done(now - since);
          requestAnimationFrame(look);
        };
        window.whatnext.seek(t - 0.002);
        window.whatnext.play();
        requestAnimationFrame(look);
      }), first);
      assert.ok(held >= 1900, `the event's frame held ${held} ms`);
      // "Why?" in the timeline: the page is at the "why" as soon as it is asked, and stays there.
      const tops = await page.evaluate(() => new Promise((done) => {
        document.querySelector('#timeline .why-link').click();
        const now = document.getElementById('why').getBoundingClientRect().top;
        setTimeout(() => done([now, document.getElementById('why').getBoundingClientRect().top]), 800);
      }));
      assert.ok(Math.abs(tops[0] - tops[1]) < 1, `the "why" at ${tops[0]} px, then at ${tops[1]} px: scrolled smoothly`);
    }, { hash: '#machine=example1', reducedMotion: 'reduce' });
  },

  // Sound: nothing before the user's first gesture (a play started by the page's own code is
  // silent), then a click at each impact and the tune when the radio comes on; muted, nothing.
  async sound() {
    await withPage(async (page) => {
      const sounds = () => page.evaluate(() => window.whatnext.sounds.map((x) => `${x.kind}: ${x.what}`));
      const radioAt = await page.evaluate(() => window.whatnext.run.events.find((e) => e.type === 'radio_on').t);
      const impactAt = await page.evaluate(() => window.whatnext.run.events.find((e) => e.impact).t);
      // No gesture yet: the page plays through the first impact on its own.
      await page.evaluate((t) => { window.whatnext.seek(t - 0.01); window.whatnext.play(); }, impactAt);
      await page.waitForFunction(() => window.whatnext.sounds.length > 0, null, { timeout: 10000 });
      assert.deepEqual(await sounds(), ['impact: before any gesture: silent']);
      assert.equal(await page.evaluate(() => document.body.dataset.sounds), '0');
      // A key is a gesture: ] goes to the next event, Space plays through the radio's switch.
      await page.evaluate((t) => window.whatnext.seek(t - 0.01), impactAt);
      await page.keyboard.press(']');
      await page.evaluate((t) => window.whatnext.seek(t - 0.01), radioAt);
      await page.keyboard.press('Space');
      await page.waitForFunction(() => window.whatnext.sounds.some((x) => x.kind === 'radio'), null, { timeout: 10000 });
      const heard = await sounds();
      assert.equal(heard[1], 'impact: played', heard.join('; '));
      assert.equal(heard[heard.length - 1], 'radio: played', heard.join('; '));
      // Muted with the button: the next event is logged as muted, not played.
      await page.click('#sound');
      assert.equal(await page.getAttribute('#sound', 'aria-pressed'), 'false');
      await page.evaluate((t) => window.whatnext.seek(t - 0.01), impactAt);
      await page.keyboard.press(']');
      assert.equal((await sounds()).pop(), 'impact: muted');
    }, { hash: '#machine=radio' });
  },

  // Projector mode (F, or the button): the drawing takes most of a 1920x1080 screen beside the
  // timeline, in big type; Space plays, PageDown/PageUp step through the events (a presenter's
  // remote), and the highlighted row's columns are whole. At 1920x1080 and 1280x720 the machine
  // itself (the pivot's stand to the radio, the floor to the sandbag's start) fills a good part of
  // the screen: the picture frames the machine, not everything the run reaches (before, example
  // 1's machine was a fifth of the width and a third of the height).
  async projector() {
    fs.mkdirSync(outDir, { recursive: true });
    for (const viewport of [{ width: 1920, height: 1080 }, { width: 1366, height: 768 }, { width: 1280, height: 720 }]) {
      const name = `${viewport.width}x${viewport.height}`;
      await withPage(async (page) => {
        await page.keyboard.press('f');
        assert.ok(await page.evaluate(() => document.body.classList.contains('projector')));
        await page.waitForTimeout(300);
        const box = await page.locator('#machine').boundingBox();
        assert.ok(box.width >= 0.55 * viewport.width, `${name}: the drawing is ${box.width} px wide`);
        assert.ok(box.height >= 0.6 * viewport.height, `${name}: the drawing is ${box.height} px high`);
        // The player under the drawing is on the screen too.
        const player = await page.locator('#scrubber').boundingBox();
        assert.ok(player.y + player.height <= viewport.height, `${name}: the scrubber ends at ${player.y + player.height} px`);
        const machine = await page.evaluate(() => {
          const m = window.whatnext.run.machine, floor = m.hinge.h - 2 * m.lid_half_length;
          const radio = m.radio_switch.x + 0.18 * Math.max(0.5, 2 * m.lid_half_length);  // machine.js radioBox
          const px = (x, h) => window.whatnext.canvasPixel(x, h);
          return { width: px(radio, floor).x - px(-0.15, floor).x, height: px(0, floor).y - px(0, m.start.sandbag_h).y };
        });
        assert.ok(machine.width >= 0.3 * viewport.width, `${name}: the machine is ${machine.width} px wide`);
        assert.ok(machine.height >= 0.5 * viewport.height, `${name}: the machine is ${machine.height} px high`);
        console.log(`${name}: the machine ${Math.round(machine.width)} x ${Math.round(machine.height)} px`);
        const type = await page.evaluate(() => parseFloat(getComputedStyle(document.body).fontSize));
        assert.ok(type >= (viewport.width >= 1920 ? 22 : 18), `${name}: type of ${type} px`);
        const events = cliEvents(['--example', '1']).events;
        await page.keyboard.press('Space');
        await page.waitForTimeout(300);
        await page.keyboard.press('Space');
        assert.ok(await page.evaluate(() => window.whatnext.time) > 0, 'Space played');
        await page.keyboard.press('PageDown');
        await page.keyboard.press('PageDown');
        assert.ok(Math.abs(await page.evaluate(() => window.whatnext.time) - events[1].t) < 1e-9);
        await page.keyboard.press('PageUp');
        assert.ok(Math.abs(await page.evaluate(() => window.whatnext.time) - events[0].t) < 1e-9);
        assert.ok(await page.locator('#timeline tr.now').isVisible());
        await checkTimelineWhole(page, `projector ${name}`);
        if (viewport.width >= 1366) {
          // What teaches, in view together: the machine, the outcome, the timeline, the energy plot
          // and the comparison's choice.
          for (const part of ['#machine', '#outcome', '#timeline', '#plot-energy', '#compare', '#plot-choice']) {
            const r = await page.locator(part).boundingBox();
            assert.ok(r && r.y >= 0 && r.y + r.height <= viewport.height && r.x + r.width <= viewport.width, `${name}: ${part} is out of view (${JSON.stringify(r)})`);
          }
          // Legible from the back: the timeline's text at 16 px and more; past events at 4.5:1.
          await page.keyboard.press('End');
          const type = await page.$$eval('#timeline td', (tds) => Math.min(...tds.filter((td) => td.offsetParent).map((td) => parseFloat(getComputedStyle(td).fontSize))));
          assert.ok(type >= 16, `${name}: timeline text of ${type} px`);
          const contrast = await page.$$eval('#timeline tr.past td', (tds) => {
            const lum = (c) => {
              const [r, g, b] = c.match(/\d+/g).slice(0, 3).map(Number).map((v) => { v /= 255; return v <= 0.03928 ? v / 12.92 : ((v + 0.055) / 1.055) ** 2.4; });
              return 0.2126 * r + 0.7152 * g + 0.0722 * b;
            };
            return Math.min(...tds.map((td) => (1.05) / (lum(getComputedStyle(td).color) + 0.05)));
          });
          assert.ok(contrast >= 4.5, `${name}: past events at ${contrast.toFixed(2)}:1`);
          // Another plot instead of the energy plot.
          await page.selectOption('#plot-choice', 'plot-angles');
          assert.ok(await page.locator('#plot-angles').isVisible());
          assert.equal(await page.locator('#plot-energy').isVisible(), false);
          await page.selectOption('#plot-choice', 'plot-energy');
          await page.evaluate(() => document.activeElement.blur());
          await page.keyboard.press('Home');
          await page.keyboard.press('PageDown');
          await page.keyboard.press('PageDown');
        }
        await page.waitForSelector('body[data-checked]');  // the sliders' red stretches drawn
        await page.screenshot({ path: path.join(outDir, viewport.width >= 1920 ? 'web-projector.png' : `web-projector-${name}.png`) });
        // Example 3's long run: the timeline's columns whole in projector mode too.
        const before = await runs(page);
        await page.selectOption('#preset', 'example3');
        await page.waitForFunction((n) => Number(document.body.dataset.runs) > n, before);
        await page.keyboard.press('End');
        await checkTimelineWhole(page, `projector ${name}, example 3 at its end`);
        await page.click('#projector');
        assert.equal(await page.evaluate(() => document.body.classList.contains('projector')), false);
      }, { viewport });
    }
  },

  // A phone upright (390x844) and on its side (740x360), and a tablet upright (768x1024), with a
  // touch screen: nothing is cut or wider than the screen; upright, the header is one row and the
  // physics comes first: the outcome, the drawing, the timeline (its top within 1.5 screen heights)
  // and the first plot above every parameter, whose sections start closed and say when changed.
  async phone() {
    fs.mkdirSync(outDir, { recursive: true });
    for (const [name, viewport] of [['phone', { width: 390, height: 844 }], ['phone-landscape', { width: 740, height: 360 }],
                                    ['tablet', { width: 768, height: 1024 }]]) {
      await withPage(async (page) => {
        const cut = await page.evaluate(() => {
          const out = [];
          for (const el of document.body.querySelectorAll('*')) {
            const r = el.getBoundingClientRect();
            if (!r.width || !r.height || el.closest('.table-box, dialog, .u-legend, pre, .visually-hidden, .brand') || getComputedStyle(el).visibility === 'hidden') continue;
            if (r.left < -0.5 || r.right > window.innerWidth + 0.5) out.push(`${el.tagName}#${el.id}.${el.className} ${r.left}-${r.right}`);
          }
          return out;
        });
        assert.deepEqual(cut, [], `${name}: cut at the sides`);
        assert.ok(await page.evaluate(() => document.documentElement.scrollWidth <= window.innerWidth), `${name}: wider than the screen`);
        const top = (sel) => page.evaluate((s) => document.querySelector(s).getBoundingClientRect().top + window.scrollY, sel);
        if (name !== 'phone-landscape') {
          const header = await page.locator('header.bar').boundingBox();
          const preset = await page.locator('#preset').boundingBox();
          assert.ok(header.height <= 56, `${name}: the header is ${header.height} px high (one row)`);
          assert.ok(preset.width >= 0.3 * viewport.width, `${name}: the machine's choice is ${preset.width} px wide`);
          // What the closed choice shows is whole: the machine's name, or on a phone its short name.
          for (const locale of ['de', 'en']) {  // English again for what follows
            await page.selectOption('#lang', locale);
            await page.waitForFunction((l) => document.documentElement.lang === l && document.body.dataset.ready, locale);
            const shown = await page.evaluate(() => {
              const face = document.getElementById('preset-face'), select = document.getElementById('preset');
              const el = face && getComputedStyle(face).display !== 'none' ? face : select;
              const text = el === face ? face.textContent : select.selectedOptions[0].text;
              const g = document.createElement('canvas').getContext('2d');
              g.font = getComputedStyle(el).font;
              const room = el === face ? face.clientWidth - parseFloat(getComputedStyle(face).paddingLeft)
                : select.clientWidth - parseFloat(getComputedStyle(select).paddingLeft) - 24;  // the select's arrow
              return { text, width: g.measureText(text).width, room };
            });
            assert.ok(shown.width <= shown.room, `${name} (${locale}): the machine's choice shows '${shown.text}' in ${shown.room} px, ${shown.width} px wide`);
          }
          const panel = await top('#panel');
          for (const part of ['#outcome', '#machine', '#timeline', '#plot-angles']) {
            assert.ok(await top(part) < panel, `${name}: ${part} is below the parameters`);
          }
          const timeline = await top('#timeline');
          assert.ok(timeline <= 1.5 * viewport.height, `${name}: the timeline starts at ${timeline} px`);
          console.log(`${name}: the timeline starts at ${Math.round(timeline)} px, the parameters at ${Math.round(panel)} px`);
          const open = await page.$$eval('#fields details.group', (ds) => ds.filter((d) => d.open).length);
          assert.equal(open, 0, `${name}: parameter sections open at the start`);
        }
        // A parameter changed: its section opened on demand says so, and the run is the CLI's.
        const field = fieldId('masses.lid');
        const section = await page.evaluate((f) => { const d = document.querySelector(f).closest('details'); d.open = true; return d.querySelector('summary').textContent; }, field);
        assert.doesNotMatch(section, /changed/);
        await page.locator(field).scrollIntoViewIfNeeded();
        await page.tap(field);
        await page.fill(field, '0.45');
        await page.press(field, 'Tab');
        await idle(page);
        assert.match(await page.evaluate((f) => document.querySelector(f).closest('details').querySelector('summary').textContent, field), /1 changed/);
        assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(['--example', '1', '--set', 'masses.lid=0.45'])}.`);
        const box = await page.locator('#machine').boundingBox();
        assert.ok(box.height >= 150, `${name}: the drawing is ${box.height} px high`);
        const text = await page.evaluate(() => document.body.innerText);
        assert.doesNotMatch(text, /Space|double-click|click one/, `${name}: a hint about keys or a mouse`);
        assert.equal(await page.isVisible('#help'), false);
        await page.evaluate(() => window.scrollTo(0, 0));
        await page.waitForSelector('body[data-checked]');  // the sliders' red stretches drawn
        await page.screenshot({ path: path.join(outDir, `web-${name}.png`) });
        if (name === 'phone') await page.screenshot({ path: path.join(outDir, 'web-phone-full.png'), fullPage: true });
      }, { viewport, scale: 2, touch: true });
    }
  },

  // Forces and velocities on the machine (V, or the button): the library's values, placed where
  // they act; at an impact its impulses instead, in N s.
  async forces() {
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-forces-'));
    const csvFile = path.join(dir, 'run.csv');
    assert.equal(cli('run', '--example', '2', '--csv', csvFile, '-q').status, 0);
    const lines = fs.readFileSync(csvFile, 'utf8').trim().split('\n');
    fs.rmSync(dir, { recursive: true, force: true });
    const head = lines[0].split(',');
    const rows = lines.slice(1).map((l) => l.split(','));
    const col = (row, name) => Number(row[head.indexOf(name)]);
    // A sample while the rope pulls the lid (mode M4, tension above zero).
    const pulling = rows.find((r) => r[head.indexOf('mode')] === 'M4' && col(r, 'tension_N') > 0.1);
    assert.ok(pulling, 'example 2 has a sample with the rope pulling');
    const events = cliEvents(['--example', '2']).events;
    const jerk = events.find((e) => e.type === 'rope_taut');
    await withPage(async (page) => {
      assert.equal(await page.getAttribute('#forces', 'aria-pressed'), 'false');
      assert.match(await page.textContent('#outcome'), /0\.550 s/);
      await page.keyboard.press('v');
      assert.equal(await page.getAttribute('#forces', 'aria-pressed'), 'true');
      const t = col(pulling, 't_s');
      await page.evaluate((x) => window.whatnext.seek(x), t);
      const drawn = await page.evaluate(() => window.whatnext.forces);
      const byName = Object.fromEntries(drawn.arrows.map((a) => [a.what, a]));
      const m = await page.evaluate(() => window.whatnext.run.machine);
      // Gravity: m g on each body.
      assert.ok(Math.abs(byName.weight_sandbag.value - m.sandbag_mass * m.gravity) < 1e-9);
      assert.ok(Math.abs(byName.weight_lid.value - m.lid_mass * m.gravity) < 1e-9);
      // The rope's tension as the command line writes it, on both ends.
      for (const end of ['tension_on_sandbag', 'tension_on_lid']) {
        assert.ok(Math.abs(byName[end].value - col(pulling, 'tension_N')) <= 1e-6 * col(pulling, 'tension_N'), `${end}: ${byName[end].value}`);
      }
      assert.ok(byName.arm_on_sandbag, 'the arm pushes the sandbag');
      // The lid's edge moves at the lid's angular speed times its length (2 r_L).
      const edge = Math.abs(col(pulling, 'dphi_l_deg_per_s')) * Math.PI / 180 * 2 * m.lid_half_length;
      assert.ok(Math.abs(byName.velocity_lid_edge.value - edge) <= 1e-6 * edge, `the lid's edge at ${byName.velocity_lid_edge.value} m/s, not ${edge}`);
      assert.ok(byName.velocity_sandbag);
      assert.match(await page.textContent('#force-scale'), /gravity on the sandbag/);
      // The jerk: its impulses (N s), the rope's as the events JSON gives it.
      // (Example 2: the taut rope pulls the lid open.)
      await page.evaluate((x) => window.whatnext.seek(x), jerk.t);
      const flash = await page.evaluate(() => window.whatnext.forces);
      const rope = flash.arrows.find((a) => a.what === 'impulse_rope_on_lid');
      assert.ok(rope && rope.unit === 'N s', 'the rope\'s impulse at the jerk');
      assert.ok(Math.abs(rope.value - jerk.impulses.rope_N_s) <= 1e-9 * jerk.impulses.rope_N_s);
      assert.ok(flash.arrows.every((a) => a.what.startsWith('impulse')));
      await page.screenshot({ path: path.join(outDir, 'web-forces-jerk.png') });
      await page.evaluate((x) => window.whatnext.seek(x), t);
      await page.screenshot({ path: path.join(outDir, 'web-forces.png') });
      await page.click('#forces');
      assert.equal(await page.evaluate(() => window.whatnext.forces), null);
      // Konstanz: the floor holds the seesaw and the stop the sandbag after the latch.
      await page.selectOption('#preset', 'konstanz');
      await idle(page);
      await page.keyboard.press('v');
      await page.keyboard.press('End');
      const end = await page.evaluate(() => window.whatnext.forces.arrows.map((a) => a.what));
      assert.ok(end.includes('floor_on_seesaw') || end.includes('stop_on_sandbag') || end.includes('floor_on_sandbag'), `konstanz at its end: ${end}`);
      await page.screenshot({ path: path.join(outDir, 'web-forces-konstanz.png') });
      // The mode's words fit the machine as built (the library's words, as the GIF's caption).
      assert.match(await page.evaluate(() => window.whatnext.caption), /M3: sandbag at the stop, seesaw on the floor, rope let go/);
    }, { viewport: { width: 1400, height: 900 }, hash: '#machine=example2' });
  },

  // The energy bars: the ledger at the time shown, adding up to the energy at the start (the
  // command line's initial_total) at every time; named for screen readers in both languages.
  async energy_bars() {
    await withPage(async (page) => {  // the built machine's mode in German words
      await page.keyboard.press('End');
      assert.match(await page.evaluate(() => window.whatnext.caption), /M3: Sandsack am Anschlag, Wippe auf dem Boden, Seil losgelassen/);
    }, { locale: 'de-DE', hash: '#machine=konstanz' });
    const events = cliEvents(['--example', '1']).events;
    const start = events[0].ledger.initial_total;
    await withPage(async (page) => {
      for (const t of [0, events[0].t, events[1].t, 0.6, events[events.length - 1].t]) {
        await page.evaluate((x) => window.whatnext.seek(x), t);
        const values = await page.$$eval('#bars .bar-value', (vs) => vs.map((v) => Number(v.textContent.replace(' J', ''))));
        const sum = values.reduce((a, b) => a + b, 0);
        assert.ok(Math.abs(sum - start) <= 0.0005 * values.length + 1e-9, `t = ${t}: the bars add up to ${sum}, not ${start}`);
        assert.match(await page.textContent('#bars .bar-total'), new RegExp(`= energy at the start ${start.toFixed(3)} J`));
      }
      // At the jerk, what the impacts lost so far is the command line's.
      await page.evaluate((x) => window.whatnext.seek(x), events[1].t);
      const label = await page.getAttribute('#bars', 'aria-label');
      assert.match(label, /^Energy bars: /);
      assert.match(label, new RegExp(`lost in impacts ${events[1].ledger.lost_impacts.toFixed(3)} J`));
      assert.match(await page.textContent('#bars-zero'), /pivot's height/);
      // The drawing is an image whose description follows the run; an event reached is announced.
      await page.evaluate(() => window.whatnext.seek(0));
      assert.equal(await page.getAttribute('#machine', 'role'), 'img');
      assert.match(await page.getAttribute('#machine', 'aria-label'), /no event yet/);
      await page.keyboard.press(']');
      assert.equal(await page.textContent('#announce'), `${events[0].t.toFixed(3)} s: sandbag lands`);
      assert.match(await page.getAttribute('#machine', 'aria-label'), /M3: sandbag on the seesaw, rope slack; last event at [\d.]+ s: sandbag lands/);
      assert.equal(await page.getAttribute('#announce', 'aria-live'), 'polite');
    });
    await withPage(async (page) => {
      assert.match(await page.getAttribute('#bars', 'aria-label'), /^Energiebalken: /);
      assert.match(await page.textContent('#energy-bars figcaption'), /^Energiebalken$/);
    }, { locale: 'de-DE' });
  },

  // The "why": reachable from the comparison and the timeline; the stiff rope's rebound e(ζ) at
  // the closed form's values (docs/impact.md), and the lid's speed after the jerk under the rope
  // law as the command line's events give it.
  async why() {
    const jerk = cliEvents(['--example', '1']).events.find((e) => e.type === 'rope_taut');
    await withPage(async (page) => {
      const e = await page.evaluate(() => [0, 0.1, 1, 10].map((z) => window.whatnextTeach.restitution(z)));
      assert.equal(e[0], 1);
      assert.ok(Math.abs(e[2] - Math.exp(-2)) < 1e-9, `e(1) = ${e[2]}`);
      assert.ok(Math.abs(e[1] - 0.744) < 0.0006, `e(0.1) = ${e[1]}`);
      assert.ok(Math.abs(e[3] - 0.0024) < 0.00006, `e(10) = ${e[3]}`);
      await page.click('#why-compare');
      await page.waitForSelector('#why[data-ready]');
      const rows = await page.$$eval('#zeta-table tr', (rs) => rs.map((r) => [...r.cells].map((c) => c.textContent)));
      const rope = rows.find((r) => r[0] === 'rope');
      assert.equal(rope[1], jerk.state.dphi_l_deg_per_s.toFixed(1));
      assert.equal(rows.length, 6);
      // The interactive: ζ chosen so that e = 0.5 is not on its steps; a step's e and the run agree
      // with a run of the command line at restitution.rope = e (here: the step nearest e = 0.5).
      await page.$eval('#zeta', (el) => { el.value = '2'; el.dispatchEvent(new Event('change')); });
      await page.waitForFunction(() => /0\.2/.test(document.getElementById('zeta-out').textContent));
      assert.match(await page.getAttribute('#zeta', 'aria-valuetext'), /^ζ = 0\.2: e\(ζ\) = 0\.\d{3}$/);
      // From the timeline: the jerk's line has a "Why?".
      await page.evaluate(() => { document.getElementById('why').open = false; });
      await page.click('#timeline tr.note .why-link');
      assert.ok(await page.evaluate(() => document.getElementById('why').open));
      await page.screenshot({ path: path.join(outDir, 'web-why.png'), fullPage: true });
      // Konstanz's "what makes it work" loads that build, and its radio comes on as on the
      // command line (the realistic konstanz keeps it off).
      const fixed = ['--example', 'konstanz', ...sets(['balloon.radius=0.11', 'radio.switch_force=0.01'])];
      assert.match(cliOutcome(['--example', 'konstanz']), /the radio stays off$/);
      // (A link's machine is loaded afresh: the page reloads.)
      await Promise.all([page.waitForEvent('load'), page.click('#konstanz-fix')]);
      await page.waitForSelector('body[data-ready]', { timeout: 30000 });
      await idle(page);
      assert.equal(await page.textContent('#cli-command'), `$ whatnext run ${fixed.join(' ')}`);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(fixed)}.`);
      assert.match(await outcomeText(page), /radio on at t = /);
    });
  },

  // Share -> QR code: drawn in the page (nothing fetched), dark modules on white with a quiet zone.
  async qr_code() {
    await withPage(async (page) => {
      await menuClick(page, '#qr');
      await page.waitForSelector('#qr-dialog[open] svg');
      const qr = await page.evaluate(() => {
        const svg = document.querySelector('#qr-code svg');
        const size = Number(svg.getAttribute('viewBox').split(' ')[2]);
        const cells = [...svg.querySelector('path').getAttribute('d').matchAll(/M(\d+) (\d+)/g)].map((m) => [Number(m[1]), Number(m[2])]);
        return { size, cells, link: document.getElementById('qr-note').textContent, href: location.href,
                 fill: svg.querySelector('path').getAttribute('fill'), back: svg.querySelector('rect').getAttribute('fill') };
      });
      assert.equal(qr.link, qr.href);
      assert.match(qr.link, /#machine=example1/);
      assert.equal(qr.fill, '#000');
      assert.equal(qr.back, '#fff');
      // Version v has 17 + 4 v modules a side, plus 4 quiet modules each side.
      assert.equal((qr.size - 8 - 17) % 4, 0, `a side of ${qr.size}`);
      assert.ok(qr.cells.every(([x, y]) => x >= 4 && y >= 4 && x < qr.size - 4 && y < qr.size - 4), 'a dark module in the quiet zone');
      // The three finder patterns: dark 7x7 squares' corners.
      const dark = new Set(qr.cells.map(([x, y]) => `${x},${y}`));
      for (const [x, y] of [[4, 4], [qr.size - 5, 4], [4, qr.size - 5]]) assert.ok(dark.has(`${x},${y}`), `finder at ${x},${y}`);
      await page.screenshot({ path: path.join(outDir, 'web-qr.png') });
      // Scanned as a phone would (zbar, where it is installed): the link itself.
      if (fs.existsSync('/usr/bin/zbarimg')) {
        const shot = path.join(outDir, 'web-qr-code.png');
        await page.locator('#qr-code svg').screenshot({ path: shot });
        const scan = spawnSync('/usr/bin/zbarimg', ['-q', '--raw', shot], { encoding: 'utf8' });
        assert.equal(scan.stdout.trim(), qr.href, `zbarimg read ${scan.stdout}`);
      } else {
        console.log('qr_code: no zbarimg here, the code is not scanned');
      }
    });
  },

  async axe_desktop() { await axeCheck('desktop', { width: 1400, height: 900 }, {}); },
  async axe_phone() { await axeCheck('phone', { width: 390, height: 844 }, { touch: true, scale: 2 }); },
  async axe_projector() { await axeCheck('projector', { width: 1366, height: 768 }, { projector: true }); },

  // German: from the browser's language; every word of the page in German, numbers with a decimal
  // comma, the library's messages in German words; the switch back to English.
  async german() {
    fs.mkdirSync(outDir, { recursive: true });
    await withPage(async (page) => {
      assert.equal(await page.getAttribute('html', 'lang'), 'de');
      assert.equal(await outcomeText(page), 'Ergebnis: Deckel offen bei 0,820 s.');
      assert.equal(await page.textContent('#timeline tbody tr.event td:nth-child(2)'), 'Sandsack landet');
      // No English word in what the page shows (the timeline's rows and the command line's text
      // are the command line's own; keys and units are the library's names).
      const english = await page.evaluate(() => {
        const words = ['Play', 'Outcome', 'Parameters', 'Reset', 'Compare', 'Angles', 'tension', 'Machine', 'Copy', 'Download',
                       'speed', 'the', 'and', 'of', 'with', 'run', 'Events', 'event', 'sandbag', 'lid', 'seesaw', 'rope', 'Example',
                       'paused', 'Sound', 'Projector', 'Open', 'file', 'Last', 'states', 'dashed', 'nothing', 'blank', 'change'];
        const clone = document.body.cloneNode(true);
        for (const el of clone.querySelectorAll('#timeline tbody, pre, code, script, .help, dialog, #cli')) el.remove();
        const text = clone.innerText || clone.textContent;
        return words.filter((w) => new RegExp(`(^|[^\\wäöüß.])${w}([^\\wäöüß]|$)`).test(text));
      });
      assert.deepEqual(english, [], 'English words in the German page');
      // Every parameter's name whole (a long German word wraps at its soft hyphen, never cut).
      const cutNames = await page.evaluate(() => {
        const closed = [...document.querySelectorAll('#fields details')].filter((d) => !d.open);
        for (const d of closed) d.open = true;
        const cut = [...document.querySelectorAll('.field label')].filter((l) => l.scrollWidth > l.clientWidth + 1).map((l) => l.textContent);
        for (const d of closed) d.open = false;
        return cut;
      });
      assert.deepEqual(cutNames, [], 'parameter names cut');
      await setFieldAndRun(page, 'geometry.rope_length', '0,9');
      assert.match(await outcomeText(page), /^Ergebnis: Deckel offen bei \d,\d{3} s\.$/);
      await setField(page, 'geometry.rope_length', '-1');
      assert.match(await page.textContent('#problem'), /^Nicht gerechnet: geometry\.rope_length muss > 0 m sein \(gegeben: -1\)\./);
      await page.waitForSelector('body[data-checked]');  // the sliders' red stretches drawn
      await page.screenshot({ path: path.join(outDir, 'web-german.png') });
      await page.selectOption('#lang', 'en');
      await page.waitForFunction(() => document.documentElement.lang === 'en' && document.body.dataset.ready);
      assert.match(await outcomeText(page), /^Outcome: lid open at /);
    }, { locale: 'de-DE', viewport: { width: 1366, height: 768 } });
  },

  // German numbers in the panel: every field, placeholder and slider value with a
  // decimal comma; what the page sends and keeps (the library's input, the link, the TOML) with a
  // point; the switch to English shows the point again.
  async decimal_comma() {
    fs.mkdirSync(outDir, { recursive: true });
    await withPage(async (page, { downloads: dir }) => {
      assert.equal(await page.getAttribute('html', 'lang'), 'de');
      assert.equal(await page.inputValue(fieldId('geometry.rope_length')), '1');
      assert.equal(await page.inputValue(fieldId('geometry.lid_half_length')), '0,2');
      // Blank fields: the grey value they stand for, a pair's too.
      assert.equal(await page.getAttribute(fieldId('balloon.drag_coefficient'), 'placeholder'), '0,47');
      assert.equal(await page.getAttribute(fieldId('radio.switch_offset'), 'placeholder'), '0,5');

      // A slider dragged with the mouse: the field shows its value with a comma.
      const slider = `[data-key="geometry.lid_half_length"] input.slider`;
      await page.locator(slider).scrollIntoViewIfNeeded();
      const box = await page.locator(slider).boundingBox();
      await page.mouse.move(box.x + box.width * 0.3, box.y + box.height / 2);
      await page.mouse.down();
      await page.mouse.move(box.x + box.width * 0.37, box.y + box.height / 2, { steps: 5 });
      await page.mouse.up();
      await idle(page);
      const dragged = await page.inputValue(fieldId('geometry.lid_half_length'));
      assert.match(dragged, /^0,\d+$/, 'the dragged value');
      await page.click(`[data-key="geometry.lid_half_length"] button.reset`);
      await idle(page);
      assert.equal(await page.inputValue(fieldId('geometry.lid_half_length')), '0,2');

      // Typed with a comma: the machine runs with 0.7 m, as the command line does.
      await setFieldAndRun(page, 'geometry.rope_length', '0,7');
      assert.equal(await page.inputValue(fieldId('geometry.rope_length')), '0,7');
      const args = ['--example', '1', '--set', 'geometry.rope_length=0.7'];
      const expected = await page.evaluate((text) => window.whatnext.words(text), cliOutcome(args));
      assert.equal(await outcomeText(page), `Ergebnis: ${expected}.`);
      assert.notEqual(cliOutcome(args), cliOutcome(['--example', '1']), '0.7 m changes the outcome');
      await page.waitForFunction(() => location.hash.includes('rope_length'));
      assert.match(page.url(), /[#&]geometry\.rope_length=0\.7$/, 'the link keeps the point');
      const toml = await download(page, '#dl-toml', dir);
      assert.match(fs.readFileSync(toml, 'utf8'), /^rope_length = 0\.7\b/m);
      assert.equal(`Ergebnis: ${await page.evaluate((text) => window.whatnext.words(text), cliOutcome([toml]))}.`, await outcomeText(page));
      // The comparison's Euler step too: shown with a comma, typed with one, kept with a point.
      await page.selectOption('#compare', 'euler');
      await idle(page);
      assert.equal(await page.inputValue('#compare-step'), '0,001');
      await page.fill('#compare-step', '0,002');
      await idle(page);
      const euler = cliOutcome([...args, ...sets(['run.integrator=euler', 'run.step=0.002'])]);
      assert.equal(await page.textContent('#compare-outcome'),
                   `Gestrichelt, Euler, Schritt 0,002 s: ${await page.evaluate((text) => window.whatnext.words(text), euler)}.`);
      assert.match(page.url(), /compare=euler%3A0\.002$/);
      await page.selectOption('#compare', 'none');
      await idle(page);
      // A pair with one part typed: the other is its grey "0,5", sent as 0.5.
      await page.click('details.group:last-of-type > summary');  // "Extensions beyond the paper"
      await page.check(fieldId('radio.enabled'));
      await idle(page);
      await setFieldAndRun(page, 'radio.switch_offset-dh', '0,1');
      args.push(...sets(['radio.enabled=true', 'radio.switch_offset=[0.5, 0.1]']));
      assert.equal(await outcomeText(page), `Ergebnis: ${await page.evaluate((text) => window.whatnext.words(text), cliOutcome(args))}.`);
      assert.deepEqual([await page.inputValue(fieldId('radio.switch_offset')), await page.inputValue(fieldId('radio.switch_offset-dh'))], ['0,5', '0,1']);
      await page.screenshot({ path: path.join(outDir, 'web-german-commas.png') });

      await page.selectOption('#lang', 'en');
      await page.waitForFunction(() => document.documentElement.lang === 'en' && document.body.dataset.ready);
      assert.equal(await page.inputValue(fieldId('geometry.rope_length')), '0.7');
      assert.equal(await page.inputValue(fieldId('geometry.lid_half_length')), '0.2');
      assert.equal(await page.getAttribute(fieldId('balloon.drag_coefficient'), 'placeholder'), '0.47');
      assert.deepEqual([await page.inputValue(fieldId('radio.switch_offset')), await page.inputValue(fieldId('radio.switch_offset-dh'))], ['0.5', '0.1']);
      assert.equal(await outcomeText(page), `Outcome: ${cliOutcome(args)}.`);
    }, { locale: 'de-DE', viewport: { width: 1366, height: 768 } });
  },

  // German: the library's rarer messages too. First every message the command line
  // gives for a list of bad inputs (values out of range, rules between keys, words where numbers
  // belong, unknown keys and sections, files that are not TOML or not a whatnext.inp) and every
  // reason a run can fail for (as src/core writes them), put into the page's words: no English
  // left. Then the page itself provokes several and shows them in German: a value beyond the
  // model's range, two rules between keys, a word in a number's field, a key in a link the
  // library does not know, a link whose file is cut, a comparison that cannot run, a file that is
  // not TOML and a whatnext.inp with a decimal comma.
  async messages() {
    const bad = [
      ['geometry.rope_length=5000'], ['geometry.rope_length=-1'], ['geometry.rope_length=0.3'], ['geometry.rope_length=3'],
      ['start.seesaw_angle=95'], ['start.sandbag_x=0.2'], ['start.sandbag_x=-2000'], ['start.sandbag_height=-1'],
      ['start.lid_angle=95'], ['air.helium_density=2'], ['air.density=1e6'], ['balloon.model=lagrangian', 'air.helium_density=0.0001'],
      ['run.output_step=1e-9'], ['run.integrator=euler', 'run.step=1e-9'], ['run.tolerance=1'], ['run.t_max=1e9'],
      ['run.step=abc'], ['run.integrator=foo'], ['run.impact_law=y'], ['balloon.model=x'], ['radio.enabled=maybe'],
      ['radio.switch_offset=abc'], ['radio.switch_offset=[5000, 0]'], ['geometry.hinge_offset=[0,0]'],
      ['geometry.rope_on_lid=0.5'], ['geometry.rope_lenght=1'],
      ['seesaw.com_offset=0.3'], ['seesaw.inertia=1'], ['seesaw.mass=-1'], ['seesaw.mass=1'],
      ['seesaw.mass=1', 'seesaw.left_arm=900'], ['seesaw.mass=1', 'seesaw.left_arm=1', 'seesaw.com_offset=0.9'],
      ['seesaw.mass=1', 'seesaw.inertia=0.01', 'seesaw.com_offset=0.5'], ['start.sandbag_height=0', 'start.seesaw_angle=0', 'seesaw.left_arm=0.1'],
      ['damping.pivot=1'],
      ['damping.lid_hinge=100', 'run.integrator=euler'], ['radio.string_length=0.1'], ['radio.enabled=false', 'radio.string_length=2'],
      ['balloon.rubber_mass=1'], ['balloon.rubber_mass=-1'], ['balloon.drag=false', 'balloon.drag_coefficient=0.5'],
      ['balloon.drag_coefficient=100'], ['run.vertical_margin=inf'], ['run.gravity=-1'], ['masses.sandbag=1e-9'],
      // The built machine's.
      ['seesaw.end_stop=true'], ['floor.enabled=true'], ['seesaw.left_arm=1.2', 'floor.enabled=true', 'geometry.hinge_angle=-60'],
      ['seesaw.left_arm=1.2', 'floor.enabled=true', 'start.seesaw_angle=60', 'geometry.rope_length=1.4'],
      ['seesaw.left_arm=1.2', 'floor.enabled=true', 'start.seesaw_angle=30', 'start.sandbag_x=-1.5', 'start.sandbag_height=-0.8',
       'geometry.rope_length=1.4'],
      ['floor.restitution=2'], ['floor.enabled=false', 'floor.restitution=0.5'], ['radio.switch_force=-1'], ['seesaw.end_stop=maybe'],
      // Restitution on the paper's contacts.
      ['restitution.stop=0.5'], ['restitution.rope=0.5', 'run.impact_law=kinetic-energy'], ['restitution.lid=1.5'],
    ];
    const files = {
      'a.toml': '[foo]\n', 'b.toml': '[geometry]\nrope_length = \n', 'c.toml': '"masses.sandbag" = 0.5\n',
      'd.toml': '[geometry]\nrope_length = "x"\n', 'e.toml': '[run]\nintegrator = 3\n', 'f.toml': '[balloon]\nmodel = 1\n',
      'g.toml': '[geometry]\nrope_length = 1\nrope_length = 2\n', 'h.toml': '[geometry]\nrope_length = [1\n',
      'i.toml': 'x = 1\n', 'j.toml': '[geometry]\nrope_length = 01\n', 'k.toml': '[geometry]\nrope_length = 1x\n',
      'l.toml': '[radio]\nenabled = 2\n', 'm.toml': '[geometry]\nhinge_offset = [0.5, 0.5]\nhinge_distance = 0.8\n', 'w.inp': '1\n-0,3\n', 'x.inp': '1\n-0.3\n', 'y.inp': Array.from({ length: 16 }, (_, i) => `${i + 1}`).join('\n'),
    };
    const messages = new Set();
    for (const list of bad) messages.add(cliError(['--example', '1', ...sets(list)]));
    const dir = fs.mkdtempSync(path.join(os.tmpdir(), 'whatnext-messages-'));
    try {
      for (const [name, text] of Object.entries(files)) {
        fs.writeFileSync(path.join(dir, name), text);
        const r = spawnSync(cliPath, ['run', name, '-q'], { cwd: dir, encoding: 'utf8' });
        assert.equal(r.status, 2, `${name} should be refused`);
        messages.add(r.stderr.trim().replace(/^whatnext: error: /, ''));
      }
    } finally {
      fs.rmSync(dir, { recursive: true, force: true });
    }
    // The reasons a run fails for, as the sources write them, in the sentence each is written into.
    const source = (file) => fs.readFileSync(path.join(sourceDir, file), 'utf8');
    const literals = (text) => [...text.matchAll(/"((?:[^"\\]|\\.)*)"/g)].map((m) => m[1]).join('');
    const printf = (format, ...args) => format.replace(/%[-.\d]*[sgd]/g, () => args.shift());
    const simulate = source('src/core/simulate.cpp'), contacts = source('src/core/contact_decision.cpp');
    const failFormat = literals(simulate.match(/snprintf\(msg, sizeof msg, ("[^;]*?"),/)[1]);
    for (const m of simulate.matchAll(/\bfail\(((?:\s*"(?:[^"\\]|\\.)*")+)/g)) messages.add(printf(failFormat, literals(m[1]), '0.512345678', '4'));
    const consistentFormat = literals(contacts.match(/snprintf\(msg, sizeof msg, ("[^;]*?"),/)[1]);
    for (const m of contacts.matchAll(/no_consistent\("([^"]+)"/g)) messages.add(printf(consistentFormat, m[1], '0.512345678', '4'));
    for (const m of source('src/core/jumps.cpp').matchAll(/SimulationError\("([^"]+)"\)/g)) messages.add(m[1]);
    assert.ok(messages.size >= 60, `${messages.size} messages`);
    // Why an impact took the rope law instead of the one chosen, in the timeline's impact lines.
    const notes = [];
    for (const [file, re] of [['src/core/contact_decision.cpp', /law_note =((?:\s*"(?:[^"\\]|\\.)*")+)/g],
                              ['src/core/impact_laws.cpp', /\*note =((?:\s*"(?:[^"\\]|\\.)*")+)/g]]) {
      for (const m of source(file).matchAll(re)) notes.push(literals(m[1]));
    }
    assert.ok(notes.length >= 5, `${notes.length} notes`);

    await withPage(async (page, { open }) => {
      assert.equal(await page.getAttribute('html', 'lang'), 'de');
      const english = [];
      for (const m of messages) {
        const shown = await page.evaluate((text) => window.whatnext.words(text), m);
        const left = englishIn(shown);
        if (left.length || shown === m) english.push(`${m}\n    -> ${shown}\n    English: ${left.join(', ')}`);
      }
      for (const n of notes) {
        const shown = await page.evaluate((text) => window.whatnextStrings.t(text), n);
        const left = englishIn(shown);
        if (left.length || shown === n) english.push(`${n}\n    -> ${shown}\n    English: ${left.join(', ')}`);
      }
      assert.deepEqual(english, [], 'messages with English words on the German page');
      console.log(`${messages.size} messages and ${notes.length} impact-law notes of the library in German words`);

      // In the page: what it shows after each input, in the problem line, the fields and the
      // comparison's line.
      const shownNow = () => page.evaluate(() => [document.getElementById('problem'), ...document.querySelectorAll('.field .error'),
                                                   document.getElementById('compare-outcome')]
        .filter((e) => !e.hidden && e.textContent.trim()).map((e) => e.textContent));
      const check = async (what, expect) => {
        const texts = await shownNow();
        assert.ok(texts.length, `${what}: no message shown`);
        assert.ok(texts.some((t) => expect.test(t)), `${what}: ${expect} not in ${JSON.stringify(texts)}`);
        for (const t of texts) assert.deepEqual(englishIn(t), [], `${what}: English in "${t}"`);
      };
      await setField(page, 'geometry.rope_length', '5000');
      await check('a rope beyond the model\'s range', /geometry\.rope_length muss in \[0,001; 1000\] m liegen, dem Bereich, für den das Modell gemacht ist/);
      await setField(page, 'geometry.rope_length', '0,3');
      await check('a rope too short for the start', /ist kürzer als der Abstand vom Ende der Wippe zur Deckelkante am Anfang \(0,3 m < 0,5724 m\)/);
      await setField(page, 'geometry.rope_length', '');
      await setField(page, 'air.helium_density', '2');
      await check('helium heavier than air', /air\.helium_density muss > 0 und kleiner als air\.density \(1,29 kg\/m\^3\) sein, damit der Ballon steigt/);
      await setField(page, 'air.helium_density', '');
      await setField(page, 'run.t_max', 'abc');
      await check('a word for a number', /run\.t_max muss eine Zahl in s sein \(gegeben: „abc“\)/);
      await setField(page, 'run.t_max', '');
      await page.selectOption('#compare', 'euler');
      await page.fill('#compare-step', 'x');
      await idle(page);
      await check('a comparison that cannot run', /^Kein Vergleich: run\.step muss eine Zahl in s sein/);
      await page.selectOption('#compare', 'none');
      await idle(page);

      let other = await open('#machine=example2&geometry.rope_lenght=1');
      assert.match(await other.textContent('#problem'), /unbekannter Schlüssel „geometry\.rope_lenght“ \(gemeint: „geometry\.rope_length“\?\)/);
      assert.deepEqual(englishIn(await other.textContent('#problem')), []);
      other = await open('#file=a.toml&text=QUJD_');
      assert.match(await other.textContent('#problem'), /Die Datei im Link \(text=\) ist nicht lesbar: seine Länge ist nicht die eines Base64-Texts\./);
      assert.deepEqual(englishIn(await other.textContent('#problem')), []);

      for (const [name, expect] of [['h.toml', /h\.toml:2:18: kein gültiges TOML beim Lesen einer Liste: das Dateiende kam zu früh/],
                                    ['w.inp', /w\.inp Zeile 2: erwartet: eine Zahl für xs \(start\.sandbag_x\), gefunden: „-0,3“/]]) {
        await page.setInputFiles('#file', { name, mimeType: 'text/plain', buffer: Buffer.from(files[name]) });
        await page.waitForFunction(() => !document.getElementById('problem').hidden);
        await idle(page);
        await check(`the file ${name}`, expect);
      }
    }, { locale: 'de-DE', viewport: { width: 1366, height: 768 } });
  },

  // The sliders show where the machine is refused (asked of the library for the machine as it
  // stands, checked here against the command line); a slider moved there marks the drawing as
  // stale until a value runs again; a field's help never covers another field.
  async sliders() {
    await withPage(async (page) => {
      await page.waitForSelector('body[data-checked]');
      const key = 'geometry.rope_length';
      // A slider says its value with its unit, not its position; the label's name and unit apart.
      const shown = await page.$eval(fieldId(key), (i) => i.value || i.placeholder);
      assert.equal(await page.$eval(`[data-key="${key}"] input.slider`, (el) => el.getAttribute('aria-valuetext')), `${shown} m`);
      assert.equal(await page.$eval(`[data-key="${key}"] label`, (el) => el.textContent), 'rope length [m]');
      assert.match(await page.getAttribute('#scrub', 'aria-valuetext'), /^t = \d\.\d{3} s$/);
      const [valid, values] = await page.evaluate((k) => {
        const probe = document.querySelector(`[data-key="${k}"] input.slider`);
        return [window.whatnext.validity(k), window.whatnext.probes(k), probe];
      }, key);
      const bad = valid.indexOf(false), good = valid.indexOf(true);
      assert.ok(bad >= 0 && good >= 0, `rope length: ${valid}`);
      assert.equal(cli('run', '--example', '1', '--set', `${key}=${values[bad]}`, '-q').status, 2, `${values[bad]} m is refused`);
      assert.equal(cli('run', '--example', '1', '--set', `${key}=${values[good]}`, '-q').status, 0, `${values[good]} m runs`);
      const track = await page.evaluate((k) => getComputedStyle(document.querySelector(`[data-key="${k}"] input.slider`)).getPropertyValue('--refused'), key);
      assert.match(track, /linear-gradient/);

      // Into the refused range and back.
      const slide = (p) => page.evaluate(([k, pos]) => {
        const slider = document.querySelector(`[data-key="${k}"] input.slider`);
        slider.value = String(pos);
        slider.dispatchEvent(new Event('input', { bubbles: true }));
        slider.dispatchEvent(new Event('change', { bubbles: true }));
      }, [key, p]);
      await slide(Math.round(1000 * (bad + 0.5) / valid.length));
      await idle(page);
      assert.ok(await page.evaluate(() => document.getElementById('layout').classList.contains('stale')), 'the drawing is marked stale');
      assert.ok(await page.isVisible('#stale-note'));
      await slide(Math.round(1000 * (good + 0.5) / valid.length));
      await idle(page);
      assert.equal(await page.evaluate(() => document.getElementById('layout').classList.contains('stale')), false);
      assert.equal(await page.isVisible('#stale-note'), false);

      // The help beside the panel, over no field.
      await page.hover(fieldId('geometry.lid_half_length'));
      await page.waitForSelector('.help-tip', { state: 'visible' });
      const overlaps = await page.evaluate(() => {
        const t = document.querySelector('.help-tip').getBoundingClientRect();
        return [...document.querySelectorAll('.field')].filter((f) => {
          const r = f.getBoundingClientRect();
          return r.height > 0 && r.left < t.right && t.left < r.right && r.top < t.bottom && t.top < r.bottom;
        }).map((f) => f.dataset.key);
      });
      assert.deepEqual(overlaps, [], 'the help covers fields');
      assert.match(await page.textContent('.help-tip'), /geometry\.lid_half_length/);
    }, { viewport: { width: 1366, height: 768 } });
  },

  // Not a test: how long one run of example 2 takes in the page, and a whole change (a rope
  // length typed: the run, the timeline, the plots, the panel and the drawing), printed for
  // docs/web.md and docs/performance.md.
  async speed() {
    await withPage(async (page) => {
      const times = await page.evaluate(async () => { await window.whatnext.timeRun('example2', 50); return window.whatnext.timeRun('example2', 500); });
      const median = times[times.length >> 1];
      const version = await page.evaluate(() => navigator.userAgent.match(/Chrome\/[\d.]+/)[0]);
      console.log(`example 2 in the page (${version}): median ${median.toFixed(3)} ms, fastest ${times[0].toFixed(3)} ms ` +
                  `over ${times.length} runs`);
      await page.selectOption('#preset', 'example2');
      // A change: the key typed to the run shown (the worker's round trip included).
      const changes = await page.evaluate(async () => {
        const input = document.getElementById('field-geometry-rope_length');
        const out = [];
        for (let i = 0; i < 250; ++i) {
          input.value = String(0.62 + 0.001 * (i % 50));
          const before = Number(document.body.dataset.runs);
          const shown = new Promise((resolve) => {
            const watch = new MutationObserver(() => {
              if (Number(document.body.dataset.runs) > before) { watch.disconnect(); resolve(); }
            });
            watch.observe(document.body, { attributes: true });
          });
          const t0 = performance.now();
          input.dispatchEvent(new Event('input', { bubbles: true }));
          await shown;
          if (i >= 50) out.push(performance.now() - t0);
        }
        return out.sort((a, b) => a - b);
      });
      console.log(`a change of example 2's rope length, run and shown: median ${changes[changes.length >> 1].toFixed(3)} ms, ` +
                  `fastest ${changes[0].toFixed(3)} ms over ${changes.length} changes`);
    });
  },
};

const name = process.argv[2];
if (!checks[name]) {
  console.error(`usage: node page.js (${Object.keys(checks).join('|')})`);
  process.exit(2);
}
checks[name]().then(() => console.log(`page ${name}: passed`), (e) => {
  console.error(`page ${name}: FAILED\n${e.stack || e}`);
  process.exit(1);
});
