// The page: one machine (a shipped example or a file, plus `--set` changes), run by the library in
// WebAssembly at every change; the drawing, the timeline, the plots and a second run to compare,
// all at one time that the player, the scrubber, the keyboard and the plots move. The library runs
// in a Web Worker (worker.js), so that the page stays responsive while it works.
(async function () {
  'use strict';

  const $ = (id) => document.getElementById(id);
  // The page's words (one table per language: strings.js).
  const S = window.whatnextStrings;
  const T = (english, args) => S.t(english, args);
  S.translatePage(document.body);
  document.title = S.t(document.title);
  const Machine = window.whatnextMachine;

  // ---- the worker -----------------------------------------------------------------------------
  // One request at a time goes to it; a run that takes long shows its progress and can be
  // stopped, which ends the worker and starts a new one.
  let worker = null, nextId = 1;
  const waiting = new Map();  // id -> resolve
  const progress = { since: 0, t: null, tMax: null, timer: null };

  function makeWorker() {
    // The single-file page holds the library (whatnext-module, which this thread runs too) and the
    // worker's own script as text: the worker is both, as a blob.
    const inlined = document.getElementById('worker-source');
    if (!inlined) return new Worker('worker.js');
    const source = [document.getElementById('whatnext-module').textContent, inlined.textContent].join('\n');
    return new Worker(URL.createObjectURL(new Blob([source], { type: 'text/javascript' })));
  }

  function startWorker() {
    worker = makeWorker();
    return new Promise((resolve, reject) => {
      worker.onmessage = (e) => {
        const d = e.data;
        if (d.hello) resolve(d.hello);
        else if (d.progress !== undefined) progress.t = d.progress;
        else {
          const done = waiting.get(d.id);
          waiting.delete(d.id);
          if (done) done(d.result);
        }
      };
      worker.onerror = (e) => {
        e.preventDefault();
        reject(new Error(e.message || T('the worker did not start')));
        // A worker that dies while working: every open request gets a message instead of a hang.
        for (const done of waiting.values()) done({ ok: false, kind: 'error', message: `the WebAssembly module failed (${e.message})` });
        waiting.clear();
      };
    });
  }

  function ask(fn, input, tMax = null, quiet = false) {
    return new Promise((resolve) => {
      const id = nextId++;
      waiting.set(id, (r) => {
        hideProgress();
        // A failed module is not used again: a fresh worker for the next request.
        if (r && r.kind === 'error' && /WebAssembly module failed/.test(r.message || '')) restartWorker();
        resolve(r);
      });
      worker.postMessage({ id, fn, input });
      if (!quiet) showProgressSoon(tMax);
    });
  }

  function restartWorker() {
    worker.terminate();
    for (const done of waiting.values()) done({ ok: false, kind: 'stopped' });
    waiting.clear();
    return startWorker();
  }

  // The progress box appears when a request has taken 300 ms; it says how far the run is (the
  // samples' time as the worker reports it) and how long it has taken, and holds the Stop button.
  function showProgressSoon(tMax) {
    progress.since = performance.now();
    progress.t = null;
    progress.tMax = tMax;
    clearInterval(progress.timer);
    progress.timer = setInterval(() => {
      const ms = performance.now() - progress.since;
      if (ms < 300) return;
      const box = $('progress');
      box.hidden = false;
      const tMaxNow = progress.tMax;
      const share = progress.t !== null && tMaxNow ? Math.min(1, progress.t / tMaxNow) : null;
      $('progress-bar').value = share === null ? 0 : share;
      if (share === null) $('progress-bar').removeAttribute('value');
      $('progress-text').textContent = T('Running… {where}{secs} s so far.', {
        secs: (ms / 1000).toFixed(1),
        where: progress.t !== null && tMaxNow ? T('t = {t} s of {tMax} s; ', { t: progress.t.toFixed(3), tMax: tMaxNow }) : '',
      });
    }, 100);
  }

  function hideProgress() {
    clearInterval(progress.timer);
    progress.timer = null;
    $('progress').hidden = true;
  }


  let hello;
  try {
    hello = await startWorker();
  } catch (e) {
    // index.html opened from the disk: browsers do not start a worker from a file:// folder.
    $('outcome').textContent = T('This page cannot start its worker here ({why}). Opened from a folder on the disk, use whatnext.html (the page in one file); or serve the folder (./run.sh web).', { why: e.message || String(e) });
    document.body.dataset.failed = 'true';
    return;
  }
  const { presets, keys, names } = hello;
  // The library on this thread too: the drawing's geometry is its scene (machine.js).
  Machine.useLibrary(await createWhatnext());
  // Longest first, so that a message naming balloon.drag_coefficient is not read as balloon.drag.
  const keyNames = keys.map((k) => k.key).sort((a, b) => b.length - a.length);
  const kHoldMs = 1000;
  const kMaxFileBytes = 1 << 20;
  // What each shipped machine shows (its comment in examples/), for the machine choice.
  const kPresetWhat = {
    example1: 'one hard pull of the rope opens the lid',
    example2: 'the taut rope pulls the lid open',
    example3: 'sandbag on the level seesaw: the lid never opens',
    example4: 'a hard hit throws the lid up; it never opens',
    radio: 'the balloon switches the radio on',
    konstanz: 'built with a real party balloon: the radio stays off',
  };
  const kPresetShort = { radio: 'Example 1 + radio', konstanz: 'Konstanz (built)' };  // the others: their title  // the command line reads machine files of at most 1 MiB  // an event's frame stays this long when playing
  const icon = (d) => `<svg viewBox="0 0 24 24" aria-hidden="true"><path d="${d}"/></svg>`;
  const kPlayIcon = `${icon('M7 4v16l13-8z')} ${T('Play')}`, kPauseIcon = `${icon('M6 4h4v16H6zM14 4h4v16h-4z')} ${T('Pause')}`;


  const st = {
    base: presets[0],     // {id, title, toml, source, label, cli, format}
    sets: new Map(),      // key -> value as typed: the command line's --set KEY=VALUE
    good: new Map(),      // the sets of the run shown (the last one that ran)
    run: null,
    committed: null, previous: null,  // machines before and after the last finished change
    compare: { mode: 'none', law: 'kinetic-energy', step: '0.001', run: null, runs: [], label: '', message: '' },
    t: 0, playing: false, speed: 'auto', holdUntil: 0, last: 0,
    view: null, dpr: 1, font: 16, lines: 1, band: 46, aspect: 0.7, runMs: 0, runs: 0, answers: 0, problem: '', caption: '',
    forces: false, drawnForces: null, described: '', announced: null, ghost: 0,
  };
  const Teach = window.whatnextTeach;

  // Changes come faster than a slow run: the newest change waits while one runs, and replaces any
  // change waiting before it (which would be shown only to be overwritten). A machine chosen is
  // never dropped. body[data-busy] is "true" while anything is running or waiting (for the tests).
  const queue = { busy: false, next: null, commit: false };
  function schedule(job, keep = false) {
    const before = queue.next;
    const wrapped = before && before.keep ? async () => { await before(); await job(); } : job;
    wrapped.keep = keep || Boolean(before && before.keep);
    queue.next = wrapped;
    document.body.dataset.busy = 'true';
    if (!queue.busy) pump();
  }
  async function pump() {
    queue.busy = true;
    for (;;) {
      while (queue.next) {
        const job = queue.next;
        queue.next = null;
        try {
          await job();
        } catch (e) {
          console.error(e);
        }
      }
      if (!queue.next) break;
    }
    queue.busy = false;
    document.body.dataset.busy = 'false';
    // Once the machine has stood still a moment (not at every step of a slider: each check is
    // most of a second of work).
    clearTimeout(checkTimer);
    checkTimer = setTimeout(checkSliders, 400);
  }
  let checkTimer = null;

  // Where the sliders reach values the library refuses, for the machine as it now stands: a
  // second worker checks ~1,200 inputs (no runs, most of a second), so that the runs never wait.
  let checker = null, checkedFor = null, checking = false;
  function checkSliders() {
    const machine = JSON.stringify([st.base.id, st.base.toml, [...st.good]]);
    if (!st.run || checkedFor === machine || checking) return;
    checkedFor = machine;
    checking = true;
    if (!checker) checker = makeWorker();
    const t0 = performance.now();
    checker.onmessage = (e) => {
      if (e.data.id !== 'validity') return;
      checking = false;
      document.body.dataset.validityMs = String(Math.round(performance.now() - t0));
      const valid = e.data.result;
      if (valid && valid.ok !== false && checkedFor === machine) {
        panel.showValidity(valid);
        document.body.dataset.checked = machine;
      }
      checkSliders();  // the machine changed meanwhile
    };
    checker.postMessage({ id: 'validity', fn: 'validity', input: { input: inputFor(st.base, st.good), probes: panel.probes() } });
  }

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

  // A run in the worker. A fixed-step run of millions of steps is asked about first (the
  // question box); one that takes long shows its progress and can be stopped.
  async function runAsked(input, what) {
    const tMax = st.run ? st.run.machine.run.t_max : null;
    // A run keeps its input: the drawing asks the library for the scene of this machine.
    const kept = (r) => (r.ok ? Object.assign(r, { input }) : r);
    const r = kept(await ask('run', input, tMax));
    if (r.ok || r.kind !== 'budget') return r;
    const go = await askBudget(r, what);
    if (!go) return { ok: false, kind: 'declined', message: T('not started ({steps} steps)', { steps: r.steps.toExponential(1) }) };
    return kept(await ask('run', { ...input, force: true }, r.t_max));
  }

  // The question before a long fixed-step run: resolves true to run it, false not to.
  function askBudget(r, what) {
    return new Promise((resolve) => {
      const box = $('budget');
      $('budget-text').textContent = T('{what} takes {steps} steps of the {integrator} method (t_max {tMax} s at a step of {step} s): the page may work on it for minutes. Run it anyway? (It can be stopped.)', {
        what, steps: r.steps.toExponential(1), integrator: r.integrator, tMax: r.t_max, step: r.step,
      });
      const done = (yes) => {
        $('budget-run').onclick = $('budget-cancel').onclick = null;
        box.onclose = null;
        if (box.open) box.close();
        resolve(yes);
      };
      $('budget-run').onclick = () => done(true);
      $('budget-cancel').onclick = () => done(false);
      box.onclose = () => done(false);  // Escape
      box.showModal();
    });
  }

  function answered() {
    st.answers += 1;
    document.body.dataset.answers = String(st.answers);
  }

  // Runs the machine as it stands. A bad input leaves the last good run on screen and says why.
  async function simulate(editedKey) {
    const t0 = performance.now();
    const r = await runAsked(inputFor(st.base, st.sets), T('This run'));
    const ms = performance.now() - t0;
    panel.clearErrors();
    if (!r.ok) {
      showProblem(r, editedKey);
      answered();
      return false;
    }
    $('problem').hidden = true;
    markStale(false);
    st.run = prepare(r);
    st.good = new Map(st.sets);
    st.runMs = ms;
    st.runs += 1;
    st.t = Math.min(st.t, st.run.tEnd);
    await runCompare();
    showRun();
    answered();
    return true;
  }

  // The drawing, the timeline and the plots belong to the last run that worked; when the panel
  // holds values that did not run, they say so instead of passing for the panel's machine.
  function markStale(stale) {
    $('layout').classList.toggle('stale', stale);
    $('stale-note').hidden = !stale;
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

  // The library's message without the command line's "--set KEY=VALUE: " in front: in the page
  // the value is in its field, and the message stands next to it.
  function pageWords(message) {
    for (const [k, v] of st.sets) {
      const prefix = `--set ${k}=${v}: `;
      if (message.startsWith(prefix)) return message.slice(prefix.length);
    }
    // The comparison's own settings, and a key the library does not know ("--set: unknown key").
    return message.replace(/^--set( [\w.]+=[^:]*)?: /, '');
  }

  function showProblem(r, editedKey) {
    if (r.message) r = { ...r, message: pageWords(r.message) };
    st.problem = r.kind === 'stopped' ? T('Stopped before the run was done') : S.sentence(r.message);
    const key = r.kind === 'stopped' ? null : keyIn(r.message);
    if (key) panel.showError(key, S.sentence(r.message));
    if (editedKey && editedKey !== key) panel.showError(editedKey, S.sentence(r.message));
    const what = r.kind === 'simulation' ? T('This machine cannot be run') : r.kind === 'stopped' ? T('Stopped before the run was done')
               : r.kind === 'declined' ? T('Not started') : T('Not run');
    const message = r.kind === 'stopped' ? '' : `: ${S.sentence(r.message)}`;
    $('problem').textContent = `${what}${message}. ${st.run ? T('The drawing and plots still show the last run that worked.') : ''}`;
    $('problem').hidden = false;
    if (st.run) markStale(true);
  }

  const sameMachine = (a, b) => a && b && a.base === b.base && JSON.stringify([...a.sets]) === JSON.stringify([...b.sets]);

  // Remembers the machine after a finished change (a field left, a slider let go), so that "the
  // previous parameters" can show the one before.
  function commitChange() {
    const now = { base: st.base, sets: new Map(st.good) };
    if (st.committed && !sameMachine(st.committed, now)) st.previous = st.committed;
    st.committed = now;
    if (st.compare.mode === 'previous') {
      schedule(async () => { await runCompare(); showRun(); });
    }
    writeUrl();
  }

  // The other runs' colours in the drawing and their dashes in the plots ("all four laws": one
  // each for the three laws the machine does not use).
  const kGhosts = [{ colour: 'rgb(60,90,200)', dash: [8, 5] }, { colour: 'rgb(15,120,50)', dash: [2, 3] },
                   { colour: 'rgb(150,40,170)', dash: [12, 4, 2, 4] }];

  // Whether the machine shown has a rope that stretches, or friction: its changes, else its run's values.
  const given = (key) => {
    const set = [...st.good].find(([k]) => k === key);
    const v = set ? set[1] : st.run && st.run.values ? st.run.values.effective[key] : undefined;
    return v !== undefined && v !== '' && Number(v) > 0;
  };
  const stretches = () => given('rope.stiffness');
  const rubs = () => given('friction.sandbag') || given('friction.pivot') || given('friction.lid_hinge');

  async function runCompare() {
    const c = st.compare;
    c.run = null;
    c.runs = [];
    c.message = '';
    let input = null;
    if (c.mode === 'laws') {
      // The machine's own law is the main run; the other three beside it.
      const own = st.run ? st.run.machine.run.impact_law : null;
      const messages = [];
      for (const law of names['run.impact_law'].filter((x) => x !== own)) {
        const r = await runAsked(inputFor(st.base, st.good, [`run.impact_law=${law}`]), T('The run to compare with'));
        if (r.ok) c.runs.push({ run: prepare(r), label: law, ...kGhosts[c.runs.length] });
        else messages.push(`${law}: ${r.kind === 'stopped' ? T('Stopped before the run was done') : S.sentence(pageWords(r.message))}`);
      }
      if (messages.length) c.message = T('Nothing to compare with: {message}', { message: messages.join('; ') });
      c.label = T('all four impact laws');
      return;
    }
    if (c.mode === 'law') {
      input = inputFor(st.base, st.good, [`run.impact_law=${c.law}`]);
      c.label = T('impact law {law}', { law: c.law });
    } else if (c.mode === 'euler') {
      input = inputFor(st.base, st.good, ['run.integrator=euler', `run.step=${c.step}`]);
      c.label = T('Euler, step {step} s', { step: S.decimals(c.step) });
    } else if (c.mode === 'rigid') {
      // The same machine with the paper's inextensible rope (docs/impact.md): the table's default
      // word for rope.stiffness is the key left out.
      if (!stretches()) c.message = T('This rope does not stretch: give it a stiffness (rope.stiffness) to compare it with the one that does not.');
      else input = inputFor(st.base, st.good, ['rope.stiffness=inextensible', 'rope.damping=0']);
      c.label = T('the rope that does not stretch');
    } else if (c.mode === 'frictionless') {
      if (!rubs()) c.message = T('This machine has no friction: give friction.sandbag, friction.pivot or friction.lid_hinge to compare it with none.');
      else input = inputFor(st.base, st.good, ['friction.sandbag=0', 'friction.pivot=0', 'friction.lid_hinge=0']);
      c.label = T('no friction');
    } else if (c.mode === 'previous') {
      // While a change is under way (a slider moving) the machine before it; after it, the one
      // before the last change.
      const shown = { base: st.base, sets: st.good };
      const before = st.committed && !sameMachine(st.committed, shown) ? st.committed : st.previous;
      if (before) input = inputFor(before.base, before.sets);
      else c.message = T('Change a parameter: the run before the change is then drawn dashed.');
      c.label = T('previous parameters');
    }
    if (!input) return;
    const r = await runAsked(input, T('The run to compare with'));
    if (r.ok) {
      c.run = prepare(r);
      c.runs = [{ run: c.run, label: T('dashed'), ...kGhosts[0] }];
    } else c.message = r.kind === 'stopped' ? T('Nothing to compare with: that run was stopped.') : T('Nothing to compare with: {message}', { message: S.sentence(pageWords(r.message)) });
  }

  // ---- showing a run ----------------------------------------------------------------------------

  const canvas = $('machine'), ctx = canvas.getContext('2d');
  const plots = window.whatnextPlots.create({ onSeek: (t) => { pause(); seek(t); } });
  const panel = window.whatnextPanel.create($('fields'), keys, names, onField);

  function showRun() {
    const run = st.run;
    st.view = null;
    showTimeline();
    $('outcome').textContent = T('Outcome: {sentence}.', { sentence: S.sentence(run.outcome.sentence) });
    const c = st.compare;
    $('compare-outcome').hidden = c.mode === 'none';
    if (c.mode === 'laws') {
      // One line per law, in its colour: the main run's law first.
      const box = $('compare-outcome');
      box.textContent = '';
      const line = (colour, text) => {
        const p = document.createElement('span');
        p.className = 'law-line';
        p.style.color = colour;
        p.textContent = text;
        box.append(p);
      };
      line('var(--ink)', `${run.machine.run.impact_law}: ${S.sentence(run.outcome.sentence)}`);
      for (const o of c.runs) line(o.colour, `${o.label}: ${S.sentence(o.run.outcome.sentence)}`);
      if (c.message) line('var(--red)', c.message);
    } else {
      $('compare-outcome').textContent = c.run ? T('Dashed, {label}: {sentence}.', { label: c.label, sentence: S.sentence(c.run.outcome.sentence) }) : c.message;
    }
    $('compare-note').textContent = c.mode === 'laws' ? T('each law in its colour; in the drawing one at a time (choose it below)')
                                   : c.run ? T('dashed in the plots, blue outline in the drawing') : '';
    showLegend();
    whyFor = null;
    if ($('why').open) showWhy();
    plots.show(run, c.runs);
    panel.show(run.values, st.sets);
    showTicks();
    showCommandLine();
    $('perf').textContent = T('Last run: {ms} ms in WebAssembly, {events} events, {states} states.',
                              { ms: S.decimals(st.runMs.toFixed(1)), events: run.events.length, states: run.samples.t.length });
    document.body.dataset.runs = String(st.runs);
    writeUrlSoon();
    render();
  }

  // The "why", built when opened for the machine shown (it runs the machine with each law).
  let whyFor = null;
  function showWhy() {
    const machine = JSON.stringify([st.base.id, st.base.toml, [...st.good]]);
    if (whyFor === machine) return;
    whyFor = machine;
    const base = st.base, good = new Map(st.good);
    Teach.why((extra) => ask('run', inputFor(base, good, extra), null, true), st.run.machine.run.impact_law);
  }
  function openWhy() {
    $('why').open = true;
    showWhy();
    $('why').scrollIntoView({ block: 'start', behavior: reducedMotion ? 'auto' : 'smooth' });
    $('why').querySelector('summary').focus({ preventScroll: true });
  }

  // The four laws' legend: each law in its colour; the one chosen is drawn as the ghost (one at a
  // time: four outlines on one spot cannot be told apart).
  function showLegend() {
    const c = st.compare, box = $('compare-legend');
    box.textContent = '';
    box.hidden = c.mode !== 'laws' || !c.runs.length;
    if (box.hidden) return;
    st.ghost = Math.min(st.ghost, c.runs.length - 1);
    const own = document.createElement('span');
    own.innerHTML = '<span class="swatch" style="border-color: var(--ink)"></span>';
    own.append(T('{law} (this run, filled)', { law: st.run.machine.run.impact_law }));
    box.append(own);
    c.runs.forEach((o, i) => {
      const b = document.createElement('button');
      b.type = 'button';
      b.setAttribute('aria-pressed', String(i === st.ghost));
      b.innerHTML = `<span class="swatch" style="border-color: ${o.colour}"></span>`;
      b.append(T('{law} (outline)', { law: o.label }));
      b.style.color = o.colour;
      b.addEventListener('click', () => { st.ghost = i; showLegend(); render(); });
      box.append(b);
    });
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
        cell.textContent = k === 1 || k === 2 ? text : S.decimals(text);
        if (k === 1) cell.title = e.words;
        // In another language the event's name in its words (the command line's name in the title).
        if (k === 2) cell.title = S.sentence(names.modes[Number(text.replace(/\D/g, ''))] || text);
        if (k === 1 && S.lang !== 'en') {
          cell.textContent = S.eventWords(text.replace(/_/g, ' '));
          cell.title = text;
        }
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
        // The impact's energy, its impulses per contact (N s) and why another law than the one
        // chosen was applied, in the page's words.
        cell.textContent = cells.slice(6).join(' ').replace(/^energy /, `${T('energy')} `)
          .replace(/; impulse (.*?)(;|$)/, (all, list, end) =>
            `; ${T('impulse')} ${list.replace(/\b(floor on seesaw|floor on sandbag|sandbag|rope|lid|stop)\b/g, (w) => T(w))}${end}`)
          .replace(/; not the (\S+) law: (.*)$/, (all, law, note) => `; ${T('not the {law} law: {note}', { law, note: T(note) })}`);
        // A negative energy is no error: the potential's zero is at the pivot's height.
        cell.textContent = S.decimals(cell.textContent);
        if (/-\d/.test(cell.textContent.split(';')[0])) {
          const why = document.createElement('span');
          why.className = 'why';
          why.textContent = ` (${T('Energy from the pivot\'s height: below it, potential energy is negative.')})`;
          cell.append(why);
        }
        if (e.type === 'rope_taut' || e.type === 'lid_open' && st.run.machine.radio) {
          const link = document.createElement('button');
          link.type = 'button';
          link.className = 'why-link';
          link.textContent = T('Why?');
          link.addEventListener('click', (ev) => { ev.stopPropagation(); openWhy(); });
          cell.append(' ', link);
        }
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
      mark.title = S.lang === 'en' ? g.label
        : `${S.decimals(g.t.toFixed(3))} s ${g.events.map((i) => S.eventWords(st.run.events[i].words)).join(' + ')}`;
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
    // At most a share of the window's height (style.css: three quarters, less on a phone where
    // the parameters share the screen with it), but never less than the caption and a picture
    // below it (a short window, or one not laid out yet, has almost no height).
    const share = Number(getComputedStyle($('canvas-box')).getPropertyValue('--canvas-max')) || 0.75;
    let most = share * window.innerHeight;
    if (document.body.classList.contains('projector')) {
      // Projector mode: all of the screen's height below the header, but for the player under it.
      const box = $('canvas-box').getBoundingClientRect(), below = $('stage').getBoundingClientRect().bottom - box.bottom;
      most = window.innerHeight - (box.top + window.scrollY) - below - 10;
    }
    const height = Math.round(Math.max(Math.min(Math.max(st.aspect * width + st.band, 240), most), st.band + 150));
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

  // prefers-reduced-motion: playback starts in slow motion nowhere, the events are held longer, and
  // nothing moves unless asked (no auto-play exists).
  const reducedMotion = window.matchMedia('(prefers-reduced-motion: reduce)').matches;
  // A touch screen has no Space bar to mention.
  const touch = window.matchMedia('(pointer: coarse)').matches;
  function speedWords() {
    if (!st.playing) {
      if (st.t >= st.run.tEnd) return T(touch ? 'end of the run (▶ plays it again)' : 'end of the run (Space plays it again)');
      return T(touch ? 'paused (▶ plays)' : 'paused (Space plays)');
    }
    const v = speedAt(st.t);
    if (Math.abs(v - 1) < 1e-9) return T('real time');
    const words = v < 1 ? T('slow motion ×{x}', { x: S.decimals(String(Number((1 / v).toPrecision(2)))) })
                        : T('fast forward ×{x}', { x: S.decimals(String(Number(v.toPrecision(2)))) });
    return st.speed === 'auto' && v > kSlow ? T('quiet stretch: {words}', { words }) : words;
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
      `t = ${S.decimals(st.t.toFixed(3))} s    ${S.sentence(modeWords(s))}`,
      group ? T('event at {t} s: {words}', { t: S.decimals(group.t.toFixed(3)), words: group.events.map((i) => S.eventWords(run.events[i].words)).join(' + ') })
            : speedWords(),
    ];
    const shownRuns = st.compare.mode === 'laws' ? (st.compare.runs || []).slice(st.ghost, st.ghost + 1) : (st.compare.runs || []);
    const ghosts = shownRuns.map((o) => ({ run: o.run, colour: o.colour, state: Machine.stateAt(o.run.samples, Math.min(st.t, o.run.tEnd)) }));
    ctx.setTransform(st.dpr, 0, 0, st.dpr, 0, 0);
    // At an impact's frame its impulses flash instead of the forces.
    const impacts = group ? group.events.map((i) => run.events[i]).filter((e) => e.impact && e.impulses) : [];
    const impulses = impacts.length ? impacts.map((e) => ({ state: e.state, impulses: e.impulses })) : null;
    const drawn = Machine.draw(ctx, st.view, { run, state: s, ghosts, caption, event: group, font: st.font, lines: st.lines,
                                              forces: st.forces, impulses });
    st.drawnForces = drawn.forces;
    st.caption = [...caption, drawn.far].filter(Boolean).join('\n');
    Teach.bars(run, st.t);
    describe(run, s, group);

    $('clock').textContent = `t = ${S.decimals(st.t.toFixed(6))} s`;
    const scrub = $('scrub');
    if (document.activeElement !== scrub || st.playing) scrub.value = String(st.t);
    const said = `t = ${S.decimals(st.t.toFixed(3))} s`;
    if (scrub.getAttribute('aria-valuetext') !== said) scrub.setAttribute('aria-valuetext', said);
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

  // The mode in words that fit the machine as built (the library's table, names.modeWords: the
  // sandbag at the stop, the seesaw on the floor, the rope let go), as the CLI's animation says it.
  const bit = (x) => (x ? 1 : 0);
  const modeWords = (s) => (names.modeWords && names.modeWords[`${s.mode},${bit(s.at_stop)},${bit(s.bag_on_floor)},${bit(s.seesaw_on_floor)},${bit(s.rope_let_go)}`])
    || names.modes[s.mode];

  // The drawing's description for screen readers (it is an image): the machine, its mode, the
  // last event and the outcome; changed only when one of them does, not at every frame.
  function describe(run, s, group) {
    const past = run.groups.filter((g) => g.t <= st.t + 1e-12 * Math.max(1, st.t));
    const last = past.length ? past[past.length - 1] : null;
    const lastWords = last ? T('last event at {t} s: {words}', { t: S.decimals(last.t.toFixed(3)), words: last.events.map((i) => S.eventWords(run.events[i].words)).join(' + ') })
                           : T('no event yet');
    const text = `${T('The machine drawn to scale')}. ${S.sentence(modeWords(s))}; ${lastWords}. ${$('outcome').textContent}`;
    if (text !== st.described) {
      st.described = text;
      canvas.setAttribute('aria-label', text);
    }
    if (st.forces && st.drawnForces) {
      const f = st.drawnForces.arrows.map((a) => `${T(kForceWords[a.what] || a.what)} ${S.decimals(String(Number(a.value.toPrecision(3))))} ${a.unit}`).join(', ');
      $('force-scale').textContent = `${T('Arrows (scale at the upper right): green gravity, purple the rope, blue the arm, the stop and the floor, orange velocities; red at an impact its impulses. An arrow cut by two bars is longer than drawn.')} ${f}`;
    }
  }

  // The library's names of the arrows (web/wasm/bindings.cpp forces), in words.
  const kForceWords = {
    weight_sandbag: 'gravity on the sandbag', weight_lid: 'gravity on the lid', weight_seesaw: 'gravity on the seesaw',
    tension_on_sandbag: 'the rope on the sandbag', tension_on_lid: 'the rope on the lid', arm_on_sandbag: 'the arm on the sandbag',
    stop_on_sandbag: 'the stop on the sandbag', floor_on_seesaw: 'the floor on the seesaw', floor_on_sandbag: 'the floor on the sandbag',
    velocity_sandbag: 'velocity of the sandbag', velocity_lid_edge: 'velocity of the lid\'s edge',
    impulse_sandbag: 'impulse of the arm on the sandbag', impulse_rope_on_sandbag: 'impulse of the rope on the sandbag',
    impulse_rope_on_lid: 'impulse of the rope on the lid', impulse_stop: 'impulse of the stop', impulse_floor_seesaw: 'impulse of the floor on the seesaw',
    impulse_floor_sandbag: 'impulse of the floor on the sandbag',
    impulse_latch_on_lid: 'impulse of the latch on the lid (at its edge)', impulse_box_on_lid: 'impulse of the box on the lid (at its edge)',
  };

  // Each event as playback reaches it, said to screen readers (aria-live) in the page's language.
  function announce(group) {
    const run = st.run;
    $('announce').textContent = T('{t} s: {words}', { t: S.decimals(group.t.toFixed(3)), words: group.events.map((i) => S.eventWords(run.events[i].words)).join(' + ') });
  }

  function setForces(on) {
    st.forces = on;
    $('forces').setAttribute('aria-pressed', String(on));
    $('force-scale').hidden = !on;
    render();
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
    if (g) { soundOf(g); announce(g); }
  }

  // The sound of the events at one instant: the tune when the radio comes on, else a click when
  // one of them is an impact.
  const sound = window.whatnextSound.create();
  function soundOf(group) {
    const events = group.events.map((i) => st.run.events[i]);
    if (events.some((e) => e.type === 'radio_on')) sound.radio();
    else if (events.some((e) => e.impact)) sound.impact();
  }
  function showSound() {
    $('sound').setAttribute('aria-pressed', String(!sound.muted));
    const words = T(sound.muted ? 'Sound: off' : 'Sound: on');
    $('sound').innerHTML = `<span class="wide"></span><span class="narrow">${icon(sound.muted ? 'M3 9v6h4l5 5V4L7 9zM16 8l6 8M22 8l-6 8' : 'M3 9v6h4l5 5V4L7 9zM16 7a6 6 0 0 1 0 10')}</span>`;
    $('sound').firstChild.textContent = words;
  }

  // The player: simulated time runs at the chosen speed and stops for a moment at each event.
  function tick(now) {
    if (st.playing && st.run) {
      // A frame's time stamp may be a little before the moment play() was pressed.
      const dt = Math.min(0.1, Math.max(0, now - st.last) / 1000);
      st.last = now;
      if (now >= st.holdUntil) {
        let t = st.t + dt * speedAt(st.t);
        const next = st.run.groups.find((g) => g.t > st.t);
        if (next && next.t <= t) {
          t = next.t;
          // Reduced motion: no jump into the event's frame and out at once; it is held a little longer.
          st.holdUntil = now + (reducedMotion ? 2 * kHoldMs : kHoldMs);
          soundOf(next);
          announce(next);
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
    if (commit) queue.commit = true;
    schedule(async () => {
      const c = queue.commit;
      queue.commit = false;
      if (await simulate(key) && c) commitChange();
    });
  }

  function choose(base, sets) {
    schedule(async () => {
      const old = { base: st.base, sets: st.sets };
      st.base = base;
      st.sets = new Map(sets);
      st.t = 0;
      pause();
      if (!await simulate(null)) {
        st.base = old.base;  // a file that does not load: stay with the machine shown
        st.sets = old.sets;
        showPresetChoice();
        return;
      }
      showPresetChoice();
      fitCanvas();
      commitChange();
    }, true);
  }

  function showPresetChoice() {
    const select = $('preset');
    select.textContent = '';
    for (const p of presets) select.append(new Option(kPresetWhat[p.id] ? `${T(p.title)}: ${T(kPresetWhat[p.id])}` : T(p.title), p.id));
    if (st.base.id === 'file') select.append(new Option(T('file: {name}', { name: st.base.title }), 'file'));
    select.value = st.base.id;
    showPresetFace();
  }
  // The short name a phone shows on the closed choice (style.css: .preset-face).
  function showPresetFace() {
    const select = $('preset'), p = presets.find((x) => x.id === select.value);
    $('preset-face').textContent = p ? T(kPresetShort[p.id] || p.title) : select.selectedOptions[0]?.text || '';
  }

  function fileBase(name, text) {
    return { id: 'file', title: name, toml: text, source: name, label: name, cli: shellWord(name),
             format: /\.inp$/i.test(name) ? 'inp' : 'toml' };
  }

  // ---- the URL: the machine, the comparison and the time ------------------------------------------

  // URL-safe base64 of UTF-8 text, in slices (spreading a whole file's bytes into one call
  // overflows the stack beyond ~300 KB); and back, refusing what is not base64 or not UTF-8.
  function toBase64(text) {
    const bytes = new TextEncoder().encode(text);
    let binary = '';
    for (let i = 0; i < bytes.length; i += 0x8000) binary += String.fromCharCode.apply(null, bytes.subarray(i, i + 0x8000));
    return btoa(binary).replace(/\+/g, '-').replace(/\//g, '_').replace(/=+$/, '');
  }
  function fromBase64(b64) {
    if (!/^[A-Za-z0-9_-]*$/.test(b64)) throw new Error(T('it holds characters that are not URL-safe base64'));
    // The browser's own reasons are English whatever the page's language: the page's words instead.
    let binary;
    try {
      binary = atob(b64.replace(/-/g, '+').replace(/_/g, '/'));  // throws on a bad length
    } catch (e) {
      throw new Error(T('its length is not that of base64 text'));
    }
    const bytes = new Uint8Array(binary.length);
    for (let i = 0; i < binary.length; ++i) bytes[i] = binary.charCodeAt(i);
    try {
      return new TextDecoder('utf-8', { fatal: true }).decode(bytes);
    } catch (e) {
      throw new Error(T('it is not text in UTF-8'));
    }
  }

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
    if (c.mode === 'laws') p.set('compare', 'laws:');
    if (c.mode === 'rigid' || c.mode === 'frictionless') p.set('compare', `${c.mode}:`);
    // A step that does not run is not passed on in the link.
    if (c.mode === 'euler' && validStep(c.step) && c.run) p.set('compare', `euler:${c.step}`);
    history.replaceState(null, '', `#${p.toString()}`);
  }

  // The link's machine, changes and comparison; every part that cannot be used is named in
  // `problems` (the page then shows what it can, and says what it left out).
  function readUrl() {
    const p = new URLSearchParams(location.hash.slice(1));
    const problems = [];
    let base = presets[0];
    if (p.has('machine')) {
      const found = presets.find((x) => x.id === p.get('machine'));
      if (found) base = found;
      else problems.push(T('The link\'s machine={given} is not one of this page\'s machines ({ids}).', { given: p.get('machine'), ids: presets.map((x) => x.id).join(', ') }));
    }
    if (p.has('text')) {
      try {
        const text = fromBase64(p.get('text'));
        const bytes = new TextEncoder().encode(text).length;
        if (bytes > kMaxFileBytes) throw new Error(T('it holds {bytes} bytes, more than the {most} a machine file may have', { bytes, most: kMaxFileBytes }));
        base = fileBase(p.get('file') || 'machine.toml', text);
      } catch (e) {
        problems.push(T('The link\'s file (text=) cannot be read: {why}.', { why: e.message }));
      }
    } else if (p.has('file')) {
      problems.push(T('The link names a file ({given}) but does not hold it (no text=).', { given: p.get('file') }));
    }
    const sets = [];
    for (const [k, v] of p) {
      if (k.includes('.')) sets.push([k, v]);
      else if (!['machine', 'file', 'text', 'compare', 'lang'].includes(k)) problems.push(T('The link\'s part "{given}" is not a key (keys look like geometry.rope_length) and was left out.', { given: k }));
    }
    let compare = null;
    if (p.has('compare')) {
      const [kind, ...rest] = p.get('compare').split(':');
      const what = rest.join(':');
      if (kind === 'law' && names['run.impact_law'].includes(what)) compare = { mode: 'law', law: what };
      else if (kind === 'laws' && what === '') compare = { mode: 'laws' };
      else if (kind === 'euler' && validStep(what)) compare = { mode: 'euler', step: what };
      else if ((kind === 'rigid' || kind === 'frictionless') && what === '') compare = { mode: kind };
      else problems.push(T('The link\'s compare={given} is not a comparison (law:NAME with NAME one of {laws}; laws:; euler:STEP with a step in seconds above 0; rigid:; frictionless:) and was left out.', { given: p.get('compare'), laws: names['run.impact_law'].join(', ') }));
    }
    return { base, sets, compare, problems };
  }
  const validStep = (text) => /^\s*[0-9.eE+-]+\s*$/.test(text) && Number(text) > 0 && Number.isFinite(Number(text));

  // ---- downloads --------------------------------------------------------------------------------

  async function download(kind) {
    const input = inputFor(st.base, st.good);
    const stem = (st.base.id === 'file' ? st.base.title.replace(/\.[^.]*$/, '') : st.base.id) + (st.good.size ? '-changed' : '');
    if (kind === 'csv') {
      const rows = st.run.machine.run.t_max / st.run.machine.run.output_step;
      if (rows > 2e6) {
        alert(T('That CSV would have {rows} rows: too many for a browser. Raise run.output_step, or use the command line (see "The same run on the command line").', { rows: Math.round(rows) }));
        return;
      }
    }
    const r = await ask(kind === 'toml' ? 'toml' : kind === 'json' ? 'events' : 'csv', input);
    if (r.kind === 'stopped') return;
    if (!r.ok) {
      alert(S.sentence(pageWords(r.message)));
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

  function toast(text, link = '') {
    const t = document.createElement('div');
    t.className = 'toast';
    t.textContent = text;
    if (link) t.append(document.createElement('br'), Object.assign(document.createElement('code'), { textContent: link.length > 120 ? `${link.slice(0, 117)}…` : link }));
    document.body.append(t);
    setTimeout(() => t.remove(), 2500);
  }

  // ---- wiring -----------------------------------------------------------------------------------

  $('preset').addEventListener('change', (e) => {
    showPresetFace();
    const p = presets.find((x) => x.id === e.target.value);
    if (p) choose(p, []);
  });
  $('open').addEventListener('click', () => $('file').click());
  $('file').addEventListener('change', async (e) => {
    const f = e.target.files[0];
    if (!f) return;
    if (f.size > kMaxFileBytes) {  // the command line's limit (docs/inputs.md)
      $('problem').textContent = T('{name} is not opened: it has {bytes} bytes, more than the {most} bytes a machine file may have.', { name: f.name, bytes: f.size, most: kMaxFileBytes });
      $('problem').hidden = false;
      e.target.value = '';
      return;
    }
    choose(fileBase(f.name, await f.text()), []);
    e.target.value = '';
  });
  $('reset-all').addEventListener('click', () => choose(st.base, []));
  $('stop').addEventListener('click', () => restartWorker());
  $('sound').addEventListener('click', () => { sound.muted = !sound.muted; showSound(); });
  showSound();

  // The language: the page is made again in the one chosen (the link keeps the machine).
  // On a phone's one-row header the language's code ("DE"); its name where there is room.
  const narrowHeader = window.matchMedia('(max-width: 900px)').matches;
  for (const [code, name] of Object.entries(S.languages)) $('lang').append(new Option(narrowHeader ? code.toUpperCase() : name, code));
  $('lang').value = S.lang;
  $('lang').addEventListener('change', (e) => {
    S.set(e.target.value);
    writeUrl();
    location.reload();
  });
  if (touch) $('timeline').caption.textContent = T('Events (tap one to go there)');

  // Projector mode: full screen (where the browser allows it), the machine large beside the
  // timeline, big type; Space, PageUp/PageDown (a presenter's remote) and the arrows drive it.
  function setProjector(on) {
    document.body.classList.toggle('projector', on);
    $('projector').setAttribute('aria-pressed', String(on));
    if (on && !document.fullscreenElement && document.documentElement.requestFullscreen) {
      document.documentElement.requestFullscreen().catch(() => {});
    } else if (!on && document.fullscreenElement) {
      document.exitFullscreen().catch(() => {});
    }
    // The plots are made again: their type follows the page's.
    requestAnimationFrame(() => { sizeCanvas(); fitCanvas(); if (st.run) plots.show(st.run, st.compare.runs); plots.resize(); });
  }
  $('projector').addEventListener('click', () => setProjector(!document.body.classList.contains('projector')));
  // Leaving full screen (Escape) leaves projector mode.
  document.addEventListener('fullscreenchange', () => { if (!document.fullscreenElement) setProjector(false); });
  // The link is the page's own address, wherever it is served (a school server, the LAN address
  // of ./run.sh web --lan, any static host). The clipboard API exists only on https and
  // localhost; on a LAN address over http the older copy command does it.
  $('share').addEventListener('click', async () => {
    writeUrl();
    const link = location.href;
    let copied = false;
    try {
      await navigator.clipboard.writeText(link);
      copied = true;
    } catch (e) {
      const area = document.createElement('textarea');
      area.value = link;
      area.style.position = 'fixed';
      area.style.opacity = '0';
      document.body.append(area);
      area.select();
      try { copied = document.execCommand('copy'); } catch (e2) { copied = false; }
      area.remove();
    }
    if (!copied) { prompt(T('Copy this link; it opens this machine:'), link); return; }
    const local = location.protocol === 'file:' || /^(localhost|127\.|\[::1\])/.test(location.hostname);
    toast(`${T('Link copied: it opens this machine.')} ${local ? T('This address works on this computer only: serve the page (./run.sh web --lan, or any web server) to share it.') : ''}`, link);
  });
  // The header's menus close when one of their items is chosen, or on a click elsewhere, or Escape.
  const menus = [$('share-menu'), $('download-menu')];
  for (const m of menus) m.addEventListener('click', (e) => { if (e.target.closest('button')) m.open = false; });
  document.addEventListener('click', (e) => { for (const m of menus) if (m.open && !m.contains(e.target)) m.open = false; });
  document.addEventListener('keydown', (e) => { if (e.key === 'Escape') for (const m of menus) if (m.open) { m.open = false; m.querySelector('summary').focus(); } });
  $('why').addEventListener('toggle', () => { if ($('why').open && st.run) showWhy(); });
  $('why-compare').addEventListener('click', openWhy);
  $('qr').addEventListener('click', () => { writeUrl(); Teach.showQr(location.href); });
  $('forces').addEventListener('click', () => setForces(!st.forces));
  // Projector mode's one plot: the energy plot unless another is chosen.
  function choosePlot(id) {
    for (const f of document.querySelectorAll('.plot-grid > figure')) f.classList.toggle('chosen', f.id === id);
    $('plot-choice').value = id;
    requestAnimationFrame(() => plots.resize());
  }
  $('plot-choice').addEventListener('change', (e) => choosePlot(e.target.value));
  choosePlot('plot-energy');
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
    // The step as the page's language writes it (kept with a point for the link), not rewritten
    // while it is typed in.
    if (document.activeElement !== $('compare-step')) $('compare-step').value = window.whatnextPanel.shown(c.step);
  }
  for (const law of names['run.impact_law']) $('compare-law').append(new Option(law, law));
  const compareChanged = () => {
    showCompareControls();
    schedule(async () => {
      await runCompare();
      showRun();
      writeUrl();
    });
  };
  $('compare').addEventListener('change', (e) => { st.compare.mode = e.target.value; compareChanged(); });
  $('compare-law').addEventListener('change', (e) => { st.compare.law = e.target.value; compareChanged(); });
  $('compare-step').addEventListener('input', (e) => { st.compare.step = window.whatnextPanel.point(e.target.value.trim()); compareChanged(); });

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
    } else if (e.key === 'm' || e.key === 'M') {
      sound.muted = !sound.muted;
      showSound();
    } else if (e.key === 'v' || e.key === 'V') {
      setForces(!st.forces);
    } else if (e.key === 'f' || e.key === 'F') {
      setProjector(!document.body.classList.contains('projector'));
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
  // A change still waiting to be written into the link must not overwrite the pasted one on the
  // way out (pagehide below), so it is dropped first.
  window.addEventListener('hashchange', () => {
    clearTimeout(urlTimer);
    urlTimer = null;
    location.reload();
  });
  window.addEventListener('pagehide', () => { if (urlTimer !== null) writeUrl(); });
  new ResizeObserver(() => plots.resize()).observe($('plots'));

  // ---- start: the machine of the link, or example 1 -----------------------------------------------

  const start = readUrl();
  if (start.compare) Object.assign(st.compare, start.compare);
  showCompareControls();
  sizeCanvas();
  st.base = start.base;
  st.sets = new Map(start.sets);
  showPresetChoice();
  document.body.dataset.busy = 'true';
  queue.busy = true;  // the first run before any change
  const problems = [...start.problems];
  if (!await simulate(null)) {
    // A link whose changes do not run: its machine without them, and why.
    problems.push(T('The link\'s machine does not run ({problem}).', { problem: st.problem }));
    st.sets = new Map();
    if (!await simulate(null)) {
      st.base = presets[0];
      await simulate(null);
    }
    problems.push(T('This is {title} without the link\'s changes.', { title: T(st.base.title) }));
    showPresetChoice();
  }
  if (problems.length) {
    $('problem').textContent = problems.join(' ');
    $('problem').hidden = false;
  }
  markStale(false);
  fitCanvas();
  commitChange();
  pump();  // what came meanwhile, and the sliders' valid ranges
  requestAnimationFrame(tick);

  // For the tests and the curious: the page's state and its mapping to the canvas.
  window.whatnext = {
    get time() { return st.t; },
    get run() { return st.run; },
    get sounds() { return sound.log; },
    // The canvas's caption as drawn (its lines, and how far a part beyond the picture is), and
    // where the picture below it starts, in canvas pixels.
    get caption() { return st.caption; },
    // The forces, velocities or impulses drawn now: [{what, value, unit, cut}] and the scale's legend.
    get forces() { return st.drawnForces; },
    get pictureTop() { return st.band * st.dpr; },
    validity: (key) => panel.field(key).validity,
    probes: (key) => panel.probes().find((p) => p.key === key).values,
    play: () => play(),
    seek: (t) => { pause(); seek(t); },
    // A message of the library as the page shows it (its words, its language).
    words: (message) => S.sentence(pageWords(message)),
    stateAt: (t) => Machine.stateAt(st.run.samples, t),
    canvasPixel: (x, h) => {
      const p = Machine.toPixel(st.view, { x, h });
      return { x: p.x * st.dpr, y: p.y * st.dpr };
    },
    // Milliseconds for one run of a shipped machine (as the page runs it at every change), timed
    // in the worker.
    timeRun: (id, repeat) => ask('timeRun', { input: inputFor(presets.find((x) => x.id === id), []), repeat }),
  };
  // ---- the map and the phase plots (map.js, phase.js): the machine shown, and loading another ----
  const studies = { keys, input: () => inputFor(st.base, st.good), base: () => st.base, sets: () => new Map(st.good),
                    run: () => st.run, load: (sets, base = st.base) => choose(base, sets) };
  for (const part of [window.whatnextMap, window.whatnextPhase]) if (part) part.attach(studies);
  document.body.dataset.ready = 'true';
})();
