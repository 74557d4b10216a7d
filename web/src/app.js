// The page: one machine (a shipped example or a file, plus `--set` changes), run by the library in
// WebAssembly at every change; the drawing, the timeline, the plots and a second run to compare,
// all at one time that the player, the scrubber, the keyboard and the plots move.
(async function () {
  'use strict';

  const $ = (id) => document.getElementById(id);
  const Machine = window.whatnextMachine;
  const wasm = await createWhatnext();
  const presets = wasm.presets(), keys = wasm.keys(), names = wasm.names();
  // Longest first, so that a message naming balloon.drag_coefficient is not read as balloon.drag.
  const keyNames = keys.map((k) => k.key).sort((a, b) => b.length - a.length);
  const kHoldMs = 1000;  // an event's frame stays this long when playing
  const icon = (d) => `<svg viewBox="0 0 24 24" aria-hidden="true"><path d="${d}"/></svg>`;
  const kPlayIcon = `${icon('M7 4v16l13-8z')} Play`, kPauseIcon = `${icon('M6 4h4v16H6zM14 4h4v16h-4z')} Pause`;

  // The library's answer, or its failure as one (a wasm abort, out of memory) instead of an exception.
  function call(fn, input) {
    try {
      return fn(input);
    } catch (e) {
      return { ok: false, kind: 'error', message: `the WebAssembly module failed (${e.message || e}); reload the page` };
    }
  }

  const st = {
    base: presets[0],     // {id, title, toml, source, label, cli, format}
    sets: new Map(),      // key -> value as typed: the command line's --set KEY=VALUE
    good: new Map(),      // the sets of the run shown (the last one that ran)
    run: null,
    committed: null, previous: null,  // machines before and after the last finished change
    compare: { mode: 'none', law: 'kinetic-energy', step: '0.001', run: null, label: '', message: '' },
    t: 0, playing: false, speed: 'auto', holdUntil: 0, last: 0,
    view: null, dpr: 1, font: 16, lines: 1, band: 46, aspect: 0.7, runMs: 0, runs: 0, problem: '',
  };

  // ---- running the library --------------------------------------------------------------------

  function inputFor(base, sets, extra = []) {
    return {
      toml: base.toml, source: base.source, label: base.label, format: base.format || 'toml',
      sets: [...sets].map(([k, v]) => `${k}=${v}`).concat(extra),
    };
  }

  function prepare(r) {
    r.tEnd = r.outcome.t;
    const radio = r.events.find((e) => e.type === 'radio_on');
    r.radioOnAt = radio ? radio.t : null;
    return r;
  }

  // Runs the machine as it stands. A bad input leaves the last good run on screen and says why.
  function simulate(editedKey) {
    const t0 = performance.now();
    const r = call(wasm.run, inputFor(st.base, st.sets));
    const ms = performance.now() - t0;
    panel.clearErrors();
    if (!r.ok) {
      showProblem(r, editedKey);
      return false;
    }
    $('problem').hidden = true;
    st.run = prepare(r);
    st.good = new Map(st.sets);
    st.runMs = ms;
    st.runs += 1;
    st.t = Math.min(st.t, st.run.tEnd);
    runCompare();
    showRun();
    return true;
  }

  // The key a message is about: the first known key it names.
  function keyIn(message) {
    let best = null, at = Infinity;
    for (const key of keyNames) {
      const re = new RegExp(`(^|[^\\w.])${key.replace(/\./g, '\\.')}(?![\\w])`);
      const m = re.exec(message);
      if (m && m.index < at) { at = m.index; best = key; }
    }
    return best;
  }

  function showProblem(r, editedKey) {
    st.problem = r.message;
    const key = keyIn(r.message);
    if (key) panel.showError(key, r.message);
    if (editedKey && editedKey !== key) panel.showError(editedKey, r.message);
    const what = r.kind === 'simulation' ? 'This machine cannot be run' : 'Not run';
    $('problem').textContent = `${what}: ${r.message}. The drawing and plots still show the last run that worked.`;
    $('problem').hidden = false;
  }

  const sameMachine = (a, b) => a && b && a.base === b.base && JSON.stringify([...a.sets]) === JSON.stringify([...b.sets]);

  // Remembers the machine after a finished change (a field left, a slider let go), so that "the
  // previous parameters" can show the one before.
  function commitChange() {
    const now = { base: st.base, sets: new Map(st.good) };
    if (st.committed && !sameMachine(st.committed, now)) st.previous = st.committed;
    st.committed = now;
    if (st.compare.mode === 'previous') {
      runCompare();
      showRun();
    }
    writeUrl();
  }

  function runCompare() {
    const c = st.compare;
    c.run = null;
    c.message = '';
    let input = null;
    if (c.mode === 'law') {
      input = inputFor(st.base, st.good, [`run.impact_law=${c.law}`]);
      c.label = `impact law ${c.law}`;
    } else if (c.mode === 'euler') {
      input = inputFor(st.base, st.good, ['run.integrator=euler', `run.step=${c.step}`]);
      c.label = `Euler, step ${c.step} s`;
    } else if (c.mode === 'previous') {
      // While a change is under way (a slider moving) the machine before it; after it, the one
      // before the last change.
      const shown = { base: st.base, sets: st.good };
      const before = st.committed && !sameMachine(st.committed, shown) ? st.committed : st.previous;
      if (before) input = inputFor(before.base, before.sets);
      else c.message = 'Change a parameter: the run before the change is then drawn dashed.';
      c.label = 'previous parameters';
    }
    if (!input) return;
    const r = call(wasm.run, input);
    if (r.ok) c.run = prepare(r);
    else c.message = `Nothing to compare with: ${r.message}`;
  }

  // ---- showing a run ----------------------------------------------------------------------------

  const canvas = $('machine'), ctx = canvas.getContext('2d');
  const plots = window.whatnextPlots.create({ onSeek: (t) => { pause(); seek(t); } });
  const panel = window.whatnextPanel.create($('fields'), keys, names, onField);

  function showRun() {
    const run = st.run;
    st.view = null;
    showTimeline();
    $('outcome').textContent = `Outcome: ${run.outcome.sentence}.`;
    const c = st.compare;
    $('compare-outcome').hidden = c.mode === 'none';
    $('compare-outcome').textContent = c.run ? `Dashed, ${c.label}: ${c.run.outcome.sentence}.` : c.message;
    $('compare-note').textContent = c.run ? 'dashed in the plots, blue outline in the drawing' : '';
    plots.show(run, c.run);
    panel.show(run.values, st.sets);
    showTicks();
    showCommandLine();
    $('perf').textContent = `Last run: ${st.runMs.toFixed(1)} ms in WebAssembly, ${run.events.length} events, ` +
                            `${run.samples.t.length} states.`;
    document.body.dataset.runs = String(st.runs);
    writeUrlSoon();
    render();
  }

  // The timeline as `whatnext run` prints it: its own lines, a row per event, and the energy
  // before and after an impact on a line of its own under the event.
  function showTimeline() {
    const run = st.run, lines = run.timeline.split('\n');
    const body = $('timeline').tBodies[0];
    body.textContent = '';
    run.events.forEach((e, i) => {
      const cells = lines[2 + i].trim().split(/\s+/);
      const row = body.insertRow();
      row.className = 'event';
      row.dataset.index = String(i);
      row.tabIndex = 0;
      cells.slice(0, 6).forEach((text, k) => {
        const cell = row.insertCell();
        cell.textContent = text;
        if (k === 1) cell.title = e.words;
      });
      if (e.stop) row.classList.add('stop');
      const go = () => { pause(); seek(e.t); };
      row.addEventListener('click', go);
      row.addEventListener('keydown', (ev) => { if (ev.key === 'Enter') go(); });
      if (cells.length > 6) {
        const note = body.insertRow();
        note.className = 'note';
        note.dataset.index = String(i);
        const cell = note.insertCell();
        cell.colSpan = 6;
        cell.textContent = cells.slice(6).join(' ');
        note.addEventListener('click', go);
      }
    });
  }

  function showTicks() {
    const ticks = $('ticks');
    ticks.textContent = '';
    for (const g of st.run.groups) {
      const mark = document.createElement('span');
      mark.style.left = `${(100 * g.t) / st.run.tEnd}%`;
      mark.title = g.label;
      ticks.append(mark);
    }
    $('scrub').max = String(st.run.tEnd);
  }

  function shellWord(w) {
    return /^[\w.,=/:+-]+$/.test(w) ? w : `'${w.replace(/'/g, "'\\''")}'`;
  }

  function showCommandLine() {
    const sets = [...st.good].map(([k, v]) => `--set ${shellWord(`${k}=${v}`)}`);
    $('cli-command').textContent = ['$ whatnext run', st.base.cli, ...sets].join(' ');
    $('cli-text').textContent = st.run.timeline;
  }

  // ---- time: the player, the scrubber and the picture -------------------------------------------

  function groupAt(run, t) {
    return run.groups.find((g) => Math.abs(g.t - t) <= 1e-12 * Math.max(1, g.t)) || null;
  }

  // The canvas takes the shape of the machine's extent (set when a machine is chosen, not at every
  // change, so that the page does not jump while a slider moves), within the window's height.
  function sizeCanvas() {
    const width = $('canvas-box').clientWidth;
    st.font = Math.min(Math.max(width / 42, 13), 24);
    st.lines = width < 600 ? 2 : 1;  // a narrow caption wraps the event's words
    st.band = (1.8 + 1.1 * st.lines) * st.font;
    // At most three quarters of the window's height, but never less than the caption and a
    // picture below it (a short window, or one not laid out yet, has almost no height).
    const height = Math.round(Math.max(Math.min(Math.max(st.aspect * width + st.band, 240), 0.75 * window.innerHeight),
                                       st.band + 150));
    st.dpr = window.devicePixelRatio || 1;
    canvas.style.height = `${height}px`;
    canvas.width = Math.round(width * st.dpr);
    canvas.height = Math.round(height * st.dpr);
    st.view = null;
  }

  function fitCanvas() {
    const box = Machine.extent(st.run);
    st.aspect = Math.min(Math.max((box.h1 - box.h0) / (box.x1 - box.x0), 0.45), 1.4);
    sizeCanvas();
    render();
  }

  // Simulated seconds per second on screen. "auto" does what the animation does: slow motion
  // (×10) near the events, and a quiet stretch between them crossed in about two seconds.
  const kSlow = 0.1, kPad = 0.3;
  function speedAt(t) {
    if (st.speed !== 'auto') return st.speed;
    const times = [0, ...st.run.groups.map((g) => g.t), st.run.tEnd];
    const b = times.find((x) => x > t);
    const a = [...times].reverse().find((x) => x <= t);
    if (b === undefined || t - a < kPad || b - t < kPad) return kSlow;
    return Math.max(kSlow, (b - a - 2 * kPad) / 2);
  }

  function speedWords() {
    if (!st.playing) return st.t >= st.run.tEnd ? 'end of the run (Space plays it again)' : 'paused (Space plays)';
    const v = speedAt(st.t);
    if (Math.abs(v - 1) < 1e-9) return 'real time';
    const words = v < 1 ? `slow motion ×${Number((1 / v).toPrecision(2))}` : `fast forward ×${Number(v.toPrecision(2))}`;
    return st.speed === 'auto' && v > kSlow ? `quiet stretch: ${words}` : words;
  }

  function render() {
    const run = st.run;
    if (!run) return;
    if (!st.view) {
      st.view = Machine.makeView(run, canvas.width / st.dpr, canvas.height / st.dpr, st.band);
    }
    const s = Machine.stateAt(run.samples, st.t);
    const group = groupAt(run, st.t);
    const caption = [
      `t = ${st.t.toFixed(3)} s    ${names.modes[s.mode]}`,
      group ? `event at ${group.t.toFixed(3)} s: ${group.events.map((i) => run.events[i].words).join(' + ')}` : speedWords(),
    ];
    const other = st.compare.run;
    const ghost = other ? { run: other, state: Machine.stateAt(other.samples, Math.min(st.t, other.tEnd)) } : null;
    ctx.setTransform(st.dpr, 0, 0, st.dpr, 0, 0);
    Machine.draw(ctx, st.view, { run, state: s, ghost, caption, event: group, font: st.font, lines: st.lines });

    $('clock').textContent = `t = ${st.t.toFixed(6)} s`;
    const scrub = $('scrub');
    if (document.activeElement !== scrub || st.playing) scrub.value = String(st.t);
    if ($('play').dataset.playing !== String(st.playing)) {
      $('play').dataset.playing = String(st.playing);
      $('play').innerHTML = st.playing ? kPauseIcon : kPlayIcon;
    }
    for (const row of $('timeline').tBodies[0].rows) {
      const e = run.events[Number(row.dataset.index)];
      row.classList.toggle('now', Boolean(group) && group.events.includes(Number(row.dataset.index)));
      row.classList.toggle('past', e.t < st.t && !(group && group.t === e.t));
    }
    plots.setTime(st.t);
  }

  function seek(t) {
    st.t = Math.min(Math.max(0, t), st.run.tEnd);
    st.holdUntil = 0;
    render();
  }

  function play() {
    if (st.t >= st.run.tEnd) st.t = 0;
    st.playing = true;
    st.last = performance.now();
    render();
  }

  function pause() {
    st.playing = false;
    st.holdUntil = 0;
    render();
  }

  function jumpEvent(direction) {
    pause();
    const eps = 1e-12 * Math.max(1, st.t);
    const groups = st.run.groups;
    const g = direction > 0 ? groups.find((x) => x.t > st.t + eps) : [...groups].reverse().find((x) => x.t < st.t - eps);
    seek(g ? g.t : direction > 0 ? st.run.tEnd : 0);
  }

  // The player: simulated time runs at the chosen speed and stops for a moment at each event.
  function tick(now) {
    if (st.playing && st.run) {
      const dt = Math.min(0.1, (now - st.last) / 1000);
      st.last = now;
      if (now >= st.holdUntil) {
        let t = st.t + dt * speedAt(st.t);
        const next = st.run.groups.find((g) => g.t > st.t);
        if (next && next.t <= t) {
          t = next.t;
          st.holdUntil = now + kHoldMs;
        }
        if (t >= st.run.tEnd) {
          t = st.run.tEnd;
          st.playing = false;
        }
        st.t = t;
        render();
      }
    }
    requestAnimationFrame(tick);
  }

  // ---- changes ----------------------------------------------------------------------------------

  function onField(key, text, commit) {
    st.sets.delete(key);  // a changed key moves to the end: later --set wins, as on the command line
    if (text !== null) st.sets.set(key, text);
    if (simulate(key) && commit) commitChange();
  }

  function choose(base, sets) {
    const old = { base: st.base, sets: st.sets };
    st.base = base;
    st.sets = new Map(sets);
    st.t = 0;
    pause();
    if (!simulate(null)) {
      if (!st.run) return false;
      st.base = old.base;  // a file that does not load: stay with the machine shown
      st.sets = old.sets;
      showPresetChoice();
      return false;
    }
    showPresetChoice();
    fitCanvas();
    commitChange();
    return true;
  }

  function showPresetChoice() {
    const select = $('preset');
    select.textContent = '';
    for (const p of presets) select.append(new Option(p.title, p.id));
    if (st.base.id === 'file') select.append(new Option(`file: ${st.base.title}`, 'file'));
    select.value = st.base.id;
  }

  function fileBase(name, text) {
    return { id: 'file', title: name, toml: text, source: name, label: name, cli: shellWord(name),
             format: /\.inp$/i.test(name) ? 'inp' : 'toml' };
  }

  // ---- the URL: the machine, the comparison and the time ------------------------------------------

  const toBase64 = (text) => btoa(String.fromCharCode(...new TextEncoder().encode(text)))
    .replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
  const fromBase64 = (b64) => new TextDecoder().decode(
    Uint8Array.from(atob(b64.replace(/-/g, '+').replace(/_/g, '/')), (c) => c.charCodeAt(0)));

  // The link follows the machine on screen. Browsers limit how often a page may rewrite it (Safari
  // refuses more than 100 times in 30 s, Chromium ignores calls beyond 200 in 10 s) and each write
  // is slow (8 ms in Chromium), so while a slider moves it is written at most every 250 ms, and at
  // once when a change is finished.
  let urlWritten = -Infinity, urlTimer = null;
  function writeUrlSoon() {
    if (urlTimer !== null) return;
    const wait = urlWritten + 250 - performance.now();
    if (wait <= 0) writeUrl(); else urlTimer = setTimeout(writeUrl, wait);
  }

  function writeUrl() {
    clearTimeout(urlTimer);
    urlTimer = null;
    urlWritten = performance.now();
    const p = new URLSearchParams();
    if (st.base.id === 'file') {
      p.set('file', st.base.title);
      p.set('text', toBase64(st.base.toml));
    } else {
      p.set('machine', st.base.id);
    }
    for (const [k, v] of st.good) p.append(k, v);
    const c = st.compare;
    if (c.mode === 'law') p.set('compare', `law:${c.law}`);
    if (c.mode === 'euler') p.set('compare', `euler:${c.step}`);
    history.replaceState(null, '', `#${p.toString()}`);
  }

  function readUrl() {
    const p = new URLSearchParams(location.hash.slice(1));
    let base = presets.find((x) => x.id === p.get('machine')) || presets[0];
    if (p.has('text')) {
      try {
        base = fileBase(p.get('file') || 'machine.toml', fromBase64(p.get('text')));
      } catch (e) {
        base = presets[0];
      }
    }
    const sets = [];
    for (const [k, v] of p) if (k.includes('.')) sets.push([k, v]);
    const compare = (p.get('compare') || '').split(':');
    return { base, sets, compare };
  }

  // ---- downloads --------------------------------------------------------------------------------

  function download(kind) {
    const input = inputFor(st.base, st.good);
    const stem = (st.base.id === 'file' ? st.base.title.replace(/\.[^.]*$/, '') : st.base.id) + (st.good.size ? '-changed' : '');
    if (kind === 'csv') {
      const rows = st.run.machine.run.t_max / st.run.machine.run.output_step;
      if (rows > 2e6) {
        alert(`That CSV would have ${Math.round(rows)} rows: too many for a browser. Raise run.output_step, or use ` +
              `the command line (see "The same run on the command line").`);
        return;
      }
    }
    const r = call(kind === 'toml' ? wasm.toml : kind === 'json' ? wasm.events : wasm.csv, input);
    if (!r.ok) {
      alert(r.message);
      return;
    }
    const name = kind === 'toml' ? `${stem}.toml` : kind === 'json' ? `${stem}-events.json` : `${stem}.csv`;
    const type = kind === 'json' ? 'application/json' : kind === 'csv' ? 'text/csv' : 'application/toml';
    const a = document.createElement('a');
    a.href = URL.createObjectURL(new Blob([r.text], { type }));
    a.download = name;
    document.body.append(a);
    a.click();
    a.remove();
    setTimeout(() => URL.revokeObjectURL(a.href), 10000);
  }

  function toast(text) {
    const t = document.createElement('div');
    t.className = 'toast';
    t.textContent = text;
    document.body.append(t);
    setTimeout(() => t.remove(), 2500);
  }

  // ---- wiring -----------------------------------------------------------------------------------

  $('preset').addEventListener('change', (e) => {
    const p = presets.find((x) => x.id === e.target.value);
    if (p) choose(p, []);
  });
  $('open').addEventListener('click', () => $('file').click());
  $('file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (!f) return;
    choose(fileBase(f.name, await f.text()), []);
    e.target.value = '';
  });
  $('reset-all').addEventListener('click', () => choose(st.base, []));
  $('share').addEventListener('click', async () => {
    writeUrl();
    try {
      await navigator.clipboard.writeText(location.href);
      toast('Link copied: it opens this machine.');
    } catch (e) {
      prompt('Copy this link; it opens this machine:', location.href);
    }
  });
  $('dl-toml').addEventListener('click', () => download('toml'));
  $('dl-json').addEventListener('click', () => download('json'));
  $('dl-csv').addEventListener('click', () => download('csv'));
  $('help').addEventListener('click', () => $('keys-help').showModal());

  $('play').addEventListener('click', () => (st.playing ? pause() : play()));
  $('to-start').addEventListener('click', () => { pause(); seek(0); });
  $('prev-event').addEventListener('click', () => jumpEvent(-1));
  $('next-event').addEventListener('click', () => jumpEvent(1));
  const readSpeed = (text) => (text === 'auto' ? 'auto' : Number(text));
  $('speed').addEventListener('change', (e) => { st.speed = readSpeed(e.target.value); render(); });
  $('scrub').addEventListener('input', (e) => { st.playing = false; seek(Number(e.target.value)); });

  function showCompareControls() {
    const c = st.compare;
    $('compare').value = c.mode;
    $('compare-law').hidden = c.mode !== 'law';
    $('compare-law').value = c.law;
    $('compare-step-box').hidden = c.mode !== 'euler';
    $('compare-step').value = c.step;
  }
  for (const law of names['run.impact_law']) $('compare-law').append(new Option(law, law));
  const compareChanged = () => {
    showCompareControls();
    runCompare();
    showRun();
    writeUrl();
  };
  $('compare').addEventListener('change', (e) => { st.compare.mode = e.target.value; compareChanged(); });
  $('compare-law').addEventListener('change', (e) => { st.compare.law = e.target.value; compareChanged(); });
  $('compare-step').addEventListener('input', (e) => { st.compare.step = e.target.value.trim(); compareChanged(); });

  document.addEventListener('keydown', (e) => {
    const target = e.target;
    const typing = target instanceof HTMLInputElement && target.type !== 'range' && target.type !== 'checkbox' ||
                   target instanceof HTMLSelectElement || target instanceof HTMLTextAreaElement;
    if (typing || e.ctrlKey || e.metaKey || e.altKey || !st.run) return;
    const steps = { ArrowRight: 1e-3, ArrowLeft: -1e-3 };
    if (e.key === ' ' && !(target instanceof HTMLButtonElement)) {
      if (st.playing) pause(); else play();
    } else if (e.key in steps && target.type !== 'range') {
      pause();
      seek(st.t + steps[e.key] * (e.shiftKey ? 10 : 1));
    } else if (e.key === 'PageDown' || e.key === ']') {
      jumpEvent(1);
    } else if (e.key === 'PageUp' || e.key === '[') {
      jumpEvent(-1);
    } else if (e.key === 'Home' && target.type !== 'range') {
      pause(); seek(0);
    } else if (e.key === 'End' && target.type !== 'range') {
      pause(); seek(st.run.tEnd);
    } else if (e.key === '+' || e.key === '-') {
      // Through the fixed speeds, fastest first; from "auto" as from its slow motion.
      const speeds = [...$('speed').options].map((o) => readSpeed(o.value)).filter((v) => v !== 'auto');
      const i = speeds.indexOf(st.speed === 'auto' ? kSlow : st.speed) + (e.key === '+' ? -1 : 1);
      st.speed = speeds[Math.min(Math.max(i, 0), speeds.length - 1)];
      $('speed').value = String(st.speed);
      render();
    } else if (e.key === '?') {
      $('keys-help').showModal();
    } else {
      return;
    }
    e.preventDefault();
  });

  new ResizeObserver(() => { sizeCanvas(); render(); }).observe($('canvas-box'));
  // A link pasted into this tab (or the address edited): open its machine as a new page would.
  // The page's own link updates (history.replaceState) do not fire this.
  window.addEventListener('hashchange', () => location.reload());
  window.addEventListener('pagehide', () => { if (urlTimer !== null) writeUrl(); });
  new ResizeObserver(() => plots.resize()).observe($('plots'));

  // ---- start: the machine of the link, or example 1 -----------------------------------------------

  const start = readUrl();
  if (start.compare[0] === 'law' && names['run.impact_law'].includes(start.compare[1])) {
    Object.assign(st.compare, { mode: 'law', law: start.compare[1] });
  } else if (start.compare[0] === 'euler' && start.compare[1]) {
    Object.assign(st.compare, { mode: 'euler', step: start.compare[1] });
  }
  showCompareControls();
  sizeCanvas();
  st.base = start.base;
  st.sets = new Map(start.sets);
  showPresetChoice();
  if (!simulate(null)) {
    // A link whose changes do not run: its machine without them, and why.
    const problem = st.problem;
    st.sets = new Map();
    if (!simulate(null)) {
      st.base = presets[0];
      simulate(null);
    }
    $('problem').textContent = `The link's machine does not run (${problem}); this is ${st.base.title} without its changes.`;
    $('problem').hidden = false;
    showPresetChoice();
  }
  fitCanvas();
  commitChange();
  requestAnimationFrame(tick);

  // For the tests and the curious: the page's state and its mapping to the canvas.
  window.whatnext = {
    get time() { return st.t; },
    get run() { return st.run; },
    seek: (t) => { pause(); seek(t); },
    stateAt: (t) => Machine.stateAt(st.run.samples, t),
    canvasPixel: (x, h) => {
      const p = Machine.toPixel(st.view, { x, h });
      return { x: p.x * st.dpr, y: p.y * st.dpr };
    },
    // Milliseconds for one run of a shipped machine (as the page runs it at every change).
    timeRun: (id, repeat) => {
      const input = inputFor(presets.find((x) => x.id === id), []);
      const times = [];
      for (let i = 0; i < repeat; ++i) {
        const t0 = performance.now();
        wasm.run(input);
        times.push(performance.now() - t0);
      }
      return times.sort((a, b) => a - b);
    },
  };
  document.body.dataset.ready = 'true';
})();
