// Any variable against any other: the run shown, in the columns of `whatnext run --csv` (their
// names, units and meanings come from the library, columns.hpp through map.cpp), one chosen across
// and one or more up, with the events marked. Phase plots (φL against φS, r against its rate) and
// the energy of each part against time are a click away. The run's table is made in a map worker
// (map.js), so the page's thread only draws; the drawing is uPlot's (mode 2: x and y both data).
(function () {
  'use strict';

  const S = window.whatnextStrings;
  const T = (english, args) => S.t(english, args);
  const $ = (id) => document.getElementById(id);
  const kMaxRows = 4000;  // samples kept per run: more than a plot's pixels across
  const kEnergyParts = /^(sandbag|lid|seesaw|balloon)_(kinetic|potential)_J$/;
  const kPresets = [
    { id: 'angles', label: 'φL against φS', x: 'phi_s_deg', y: ['phi_l_deg'] },
    { id: 'sandbag', label: 'r against its rate', x: 'r_m', y: ['dr_m_per_s'] },
    { id: 'lid', label: 'the lid: angle against its rate', x: 'phi_l_deg', y: ['dphi_l_deg_per_s'] },
    { id: 'energy', label: 'the energy by part against time', x: 't_s', y: 'energy' },
  ];
  const kColours = ['#1f5fbf', '#d4641c', '#2a8f3a', '#a0309a', '#6b4b2a', '#c0392b', '#0f8a8a', '#777'];

  let app = null, columns = null, table = null, plot = null, choice = { x: 'phi_s_deg', y: ['phi_l_deg'] };
  const el = (tag, attrs = {}, ...children) => {
    const e = document.createElement(tag);
    for (const [k, v] of Object.entries(attrs)) e.setAttribute(k, v);
    e.append(...children);
    return e;
  };
  const label = (name) => {
    const c = columns.find((k) => k.name === name);
    return c ? `${name}${c.unit ? ` [${c.unit}]` : ''}` : name;
  };

  // The run shown, again, in the CSV's columns. While a slider moves the runs come faster than
  // the tables: one table at a time, then the latest run's.
  let busy = false, again = false;
  async function refresh() {
    const run = app.run();
    if (!run || !columns) return;
    if (busy) { again = true; return; }
    busy = true;
    const r = await window.whatnextMap.phaseTable(app.input(), kMaxRows);
    busy = false;
    if (again) { again = false; refresh(); return; }
    table = r.ok ? r : null;
    $('phase-problem').hidden = r.ok;
    if (!r.ok) $('phase-problem').textContent = S.sentence(r.message);
    draw();
  }

  const index = (name) => columns.findIndex((c) => c.name === name);

  // A polyline through the points in their order (uPlot's own paths assume x increases).
  function polyline(u, seriesIdx) {
    const [xs, ys] = u.data[seriesIdx];
    const s = u.series[seriesIdx];
    const path = new Path2D();
    let on = false;
    for (let i = 0; i < xs.length; ++i) {
      const x = u.valToPos(xs[i], s.facets[0].scale, true), y = u.valToPos(ys[i], s.facets[1].scale, true);
      if (!Number.isFinite(x) || !Number.isFinite(y)) { on = false; continue; }
      if (on) path.lineTo(x, y); else path.moveTo(x, y);
      on = true;
    }
    return { stroke: path };
  }
  // The events: a ring at each, and its name beside it while there are few.
  function rings(u, seriesIdx) {
    const [xs, ys] = u.data[seriesIdx];
    const s = u.series[seriesIdx];
    const path = new Path2D();
    for (let i = 0; i < xs.length; ++i) {
      const x = u.valToPos(xs[i], s.facets[0].scale, true), y = u.valToPos(ys[i], s.facets[1].scale, true);
      path.moveTo(x + 5 * devicePixelRatio, y);
      path.arc(x, y, 5 * devicePixelRatio, 0, 2 * Math.PI);
    }
    return { stroke: path };
  }

  function draw() {
    const box = $('phase-plot');
    if (plot) { plot.destroy(); plot = null; }
    if (!table) return;
    const xi = index(choice.x);
    const ys = choice.y === 'energy' ? columns.filter((c) => kEnergyParts.test(c.name)).map((c) => c.name) : choice.y;
    const xsAll = table.data[xi];
    // The parts that hold no energy in this machine (a massless seesaw) are left out.
    const shownYs = ys.filter((name) => table.data[index(name)].some((v) => v !== 0));
    const series = [{}], data = [null];
    shownYs.forEach((name, k) => {
      series.push({ label: label(name), stroke: kColours[k % kColours.length], width: 1.5, facets: [{ scale: 'x', auto: true }, { scale: 'y', auto: true }], paths: polyline, points: { show: false } });
      data.push([xsAll, table.data[index(name)]]);
    });
    // Every event on the first curve.
    const ev = [], ex = [], ey = [];
    const y0 = shownYs.length ? table.data[index(shownYs[0])] : null;
    table.event.forEach((name, i) => { if (name && y0) { ev.push(name); ex.push(xsAll[i]); ey.push(y0[i]); } });
    series.push({ label: T('events'), stroke: '#000', width: 1.5, facets: [{ scale: 'x', auto: true }, { scale: 'y', auto: true }], paths: rings, points: { show: false } });
    data.push([Float64Array.from(ex), Float64Array.from(ey)]);
    const width = Math.max(260, Math.min(box.clientWidth, 820));
    plot = new uPlot({
      mode: 2, width, height: Math.round(Math.min(width * 0.6, 420)),
      scales: { x: { time: false }, y: {} },
      axes: [{ label: label(choice.x), values: (u, v) => v.map((x) => S.decimals(String(x))) },
             { label: shownYs.length === 1 ? label(shownYs[0]) : T('energy [J]'), values: (u, v) => v.map((x) => S.decimals(String(x))) }],
      legend: { live: false },
      cursor: { drag: { x: true, y: true } },
      series,
      hooks: {
        draw: [(u) => {  // the events' names, while there are few enough to read
          if (ev.length > 12) return;
          const g = u.ctx, dpr = devicePixelRatio;
          g.save();
          g.font = `${11 * dpr}px system-ui, sans-serif`;
          g.fillStyle = '#000';
          g.textAlign = 'left';
          g.textBaseline = 'bottom';
          // Events at one point (an impact and what it starts) under one label.
          const at = new Map();
          ev.forEach((name, i) => {
            const x = Math.round(u.valToPos(ex[i], 'x', true)), y = Math.round(u.valToPos(ey[i], 'y', true));
            const key = `${x},${y}`, words = S.eventWords(name.replace(/_/g, ' '));
            at.set(key, at.has(key) ? `${at.get(key)}, ${words}` : words);
          });
          for (const [key, words] of at) {
            const [x, y] = key.split(',').map(Number);
            g.textAlign = x > u.bbox.left + u.bbox.width * 0.7 ? 'right' : 'left';
            g.fillText(words, x + (g.textAlign === 'right' ? -7 : 7) * dpr, y - 4 * dpr);
          }
          g.restore();
        }],
      },
    }, data, box);
    $('phase-events').textContent = ev.length
      ? T('Events marked (rings): {list}.', { list: ev.map((name, i) => `${S.eventWords(name.replace(/_/g, ' '))} (${S.decimals(String(Number(ex[i].toPrecision(4))))}; ${S.decimals(String(Number(ey[i].toPrecision(4))))})`).join(', ') })
      : '';
  }

  function select(id, names, value) {
    const s = $(id);
    s.textContent = '';
    // The columns' meanings are the library's, in English: in another language the names and units alone.
    for (const c of columns) if (names(c)) s.append(new Option(`${label(c.name)}${c.meaning && S.lang === 'en' ? ` – ${c.meaning}` : ''}`, c.name));
    s.value = value;
  }

  function build(section) {
    const presets = el('div', { class: 'phase-presets', role: 'group', 'aria-label': T('Plots to start from') });
    for (const p of kPresets) {
      const b = el('button', { type: 'button', 'data-preset': p.id }, T(p.label));
      b.addEventListener('click', () => { choice = { x: p.x, y: p.y }; showChoice(); draw(); });
      presets.append(b);
    }
    section.append(
      el('h2', { id: 'phase-title' }, T('Any variable against any other')),
      presets,
      el('div', { class: 'phase-choice' },
        el('label', {}, T('across'), ' ', el('select', { id: 'phase-x' })),
        el('label', {}, T('up'), ' ', el('select', { id: 'phase-y' }))),
      el('p', { id: 'phase-problem', class: 'problem', role: 'alert', hidden: '' }),
      el('div', { id: 'phase-plot', class: 'phase-plot' }),
      el('p', { id: 'phase-events', class: 'note' }),
      el('p', { class: 'note' }, T('The columns of'), ' ', el('code', {}, 'whatnext run --csv'), '. ',
        el('span', { class: 'keys-only' }, T('Drag to zoom in, double-click to zoom out.'))));
    $('phase-x').addEventListener('change', (e) => { choice.x = e.target.value; draw(); });
    $('phase-y').addEventListener('change', (e) => { choice.y = e.target.value === 'energy' ? 'energy' : [e.target.value]; draw(); });
    new MutationObserver(() => refresh()).observe(document.body, { attributes: true, attributeFilter: ['data-runs'] });
    let width = 0;
    new ResizeObserver(() => { if (Math.abs($('phase-plot').clientWidth - width) > 20) { width = $('phase-plot').clientWidth; draw(); } }).observe($('phase-plot'));
  }

  function showChoice() {
    select('phase-x', () => true, choice.x);
    select('phase-y', (c) => c.name !== 't_s', Array.isArray(choice.y) ? choice.y[0] : 'energy_J');
    $('phase-y').prepend(new Option(T('the energy of each part'), 'energy'));
    $('phase-y').value = Array.isArray(choice.y) ? choice.y[0] : 'energy';
  }

  window.whatnextPhase = {
    attach(hooks) {
      app = hooks;
      const section = $('phase');
      if (!section || !window.whatnextMap) return;
      window.whatnextMap.columns((c) => {
        columns = c;
        build(section);
        showChoice();
        refresh();
      });
    },
    get shown() { return plot ? { x: choice.x, series: plot.series.slice(1).map((s) => s.label), points: plot.data[1] ? plot.data[1][0].length : 0 } : null; },
  };
})();
