// The map: which machines work, over two input keys around the machine shown. It is `whatnext
// sweep` with two --vary keys, run by the library in Web Workers (map-worker.js, one per core) a
// block of machines at a time, so that it fills in while the page stays responsive. Each cell is
// coloured by the machine's outcome or by the time of an event; the machine shown is marked;
// pointing at a cell (mouse, touch or the arrow keys) tells its values and outcome, choosing it
// loads that machine. The map's CSV is the rows the library's sweep writer made, as `whatnext
// sweep` writes them; a table beside it says the same for screen readers.
(function () {
  'use strict';

  const S = window.whatnextStrings;
  const T = (english, args) => S.t(english, args);
  // The page's numbers with its decimal sign; what goes to the library keeps the point.
  const shown = (v) => S.decimals(String(v));
  const grid = (v) => shown(Number(v.toPrecision(9)));  // a grid value as read (0.638787879), kept whole
  const point = (text) => text.trim().replace(/^([-+]?\d*),(\d+([eE][-+]?\d+)?)$/, '$1.$2');
  const kNumberKinds = ['length', 'mass', 'density', 'angle', 'time', 'acceleration', 'positive'];
  const kBlock = 50;        // machines per message: a few milliseconds of work for a worker
  const kInFlight = 2;      // blocks per worker at a time, so that none waits for the page
  const kMaxSteps = 400;    // per key: 160,000 machines, a few seconds
  const kTableMost = 40000; // machines in the table alternative
  // The outcomes' colours (an outcome not named here: kOtherStop), and the map's other cells.
  const kOutcomeColours = {
    lid_open: [38, 150, 70], seesaw_vertical: [232, 140, 20], radio_on: [45, 110, 210],
    sandbag_at_pivot: [150, 80, 170], rope_locked: [140, 90, 50], timeout: [150, 150, 150],
    event_limit: [90, 90, 90], switch_stays_off: [100, 170, 190],
  };
  const kOtherStop = [60, 160, 160], kInvalid = [232, 232, 232], kFailed = [200, 40, 40], kNever = [205, 205, 205];
  // Viridis, sampled at nine points: the times' scale, readable in grey and by colour-blind eyes.
  const kViridis = [[68, 1, 84], [71, 44, 122], [59, 81, 139], [44, 113, 142], [33, 144, 141],
    [39, 173, 129], [92, 200, 99], [170, 220, 50], [253, 231, 37]];
  const viridis = (f) => {
    const x = Math.min(Math.max(f, 0), 1) * (kViridis.length - 1), i = Math.min(Math.floor(x), kViridis.length - 2), u = x - i;
    return kViridis[i].map((c, k) => Math.round(c + (kViridis[i + 1][k] - c) * u));
  };
  const rgb = (c) => `rgb(${c[0]},${c[1]},${c[2]})`;
  const eventWords = (name) => S.eventWords(name.replace(/_/g, ' '));

  let app = null;            // the page's hooks (app.js)
  const $ = (id) => document.getElementById(id);
  const el = (tag, attrs = {}, ...children) => {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    e.append(...children);
    return e;
  };

  // ---- the workers ------------------------------------------------------------------------------

  const pool = [];
  let nextMap = 1;
  function workerSource() {
    // The single-file page holds the library and this worker's script as text (single.js).
    const inlined = $('map-worker-source');
    if (!inlined) return 'map-worker.js';
    return URL.createObjectURL(new Blob([[$('whatnext-module').textContent, inlined.textContent].join('\n')], { type: 'text/javascript' }));
  }
  function startWorkers() {
    if (pool.length) return;
    const n = Math.max(1, Math.min(navigator.hardwareConcurrency || 2, 16));
    const source = workerSource();
    for (let i = 0; i < n; ++i) {
      const w = { worker: new Worker(source), ready: null, busy: 0, map: 0 };
      w.ready = new Promise((resolve) => {
        w.worker.onmessage = (e) => {
          if (e.data.hello) { columnsKnown(e.data.hello.columns); resolve(); } else answer(w, e.data);
        };
      });
      w.worker.onerror = (e) => { e.preventDefault(); fail(T('the WebAssembly module failed ({message})', { message: e.message })); };
      pool.push(w);
    }
  }
  // The phase plots (phase.js) ask the first worker for a run's table.
  const phaseWaiting = new Map();
  let phaseId = 1, onColumns = null, columns = null;
  function columnsKnown(c) {
    if (columns) return;
    columns = c;
    if (onColumns) onColumns(c);
  }
  async function phaseTable(input, maxRows) {
    startWorkers();
    const w = pool[0];
    await w.ready;
    return new Promise((resolve) => {
      const id = phaseId++;
      phaseWaiting.set(id, resolve);
      w.worker.postMessage({ id, phase: { input, maxRows } });
    });
  }

  // ---- one map ----------------------------------------------------------------------------------

  // m: {id, input, vary, keys, axes, size, stride, numbers, done, rows (per block), errors, next,
  //     finished, t0, ms, stopped, header, events, command}
  let m = null;
  let cursor = null;         // the cell the keyboard is on: [ix, iy]

  async function draw() {
    const spec = readForm();
    if (!spec) return;
    startWorkers();
    const id = nextMap++;
    m = { id, input: app.input(), base: app.base(), sets: app.sets(), keys: [spec.x.key, spec.y.key], spec, vary: [spec.x, spec.y].map((r) => `${r.key}=${r.lo}:${r.hi}:${r.n}`),
          next: 0, blocksDone: 0, finished: 0, stopped: false, rows: [], errors: new Map(), t0: performance.now(), started: 0 };
    m.command = commandLine(m);
    $('map-stale').hidden = true;
    showRunning(true);
    status(T('Starting…'));
    await Promise.all(pool.map((w) => w.ready));
    if (!m || m.id !== id) return;
    for (const w of pool) { w.busy = 0; w.map = id; w.worker.postMessage({ map: id, start: { input: m.input, vary: m.vary } }); }
  }

  function answer(w, d) {
    if (d.phase !== undefined) {
      const done = phaseWaiting.get(d.phase);
      phaseWaiting.delete(d.phase);
      if (done) done(d.result);
      return;
    }
    if (!m || d.map !== m.id || m.ms !== undefined) return;  // an earlier map's, or one stopped before it began
    if (d.started) {
      const r = d.started;
      if (!r.ok) { fail(S.sentence(r.message)); return; }
      if (!m.size) {
        Object.assign(m, { size: r.size, stride: r.stride, header: r.header, events: r.events, axes: r.axes,
                           nx: r.axes[0].length, ny: r.axes[1].length });
        m.numbers = new Float64Array(m.size * m.stride).fill(NaN);
        m.done = new Uint8Array(m.size);
        m.blocks = Math.ceil(m.size / kBlock);
        fillValueChoice();
        layout();
      }
      feed(w);
      return;
    }
    --w.busy;
    const r = d.result;
    if (!r.ok) { fail(S.sentence(r.message)); return; }
    const [from, to] = d.block;
    m.numbers.set(r.numbers, from * m.stride);
    m.done.fill(1, from, to);
    m.rows[from / kBlock] = r.rows;
    for (const [i, message] of r.errors) m.errors.set(i, message);
    m.finished += to - from;
    ++m.blocksDone;
    feed(w);
    paintSoon();
    if (m.finished === m.size || (m.stopped && pool.every((p) => p.busy === 0))) finish();
  }

  function feed(w) {
    while (!m.stopped && w.busy < kInFlight && m.next < m.size) {
      const from = m.next, to = Math.min(m.size, from + kBlock);
      m.next = to;
      ++w.busy;
      w.worker.postMessage({ map: m.id, block: [from, to] });
    }
  }

  function stop() {
    if (!m || m.ms !== undefined) return;
    m.stopped = true;
    status(T('Stopping…'));
    if (pool.every((p) => p.busy === 0)) finish();
  }

  function finish() {
    if (m.ms !== undefined) return;
    m.ms = performance.now() - m.t0;
    showRunning(false);
    if (!m.size) {
      status(T('Stopped before the first machine.'));
      document.body.dataset.mapDone = String(m.id);
      return;
    }
    paint();
    const args = { done: count(m.finished), size: count(m.size), s: shown((m.ms / 1000).toFixed(2)), workers: pool.length };
    status(m.finished === m.size ? T('{size} machines in {s} s on {workers} workers.', args)
                                 : T('Stopped: {done} of {size} machines in {s} s.', args));
    $('map-csv').disabled = m.finished === 0;
    if ($('map-table-box').open) table();
    document.body.dataset.mapDone = String(m.id);
  }

  function fail(message) {
    if (m) m.stopped = true;
    showRunning(false);
    const p = $('map-problem');
    p.textContent = message;
    p.hidden = false;
    status('');
  }

  const count = (n) => n.toLocaleString(S.lang === 'de' ? 'de-DE' : 'en-US');

  // ---- the form: two keys, their ranges, what to colour --------------------------------------------

  function numericKeys() { return app.keys.filter((k) => kNumberKinds.includes(k.kind)).map((k) => k.key); }

  // The value the machine shown gives a key (in its input unit), or null.
  function valueOf(key) {
    const run = app.run();
    const v = run && run.values && run.values.effective[key];
    return v && v.number !== undefined ? v.number : null;
  }

  // A range around the machine's value: half of it either side (an angle: twenty degrees; zero: ±1).
  function around(key) {
    const v = valueOf(key);
    if (v === null) return [0, 1];
    const kind = app.keys.find((k) => k.key === key).kind;
    const span = kind === 'angle' ? 20 : v !== 0 ? Math.abs(v) * 0.5 : 1;
    const tidy = (x) => Number(x.toPrecision(3));
    return [tidy(v - span), tidy(v + span)];
  }

  function setRange(axis) {
    const [lo, hi] = around($(`map-${axis}-key`).value);
    $(`map-${axis}-lo`).value = shown(lo);
    $(`map-${axis}-hi`).value = shown(hi);
  }

  function readForm() {
    $('map-problem').hidden = true;
    const spec = {};
    for (const axis of ['x', 'y']) {
      const key = $(`map-${axis}-key`).value;
      const lo = point($(`map-${axis}-lo`).value), hi = point($(`map-${axis}-hi`).value), n = $(`map-${axis}-n`).value.trim();
      if (!/^\d+$/.test(n) || Number(n) < 1 || Number(n) > kMaxSteps) {
        fail(T('Steps of {key}: a whole number from 1 to {max}, not "{given}".', { key: S.keyName(key, key), max: kMaxSteps, given: n }));
        return null;
      }
      spec[axis] = { key, lo, hi, n: Number(n) };
    }
    if (spec.x.key === spec.y.key) {
      fail(T('The map needs two different keys (both are {key}).', { key: S.keyName(spec.x.key, spec.x.key) }));
      return null;
    }
    return spec;
  }

  // The command that writes the same CSV.
  function commandLine(map) {
    const base = app.base(), quote = (w) => (/^[\w.,:=+-]+$/.test(w) ? w : `'${w.replace(/'/g, "'\\''")}'`);
    const sets = [...app.sets()].map(([k, v]) => `--set ${quote(`${k}=${v}`)}`);
    return ['whatnext sweep', base.cli, ...sets, ...map.vary.map((v) => `--vary ${quote(v)}`), '--out map.csv'].join(' ');
  }

  function fillValueChoice() {
    const select = $('map-value'), was = select.value;
    select.textContent = '';
    select.append(new Option(T('the outcome'), 'outcome'), new Option(T('the outcome\'s time'), 'outcome_t'));
    for (const e of (m && m.events) || ['lid_open', 'seesaw_vertical', 'radio_on']) {
      if (e === 'timeout' || e === 'event_limit') continue;
      select.append(new Option(T('the time of: {event}', { event: eventWords(e) }), e));
    }
    select.value = [...select.options].some((o) => o.value === was) ? was : 'outcome';
  }

  // ---- drawing --------------------------------------------------------------------------------

  const kPad = { left: 64, right: 12, top: 10, bottom: 46 };
  let painted = false;
  function layout() {
    const canvas = $('map-canvas'), box = $('map-box');
    const width = Math.max(240, box.clientWidth);
    const height = Math.round(Math.min(width * 0.8, Math.max(260, window.innerHeight * 0.7)));
    const dpr = window.devicePixelRatio || 1;
    canvas.style.width = `${width}px`;
    canvas.style.height = `${height}px`;
    canvas.width = Math.round(width * dpr);
    canvas.height = Math.round(height * dpr);
    paint();
  }

  function paintSoon() {
    if (painted) return;
    painted = true;
    requestAnimationFrame(() => { painted = false; paint(); });
  }

  // What colours a cell, and the scale of times over the finished machines.
  function valueIndex() {
    const v = $('map-value').value;
    if (v === 'outcome') return -1;
    if (v === 'outcome_t') return 1;
    return 4 + m.events.indexOf(v);
  }
  function timeScale(k) {
    let lo = Infinity, hi = -Infinity;
    for (let i = 0; i < m.size; ++i) {
      const t = m.numbers[i * m.stride + k];
      if (m.done[i] && m.numbers[i * m.stride] >= 0 && Number.isFinite(t)) { lo = Math.min(lo, t); hi = Math.max(hi, t); }
    }
    return lo <= hi ? [lo, hi] : null;
  }
  function cellColour(i, k, scale) {
    const code = m.numbers[i * m.stride];
    if (code === -1) return kInvalid;
    if (code === -2) return kFailed;
    if (k < 0) return kOutcomeColours[m.events[code]] || kOtherStop;
    const t = m.numbers[i * m.stride + k];
    if (!Number.isFinite(t) || !scale) return kNever;
    return viridis(scale[1] > scale[0] ? (t - scale[0]) / (scale[1] - scale[0]) : 0.5);
  }

  // Plot coordinates: cell (ix, iy) of the map; x grows to the right, y upwards.
  // The margins and the labels grow with the page's type (large in projector mode).
  function frame() {
    const c = $('map-canvas'), dpr = c.width / c.clientWidth;
    const em = (parseFloat(getComputedStyle(c).fontSize) || 16) / 16;
    const pad = Object.fromEntries(Object.entries(kPad).map(([k, v]) => [k, v * em]));
    return { dpr, em, x0: pad.left, y0: pad.top, w: c.clientWidth - pad.left - pad.right, h: c.clientHeight - pad.top - pad.bottom };
  }

  function paint() {
    const c = $('map-canvas'), g = c.getContext('2d');
    const f = frame();
    g.setTransform(f.dpr, 0, 0, f.dpr, 0, 0);
    g.clearRect(0, 0, c.clientWidth, c.clientHeight);
    if (!m || !m.size) return;
    const k = valueIndex(), scale = k < 0 ? null : timeScale(k);
    // One pixel per machine, scaled up without smoothing.
    const img = new ImageData(m.nx, m.ny);
    for (let ix = 0; ix < m.nx; ++ix) {
      for (let iy = 0; iy < m.ny; ++iy) {
        const i = ix * m.ny + iy;
        if (!m.done[i]) continue;
        const col = cellColour(i, k, scale), p = ((m.ny - 1 - iy) * m.nx + ix) * 4;
        img.data[p] = col[0]; img.data[p + 1] = col[1]; img.data[p + 2] = col[2]; img.data[p + 3] = 255;
      }
    }
    const off = paint.canvas || (paint.canvas = document.createElement('canvas'));
    off.width = m.nx;
    off.height = m.ny;
    off.getContext('2d').putImageData(img, 0, 0);
    g.imageSmoothingEnabled = false;
    g.fillStyle = '#f4f4f4';
    g.fillRect(f.x0, f.y0, f.w, f.h);
    g.drawImage(off, f.x0, f.y0, f.w, f.h);
    g.strokeStyle = '#444';
    g.lineWidth = 1;
    g.strokeRect(f.x0 - 0.5, f.y0 - 0.5, f.w + 1, f.h + 1);
    axes(g, f);
    // The machine shown, where it lies in the map.
    const here = ofTheMap() ? marker(f) : null;
    if (here) {
      g.lineWidth = 2.5;
      g.strokeStyle = '#fff';
      g.beginPath(); g.arc(here.x, here.y, 7, 0, 2 * Math.PI); g.stroke();
      g.lineWidth = 1.5;
      g.strokeStyle = '#000';
      g.beginPath(); g.arc(here.x, here.y, 7, 0, 2 * Math.PI); g.moveTo(here.x - 11, here.y); g.lineTo(here.x + 11, here.y);
      g.moveTo(here.x, here.y - 11); g.lineTo(here.x, here.y + 11); g.stroke();
    }
    if (cursor) {
      const [ix, iy] = cursor, cw = f.w / m.nx, ch = f.h / m.ny;
      g.lineWidth = 2;
      g.strokeStyle = '#000';
      g.strokeRect(f.x0 + ix * cw, f.y0 + (m.ny - 1 - iy) * ch, Math.max(cw, 3), Math.max(ch, 3));
    }
    legend(k, scale);
  }

  // Where the machine shown lies, in canvas pixels (null: outside the map).
  function marker(f) {
    const vx = valueOf(m.keys[0]), vy = valueOf(m.keys[1]);
    if (vx === null || vy === null) return null;
    const at = (v, axis, n) => {
      const a = m.axes[axis], lo = a[0], hi = a[n - 1];
      return n === 1 ? (v === lo ? 0.5 : NaN) : 0.5 / n + ((v - lo) / (hi - lo)) * (n - 1) / n;
    };
    const fx = at(vx, 0, m.nx), fy = at(vy, 1, m.ny);
    if (!(fx >= 0 && fx <= 1 && fy >= 0 && fy <= 1)) return null;
    return { x: f.x0 + fx * f.w, y: f.y0 + (1 - fy) * f.h };
  }

  function ticks(lo, hi) {
    if (!(hi > lo)) return [lo];
    const raw = (hi - lo) / 5, mag = 10 ** Math.floor(Math.log10(raw));
    const step = [1, 2, 2.5, 5, 10].map((s) => s * mag).find((s) => s >= raw);
    const out = [];
    for (let v = Math.ceil(lo / step) * step; v <= hi + step * 1e-9; v += step) out.push(Number(v.toPrecision(12)));
    return out;
  }

  function axes(g, f) {
    g.fillStyle = '#222';
    g.font = `${Math.round(12 * f.em)}px system-ui, sans-serif`;
    const ax = m.axes[0], ay = m.axes[1];
    const pos = (v, a, n) => (n === 1 ? 0.5 : 0.5 / n + ((v - a[0]) / (a[n - 1] - a[0])) * (n - 1) / n);
    g.textAlign = 'center';
    g.textBaseline = 'top';
    for (const v of ticks(ax[0], ax[m.nx - 1])) {
      const x = f.x0 + pos(v, ax, m.nx) * f.w;
      g.fillRect(x, f.y0 + f.h, 1, 4);
      g.fillText(shown(v), x, f.y0 + f.h + 6 * f.em);
    }
    g.fillText(axisName(m.keys[0]), f.x0 + f.w / 2, f.y0 + f.h + 24 * f.em);
    g.textAlign = 'right';
    g.textBaseline = 'middle';
    for (const v of ticks(ay[0], ay[m.ny - 1])) {
      const y = f.y0 + (1 - pos(v, ay, m.ny)) * f.h;
      g.fillRect(f.x0 - 4, y, 4, 1);
      g.fillText(shown(v), f.x0 - 6, y);
    }
    g.save();
    g.translate(14 * f.em, f.y0 + f.h / 2);
    g.rotate(-Math.PI / 2);
    g.textAlign = 'center';
    g.fillText(axisName(m.keys[1]), 0, 0);
    g.restore();
  }

  function unitOf(key) { const k = app.keys.find((s) => s.key === key); return k && k.unit ? ` [${k.unit}]` : ''; }
  function axisName(key) { return `${S.keyName(key, key)}${unitOf(key)}`; }

  function legend(k, scale) {
    const box = $('map-legend');
    box.textContent = '';
    const item = (colour, text) => {
      const swatch = el('span', { class: 'map-swatch', 'aria-hidden': 'true' });
      swatch.style.background = colour;
      box.append(el('span', { class: 'map-key' }, swatch, text));
    };
    const tally = new Map();
    for (let i = 0; i < m.size; ++i) if (m.done[i]) tally.set(m.numbers[i * m.stride], (tally.get(m.numbers[i * m.stride]) || 0) + 1);
    if (k < 0) {
      for (const [code, n] of [...tally].sort((a, b) => b[1] - a[1])) {
        if (code >= 0) item(rgb(kOutcomeColours[m.events[code]] || kOtherStop), `${eventWords(m.events[code])}: ${count(n)}`);
      }
    } else if (scale) {
      const bar = el('span', { class: 'map-scale', 'aria-hidden': 'true' });
      bar.style.background = `linear-gradient(to right, ${kViridis.map(rgb).join(', ')})`;
      box.append(el('span', { class: 'map-key' }, `${shown(scale[0].toFixed(3))} s `, bar, ` ${shown(scale[1].toFixed(3))} s`));
      item(rgb(kNever), T('did not happen'));
    }
    if (tally.get(-1)) item(rgb(kInvalid), `${T('invalid machine')}: ${count(tally.get(-1))}`);
    if (tally.get(-2)) item(rgb(kFailed), `${T('the run failed')}: ${count(tally.get(-2))}`);
    item('transparent', T('⊕ the machine shown'));
  }

  // ---- pointing at a machine ----------------------------------------------------------------------

  function cellAt(ev) {
    const f = frame(), r = $('map-canvas').getBoundingClientRect();
    const fx = (ev.clientX - r.left - f.x0) / f.w, fy = 1 - (ev.clientY - r.top - f.y0) / f.h;
    if (!m || !m.size || fx < 0 || fx >= 1 || fy < 0 || fy >= 1) return null;
    return [Math.floor(fx * m.nx), Math.floor(fy * m.ny)];
  }

  // The words for machine (ix, iy): its values and what became of it.
  function describe(ix, iy) {
    const v = (d, j) => `${S.keyName(m.keys[d], m.keys[d])} = ${grid(m.axes[d][j])}`;
    const i = ix * m.ny + iy, values = `${v(0, ix)}, ${v(1, iy)}`;
    if (!m.done[i]) return { values, outcome: T('not run yet') };
    const code = m.numbers[i * m.stride];
    if (code < 0) {
      return { values, outcome: `${code === -1 ? T('invalid machine') : T('the run failed')}: ${S.sentence(m.errors.get(i) || '')}` };
    }
    let outcome = T('{event} at {t} s', { event: eventWords(m.events[code]), t: shown(m.numbers[i * m.stride + 1].toFixed(4)) });
    const k = valueIndex();
    if (k >= 4) {
      const t = m.numbers[i * m.stride + k];
      outcome += `; ${eventWords(m.events[k - 4])}: ${Number.isFinite(t) ? `${shown(t.toFixed(4))} s` : T('did not happen')}`;
    }
    return { values, outcome };
  }

  function showTip(cell, ev) {
    const tip = $('map-tip');
    if (!cell) { tip.hidden = true; return; }
    const d = describe(cell[0], cell[1]);
    tip.textContent = '';
    tip.append(el('span', {}, d.values), el('br'), el('strong', {}, d.outcome));
    tip.hidden = false;
    const box = $('map-box').getBoundingClientRect(), f = frame();
    const x = ev ? ev.clientX - box.left : f.x0 + (cell[0] + 0.5) * f.w / m.nx;
    const y = ev ? ev.clientY - box.top : f.y0 + (m.ny - cell[1] - 0.5) * f.h / m.ny;
    tip.style.left = `${Math.min(x + 12, box.width - tip.offsetWidth - 4)}px`;
    tip.style.top = `${y + 16}px`;
    $('map-here').textContent = `${d.values}: ${d.outcome}`;
  }

  // Loads machine (ix, iy): the machine shown with the two keys set (and so its link).
  function load(ix, iy) {
    const sets = new Map(m.sets);
    for (const [d, v] of [[0, m.axes[0][ix]], [1, m.axes[1][iy]]]) {
      sets.delete(m.keys[d]);
      sets.set(m.keys[d], String(v));
    }
    app.load(sets, m.base);
  }

  // Whether the machine shown is one of the map's: the map's machine with its two keys at any values.
  function ofTheMap() {
    const now = app.input(), without = (sets) => sets.filter((s) => !m.keys.some((k) => s.startsWith(`${k}=`)));
    return now.toml === m.input.toml && now.format === m.input.format &&
           JSON.stringify(without(now.sets)) === JSON.stringify(without(m.input.sets));
  }
  function machineChanged() {
    if (!m || !m.size) return;
    $('map-stale').hidden = ofTheMap();
    paint();
  }

  function keydown(e) {
    if (!m || !m.size) return;
    const moves = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, 1], ArrowDown: [0, -1] };
    if (moves[e.key]) {
      const step = e.shiftKey ? 10 : 1;
      const [ix, iy] = cursor || [Math.floor(m.nx / 2), Math.floor(m.ny / 2)];
      cursor = [Math.min(m.nx - 1, Math.max(0, ix + moves[e.key][0] * step)), Math.min(m.ny - 1, Math.max(0, iy + moves[e.key][1] * step))];
      showTip(cursor, null);
      paint();
    } else if (e.key === 'Enter' && cursor) {
      load(cursor[0], cursor[1]);
    } else return;
    e.preventDefault();
    e.stopPropagation();  // the page's own keys (the player's arrows) are not meant
  }

  // ---- the table alternative and the CSV ------------------------------------------------------------

  function table() {
    const t = $('map-table');
    t.textContent = '';
    if (!m || !m.size) return;
    if (m.size > kTableMost) {  // a table of more cells than that takes the page seconds to lay out
      t.append(el('caption', {}, T('The table holds maps of up to {most} machines; the CSV holds every one.', { most: count(kTableMost) })));
      return;
    }
    t.append(el('caption', {}, T('Outcome of each machine: {y} down, {x} across', { x: axisName(m.keys[0]), y: axisName(m.keys[1]) })));
    const head = el('tr', {}, el('th', { scope: 'col' }, `${S.keyName(m.keys[1], m.keys[1])} \\ ${S.keyName(m.keys[0], m.keys[0])}`));
    for (let ix = 0; ix < m.nx; ++ix) head.append(el('th', { scope: 'col' }, grid(m.axes[0][ix])));
    t.append(el('thead', {}, head));
    const body = el('tbody');
    const k = valueIndex();
    for (let iy = m.ny - 1; iy >= 0; --iy) {
      const row = el('tr', {}, el('th', { scope: 'row' }, grid(m.axes[1][iy])));
      for (let ix = 0; ix < m.nx; ++ix) {
        const i = ix * m.ny + iy, code = m.numbers[i * m.stride];
        let text = '–';
        if (m.done[i]) {
          if (code === -1) text = T('invalid');
          else if (code === -2) text = T('failed');
          else if (k < 0) text = eventWords(m.events[code]);
          else text = Number.isFinite(m.numbers[i * m.stride + k]) ? shown(m.numbers[i * m.stride + k].toFixed(4)) : T('never');
        }
        row.append(el('td', {}, text));
      }
      body.append(row);
    }
    t.append(body);
  }

  // The CSV as `whatnext sweep` writes it: its header and the rows of the finished machines, in order.
  function csvText() { return m.header + m.rows.filter((r) => r !== undefined).join(''); }

  function download() {
    if (!m || !m.finished) return;
    const a = el('a', { href: URL.createObjectURL(new Blob([csvText()], { type: 'text/csv' })), download: 'map.csv' });
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  }

  // ---- the section --------------------------------------------------------------------------------

  function status(text) { $('map-status').textContent = text; }
  function showRunning(on) {
    $('map-draw').disabled = on;
    $('map-stop').disabled = !on;
    $('map-progress-box').hidden = !on;
    if (on) {
      $('map-csv').disabled = true;
      const tick = () => {
        if (!m || m.ms !== undefined) return;
        $('map-progress').max = m.size || 1;
        $('map-progress').value = m.finished;
        if (m.size) status(T('{done} of {size} machines', { done: count(m.finished), size: count(m.size) }));
        setTimeout(tick, 100);
      };
      tick();
    }
  }

  function build(section) {
    // Named by its axis's legend (axe: a select needs an accessible name).
    const keySelect = (axis, label) => {
      const s = el('select', { id: `map-${axis}-key`, 'aria-label': label });
      // The key's name in the page's language (the key itself in English), the key as its title.
      for (const key of numericKeys()) {
        const o = new Option(S.keyName(key, key), key);
        o.title = key;
        s.append(o);
      }
      return s;
    };
    const axisRow = (axis, label) => el('fieldset', { class: 'map-axis' },
      el('legend', {}, label), keySelect(axis, label),
      el('label', {}, T('from'), ' ', el('input', { id: `map-${axis}-lo`, type: 'text', inputmode: 'decimal', size: '7' })),
      el('label', {}, T('to'), ' ', el('input', { id: `map-${axis}-hi`, type: 'text', inputmode: 'decimal', size: '7' })),
      el('label', {}, T('steps'), ' ', el('input', { id: `map-${axis}-n`, type: 'text', inputmode: 'numeric', size: '4', value: '100' })));
    section.append(
      el('h2', { id: 'map-title' }, T('Map: which machines work')),
      el('p', { class: 'note' }, T('Many machines around the one shown, two keys varied: each cell is one machine run to its end.'), ' ',
        el('span', { class: 'keys-only' }, T('Point at a cell to read it, click it (or Enter) to load that machine.')),
        el('span', { class: 'touch-only' }, T('Tap a cell to read it, tap it again to load that machine.'))),
      el('form', { id: 'map-form', autocomplete: 'off' },
        axisRow('x', T('across')), axisRow('y', T('up')),
        el('div', { class: 'map-actions' },
          el('label', {}, T('colour'), ' ', el('select', { id: 'map-value' })),
          el('button', { id: 'map-draw', type: 'submit', class: 'primary' }, T('Draw the map')),
          el('button', { id: 'map-stop', type: 'button', disabled: '' }, T('Stop')),
          el('button', { id: 'map-csv', type: 'button', disabled: '', title: T('The map\'s machines as whatnext sweep writes them') }, T('Download the map\'s CSV')))),
      el('div', { id: 'map-progress-box', class: 'progress', hidden: '' }, el('progress', { id: 'map-progress', value: '0', max: '1' })),
      el('p', { id: 'map-status', class: 'note', 'aria-live': 'polite' }),
      el('p', { id: 'map-problem', class: 'problem', role: 'alert', hidden: '' }),
      el('p', { id: 'map-stale', class: 'note', hidden: '' }, T('This map is of the machine before the last change (other keys or another machine): a cell loads its own machine; Draw the map again for the machine shown.')),
      el('div', { id: 'map-box' },
        el('canvas', { id: 'map-canvas', tabindex: '0', role: 'img',
                       'aria-label': T('The map (arrow keys move between machines, Enter loads one; the table below says the same)') }),
        el('div', { id: 'map-tip', class: 'map-tip', hidden: '' })),
      el('p', { id: 'map-here', class: 'note', 'aria-live': 'polite' }),
      el('div', { id: 'map-legend', class: 'map-legend' }),
      el('details', { id: 'map-command-box' }, el('summary', {}, T('The same map on the command line')), el('pre', { id: 'map-command' })),
      el('details', { id: 'map-table-box' }, el('summary', {}, T('The map as a table')), el('div', { class: 'table-box' }, el('table', { id: 'map-table' }))));
    $('map-x-key').value = numericKeys().includes('geometry.rope_length') ? 'geometry.rope_length' : numericKeys()[0];
    $('map-y-key').value = numericKeys().includes('start.sandbag_height') ? 'start.sandbag_height' : numericKeys()[1];
    setRange('x');
    setRange('y');
    fillValueChoice();
    $('map-x-key').addEventListener('change', () => setRange('x'));
    $('map-y-key').addEventListener('change', () => setRange('y'));
    $('map-form').addEventListener('submit', (e) => { e.preventDefault(); draw().then(() => { $('map-command').textContent = m ? m.command : ''; }); });
    $('map-stop').addEventListener('click', stop);
    $('map-csv').addEventListener('click', download);
    $('map-value').addEventListener('change', () => { paint(); if ($('map-table-box').open) table(); });
    $('map-table-box').addEventListener('toggle', () => { if ($('map-table-box').open) table(); });
    const canvas = $('map-canvas');
    canvas.addEventListener('mousemove', (e) => showTip(cellAt(e), e));
    canvas.addEventListener('mouseleave', () => { $('map-tip').hidden = true; });
    // A mouse's click loads the machine it points at; a finger has no pointing, so its first tap
    // reads the cell and a second tap on it loads it.
    let tapped = null, touched = false;
    canvas.addEventListener('pointerdown', (e) => { touched = e.pointerType !== 'mouse'; });
    canvas.addEventListener('click', (e) => {
      const c = cellAt(e);
      if (!c || !m.done[c[0] * m.ny + c[1]]) return;
      if (touched && !(tapped && tapped[0] === c[0] && tapped[1] === c[1])) {
        tapped = c;
        showTip(c, e);
        return;
      }
      tapped = null;
      load(c[0], c[1]);
    });
    canvas.addEventListener('keydown', keydown);
    canvas.addEventListener('blur', () => { $('map-tip').hidden = true; });
    new ResizeObserver(() => layout()).observe($('map-box'));
    // The machine shown changed (app.js counts its runs on the body): its mark moves.
    new MutationObserver(machineChanged).observe(document.body, { attributes: true, attributeFilter: ['data-runs'] });
    new MutationObserver(layout).observe(document.body, { attributes: true, attributeFilter: ['class'] });  // projector mode
    layout();
  }

  window.whatnextMap = {
    // app: {keys, input(), base(), sets(), run(), load(sets)}, from app.js once the page is up.
    attach(hooks) {
      app = hooks;
      const section = $('map');
      if (section) build(section);
      startWorkers();
    },
    phaseTable,
    columns(callback) { if (columns) callback(columns); else onColumns = callback; startWorkers(); },
    // For the tests and web/tests/map-bench.js.
    get state() { return m && { id: m.id, size: m.size, finished: m.finished, ms: m.ms, workers: pool.length, command: m.command, nx: m.nx, ny: m.ny }; },
    csv: () => csvText(),
    describe: (ix, iy) => describe(ix, iy),
    cellPixel(ix, iy) {  // where cell (ix, iy)'s centre is on the map's canvas, in CSS pixels
      const f = frame();
      return { x: f.x0 + (ix + 0.5) * f.w / m.nx, y: f.y0 + (m.ny - iy - 0.5) * f.h / m.ny };
    },
    marker: () => (m && m.size && ofTheMap() ? marker(frame()) : null),
  };
})();
