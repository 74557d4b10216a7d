// The four live plots (uPlot): angles, heights, energy with what the impacts took, rope tension.
// Dashed vertical lines at the events, a cursor line at the scrubber's time, an optional second
// run dashed over the first; click to go to a time, drag to zoom in, double-click to zoom out.
(function () {
  'use strict';

  const deg = 180 / Math.PI;
  const S = window.whatnextStrings;
  // Each plot: its figure, the y axis and its curves (value of row i of a run's samples). A curve
  // of a part has the part's colour in the drawing (the library's, machine.js); the others their own.
  const kPlots = [
    {
      id: 'plot-angles', axis: S.t('angle [°]'), guide: 90,
      curves: [
        { label: S.t('φS seesaw'), part: 'seesaw', value: (s, i) => s.phi_s[i] * deg },
        { label: S.t('φL lid'), part: 'lid', value: (s, i) => s.phi_l[i] * deg },
      ],
    },
    {
      id: 'plot-heights', axis: S.t('height [m]'),
      curves: [
        { label: S.t('sandbag'), part: 'sandbag', value: (s, i) => s.h[i] },
        { label: S.t('balloon centre'), part: 'balloon', value: (s, i, m) => m.hinge.h + s.balloon_h[i] },
        { label: S.t('lid limit'), stroke: '#f29a9e', dash: [5, 4], value: (s, i, m) => m.hinge.h + s.balloon_limit[i] },
      ],
    },
    {
      id: 'plot-energy', axis: S.t('energy [J]'), impacts: true,
      curves: [
        { label: S.t('machine E'), stroke: '#222222', value: (s, i) => s.energy[i] },
        { label: S.t('lost (impacts, damping)'), stroke: '#c0392b', value: (s, i) => losses(s, i) },
        { label: S.t('E + lost'), stroke: '#2e8b57', dash: [2, 3], value: (s, i) => s.energy[i] + losses(s, i) },
      ],
    },
    {
      id: 'plot-tension', axis: S.t('tension [N]'),
      curves: [{ label: S.t('rope tension'), stroke: '#6a3d9a', value: (s, i) => s.tension[i] }],
    },
  ];

  const strokeOf = (c) => (c.part ? window.whatnextMachine.colour[c.part] : c.stroke);

  // What the machine (sandbag, seesaw, lid) has lost so far: impacts and its damped joints.
  function losses(s, i) {
    return s.lost_impacts[i] + s.dissipated_pivot[i] + s.dissipated_lid_hinge[i];
  }

  // Columns [t, curve...] of one run for one plot. For the energy plot each impact gets a row just
  // before it too, so that the drop is drawn as the vertical step it is.
  function table(plot, run) {
    const s = run.samples, m = run.machine, n = s.t.length;
    const cols = [[]].concat(plot.curves.map(() => []));
    const push = (t, values) => { cols[0].push(t); values.forEach((v, k) => cols[k + 1].push(v)); };
    for (let i = 0; i < n; ++i) {
      const values = plot.curves.map((c) => c.value(s, i, m));
      const e = s.event[i] >= 0 ? run.events[s.event[i]] : null;
      if (plot.impacts && e && e.impact) {
        const drop = e.energy_before - e.energy_after;
        push(s.t[i], [e.energy_before, values[1] - drop, values[2]]);
      }
      push(s.t[i], values);
    }
    return cols;
  }

  // The rows of two runs' tables in one, in time order, each row holding one run's values and
  // gaps for the other's (uPlot draws across the gaps). Unlike uPlot.join this keeps rows with the
  // same time, which an instant with several events has.
  function merge(a, b) {
    const n = a.length - 1, m = b.length - 1;
    const out = [[]].concat(Array.from({ length: n + m }, () => []));
    let i = 0, j = 0;
    while (i < a[0].length || j < b[0].length) {
      const fromA = j >= b[0].length || (i < a[0].length && a[0][i] <= b[0][j]);
      out[0].push(fromA ? a[0][i] : b[0][j]);
      for (let k = 1; k <= n; ++k) out[k].push(fromA ? a[k][i] : null);
      for (let k = 1; k <= m; ++k) out[n + k].push(fromA ? null : b[k][j]);
      if (fromA) ++i; else ++j;
    }
    return out;
  }

  function create(opts) {
    const { onSeek } = opts;
    const charts = [];
    let hovering = null, time = 0, groups = [];

    for (const plot of kPlots) {
      const figure = document.getElementById(plot.id);
      const chart = { plot, figure, u: null, zoom: null, downX: null, cursor: null };
      charts.push(chart);
    }

    function seriesFor(plot, others) {
      const series = [{ label: 't [s]', value: (u, v) => (v == null ? '' : S.decimals(v.toFixed(4))) }];
      // Rounding noise (an energy-keeping impact's loss of -1.8e-15 J) reads as the zero it is.
      const format = (v) => (v == null ? '—' : Math.abs(v) < 1e-9 ? '0' : S.decimals(Number(v.toPrecision(5)).toString()));
      // With two runs a row holds one run's values only: the other's value at that time is its
      // nearest row.
      const value = (u, v, sidx, idx) => {
        if (v != null || idx == null) return format(v);
        const col = u.data[sidx];
        for (let d = 1; idx - d >= 0 || idx + d < col.length; ++d) {
          if (col[idx - d] != null) return format(col[idx - d]);
          if (col[idx + d] != null) return format(col[idx + d]);
        }
        return format(null);
      };
      for (const c of plot.curves) {
        series.push({ label: c.label, stroke: strokeOf(c), width: 2, dash: c.dash, value, spanGaps: true, points: { show: false } });
      }
      // Each other run: its curves dashed in their colours (with several runs, in the run's
      // colour and dash, so that the laws can be told apart).
      for (const o of others) {
        for (const c of plot.curves) {
          series.push({ label: `${c.label}, ${o.label}`, stroke: others.length > 1 ? o.colour : strokeOf(c), width: 1.5,
                        dash: o.dash, alpha: 0.8, value, spanGaps: true, points: { show: false } });
        }
      }
      return series;
    }

    function drawMarks(u, plot) {
      const ctx = u.ctx, { left, top, width, height } = u.bbox;
      ctx.save();
      ctx.beginPath();
      ctx.rect(left, top, width, height);
      ctx.clip();
      ctx.lineWidth = Math.max(1, devicePixelRatio);
      if (plot.guide !== undefined) {  // 90 degrees: where lid_open and seesaw_vertical are near
        const y = u.valToPos(plot.guide, 'y', true);
        ctx.strokeStyle = 'rgba(0,0,0,0.35)';
        ctx.setLineDash([2 * devicePixelRatio, 4 * devicePixelRatio]);
        ctx.beginPath(); ctx.moveTo(left, y); ctx.lineTo(left + width, y); ctx.stroke();
      }
      ctx.strokeStyle = 'rgba(204,0,0,0.55)';
      ctx.setLineDash([5 * devicePixelRatio, 4 * devicePixelRatio]);
      for (const g of groups) {
        const x = u.valToPos(g.t, 'x', true);
        if (x < left || x > left + width) continue;
        ctx.beginPath(); ctx.moveTo(x, top); ctx.lineTo(x, top + height); ctx.stroke();
      }
      ctx.restore();
    }

    function build(chart, data, others) {
      const { plot, figure } = chart;
      if (chart.u) chart.u.destroy();
      const width = Math.max(200, figure.clientWidth);
      const type = Math.round(Math.max(12, 0.72 * parseFloat(getComputedStyle(document.body).fontSize)));
      const u = new uPlot({
        width, height: plotHeight(width, figure),
        scales: { x: { time: false } },
        axes: [
          // The ticks' numbers with the page's decimal sign (uPlot's own are English).
          // The axes' type grows with the page's (projector mode: legible from the back).
          { label: 't [s]', labelSize: 1.4 * type, size: 2.4 * type, font: `${type}px sans-serif`, labelFont: `bold ${type}px sans-serif`,
            values: (uu, ticks) => ticks.map((v) => S.decimals(String(Number(v.toPrecision(6))))) },
          { label: plot.axis, labelSize: 1.4 * type, size: 3.8 * type, font: `${type}px sans-serif`, labelFont: `bold ${type}px sans-serif`,
            values: (uu, ticks) => ticks.map((v) => S.decimals(String(Number(v.toPrecision(6))))) },
        ],
        series: seriesFor(plot, others),
        cursor: { y: false, sync: { key: 'whatnext' }, drag: { x: true, y: false }, points: { size: 6 } },
        legend: { live: true },
        hooks: {
          draw: [(uu) => drawMarks(uu, plot)],
          setScale: [(uu, key) => {
            if (key !== 'x' || chart.settingData) return;
            const full = uu.data[0];
            const min = uu.scales.x.min, max = uu.scales.x.max;
            chart.zoom = full.length && (min > full[0] || max < full[full.length - 1]) ? { min, max } : null;
            placeCursor(chart);
          }],
        },
      }, data, figure);
      chart.u = u;
      const line = document.createElement('div');
      line.className = 'now-line';
      u.over.appendChild(line);
      chart.cursor = line;
      u.over.addEventListener('mouseenter', () => { hovering = chart; });
      u.over.addEventListener('mouseleave', () => { hovering = null; placeAll(); });
      u.over.addEventListener('mousedown', (e) => { chart.downX = e.clientX; });
      u.over.addEventListener('click', (e) => {
        if (chart.downX !== null && Math.abs(e.clientX - chart.downX) < 4) onSeek(u.posToVal(e.offsetX, 'x'));
        chart.downX = null;
      });
      return u;
    }

    function plotHeight(width, figure) {
      const usual = Math.min(320, Math.max(170, 0.5 * width));
      // Projector mode: the one plot ends on the screen, its legend under it included.
      if (!document.body.classList.contains('projector') || !figure) return Math.round(usual);
      const top = figure.getBoundingClientRect().top + window.scrollY, caption = figure.querySelector('figcaption');
      const over = top + (caption ? caption.offsetHeight : 0);
      const legend = figure.querySelector('.u-legend');
      const room = window.innerHeight - over - (legend ? legend.offsetHeight : 60) - 16;
      return Math.round(Math.max(140, Math.min(usual, room)));
    }

    // The plotting area's width in CSS pixels, as uPlot set it: reading clientWidth instead would
    // make the browser lay out the whole page again after every change (a third of a change's time).
    const areaWidth = (u) => parseFloat(u.over.style.width) || 0;

    function placeCursor(chart) {
      const u = chart.u;
      if (!u) return;
      const x = u.valToPos(time, 'x');
      const inside = x >= 0 && x <= areaWidth(u);
      chart.cursor.style.display = inside ? 'block' : 'none';
      chart.cursor.style.transform = `translateX(${x}px)`;
    }

    function placeAll() {
      for (const c of charts) placeCursor(c);
      // The legends show the values at the scrubber's time unless the mouse is over a plot.
      if (hovering) return;
      for (const { u } of charts) {
        if (!u) continue;
        const x = u.valToPos(time, 'x');
        if (x >= 0 && x <= areaWidth(u)) u.setCursor({ left: x, top: 1 }, false);
      }
    }

    return {
      // A new run (and maybe a second run to compare): rebuild the data, keeping any zoom.
      // others: [{run, label, colour, dash}], drawn dashed.
      show(run, others = []) {
        groups = run.groups;
        const key = others.map((o) => o.label).join('|');
        for (const chart of charts) {
          let data = table(chart.plot, run);
          for (const o of others) data = merge(data, table(chart.plot, o.run));
          if (!chart.u || chart.compareKey !== key) {
            build(chart, data, others);
            chart.compareKey = key;
          } else {
            chart.settingData = true;
            chart.u.setData(data);
            chart.settingData = false;
          }
          if (chart.zoom) chart.u.setScale('x', chart.zoom);
        }
        placeAll();
      },
      setTime(t) {
        time = t;
        placeAll();
      },
      resize() {
        for (const chart of charts) {
          if (!chart.u) continue;
          const width = Math.max(200, chart.figure.clientWidth);
          chart.u.setSize({ width, height: plotHeight(width, chart.figure) });
        }
        placeAll();
      },
    };
  }

  window.whatnextPlots = { create };
})();
