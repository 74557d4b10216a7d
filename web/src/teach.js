// What the page teaches beside the animation: the energy bars (the ledger at the time shown), the
// "why" (what each impact law keeps, the stiff rope's answer with its damping ratio, the latch,
// negative energies) and the QR code of the machine's link. Every number is the library's: the
// bars read the run's samples, the "why" runs the machine (app.js hands over `run`); only the
// rebound e(ζ) of a one-sided spring-damper is worked out here, from its closed form in
// docs/impact.md (it belongs to no machine).
(function () {
  'use strict';

  const S = window.whatnextStrings;
  const T = (english, args) => S.t(english, args);
  const $ = (id) => document.getElementById(id);
  const num = (x, digits = 3) => S.decimals(String(Number(x.toPrecision(digits))));
  const fixed = (x, digits) => S.decimals(x.toFixed(digits));

  // ---- the energy bars --------------------------------------------------------------------------
  // The ledger of docs/extensions.md: initial = now + lost + dissipated − the lid's work on the
  // balloon. Each row a sum of sample columns (json keys of columns.hpp, and the bindings' own).
  // A body's rows have its colour in the drawing (the library's, machine.js), its potential energy
  // a lighter shade of it; the other rows their own.
  const kRows = [
    { name: 'sandbag, kinetic', part: 'sandbag', keys: ['sandbag_kinetic'] },
    { name: 'sandbag, potential', part: 'sandbag', light: true, keys: ['sandbag_potential'] },
    { name: 'lid, kinetic', part: 'lid', keys: ['lid_kinetic'] },
    { name: 'lid, potential', part: 'lid', light: true, keys: ['lid_potential'] },
    { name: 'seesaw, kinetic', part: 'seesaw', keys: ['seesaw_kinetic'] },
    { name: 'seesaw, potential', part: 'seesaw', light: true, keys: ['seesaw_potential'] },
    { name: 'rope, spring', colour: '#6a3d9a', keys: ['rope_potential'] },
    { name: 'balloon, kinetic and lift', part: 'balloon', keys: ['balloon_kinetic', 'balloon_potential'] },
    { name: 'lost in impacts', colour: '#8a1c1c', keys: ['lost_impacts', 'lost_balloon_catch'] },
    { name: 'friction heat', colour: '#a15c00', keys: ['dissipated_friction'] },
    { name: 'damping', colour: '#5f6368', keys: ['dissipated_pivot', 'dissipated_lid_hinge', 'dissipated_drag', 'dissipated_rope'] },
    { name: 'lid\'s work on the balloon', colour: '#999999', keys: ['lid_push_on_balloon'], sign: -1 },
  ];
  const colourOf = (row) => {
    if (!row.part) return row.colour;
    const c = window.whatnextMachine.colour[row.part];
    if (!row.light) return c;
    const [r, g, b] = c.match(/\d+/g).map(Number);
    return `rgb(${[r, g, b].map((x) => Math.round((x + 255) / 2)).join(',')})`;
  };
  const prepared = new WeakMap();
  function rowsOf(run) {
    let p = prepared.get(run);
    if (p) return p;
    const s = run.samples, n = s.t.length;
    const value = (row, i) => (row.sign || 1) * row.keys.reduce((sum, k) => sum + (s[k] ? s[k][i] : 0), 0);
    const rows = kRows.filter((row) => row.keys.some((k) => s[k]) && Array.from({ length: n }, (x, i) => i).some((i) => Math.abs(value(row, i)) > 1e-12));
    let lo = 0, hi = 0;
    for (let i = 0; i < n; ++i) {
      for (const row of rows) { const v = value(row, i); lo = Math.min(lo, v); hi = Math.max(hi, v); }
      lo = Math.min(lo, s.initial_total[i]); hi = Math.max(hi, s.initial_total[i]);
    }
    const box = $('bars');
    box.textContent = '';
    const cells = rows.map((row) => {
      const name = document.createElement('span');
      name.className = 'bar-name';
      name.textContent = T(row.name);
      const track = document.createElement('span');
      track.className = 'bar-track';
      track.innerHTML = `<span class="bar-zero" style="left: ${(100 * -lo) / (hi - lo || 1)}%"></span><span class="bar-fill" style="background: ${colourOf(row)}"></span>`;
      const out = document.createElement('span');
      out.className = 'bar-value';
      box.append(name, track, out);
      return { row, fill: track.lastChild, out };
    });
    const total = document.createElement('span');
    total.className = 'bar-total';
    total.style.gridColumn = '1 / -1';
    box.append(total);
    $('bars-zero').textContent = T('Zero of potential energy: the sandbag and the seesaw at the pivot\'s height, the lid lying flat (at its hinge\'s height), the balloon\'s lift at the box\'s top. Below the zero a potential energy is negative (a bar to the left).');
    p = { rows, cells, total, lo, hi, value };
    prepared.set(run, p);
    return p;
  }

  // The bars at time t: each row's value interpolated between the samples around t (the
  // ledger's terms each linearly, so that they still add up to the start's energy).
  function bars(run, t) {
    const p = rowsOf(run), s = run.samples, ts = s.t;
    let lo = 0, hi = ts.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (ts[mid] <= t) lo = mid + 1; else hi = mid; }
    const j = lo, i = Math.max(0, j - 1);
    const w = j < ts.length && ts[j] > ts[i] && t > ts[i] ? (t - ts[i]) / (ts[j] - ts[i]) : 0;
    const at = (f) => (w > 0 ? f(i) + (f(j) - f(i)) * w : f(i));
    const span = p.hi - p.lo || 1, zero = -p.lo / span;
    let sum = 0;
    const said = [];
    for (const c of p.cells) {
      const v = at((k) => p.value(c.row, k));
      sum += v;
      const a = Math.min(zero, zero + v / span), b = Math.max(zero, zero + v / span);
      c.fill.style.left = `${100 * a}%`;
      c.fill.style.width = `${100 * (b - a)}%`;
      const text = `${fixed(v, 3)} J`;
      if (c.out.textContent !== text) c.out.textContent = text;
      said.push(`${T(c.row.name)} ${text}`);
    }
    const start = s.initial_total[0];
    const total = T('Sum {sum} J = energy at the start {start} J', { sum: fixed(sum, 3), start: fixed(start, 3) });
    if (p.total.textContent !== total) p.total.textContent = total;
    const label = `${T('Energy bars')}: ${said.join(', ')}. ${total}.`;
    if ($('bars').getAttribute('aria-label') !== label) $('bars').setAttribute('aria-label', label);
    return { sum, start };
  }

  // ---- the rebound of a rope that can only pull: e(ζ) -------------------------------------------
  // m x'' = −max(0, k x + c x'), struck at speed v: in units of √(m/k) and v, x'' + 2ζ x' + x = 0
  // from x = 0, x' = 1 until the pull x + 2ζ x' falls to zero; e is the speed it leaves with.
  function restitution(zeta) {
    if (zeta <= 0) return 1;
    const motion = (t) => {
      if (zeta < 1) {
        const wd = Math.sqrt(1 - zeta * zeta), decay = Math.exp(-zeta * t);
        const x = decay * Math.sin(wd * t) / wd;
        return [x, decay * (Math.cos(wd * t) - (zeta / wd) * Math.sin(wd * t))];
      }
      if (zeta === 1) return [t * Math.exp(-t), (1 - t) * Math.exp(-t)];
      const q = Math.sqrt(zeta * zeta - 1), r1 = -zeta + q, r2 = -zeta - q;
      return [(Math.exp(r1 * t) - Math.exp(r2 * t)) / (r1 - r2), (r1 * Math.exp(r1 * t) - r2 * Math.exp(r2 * t)) / (r1 - r2)];
    };
    const pull = (t) => { const [x, v] = motion(t); return x + 2 * zeta * v; };
    // The pull starts at 2ζ > 0 and ends at its first zero: bracket it, then halve.
    let a = 0, b = 1e-3;
    while (pull(b) > 0 && b < 1e4) { a = b; b *= 1.5; }
    for (let k = 0; k < 200; ++k) { const m = 0.5 * (a + b); if (pull(m) > 0) a = m; else b = m; }
    return -motion(b)[1];
  }

  // ---- the "why" ----------------------------------------------------------------------------------
  let why = null;  // {run(sets) -> result}, from app.js
  const kLawWords = {
    rope: 'rope (the paper\'s eq. 7): the jerk is perfectly inelastic, like clay on clay. After it the sandbag and the lid move together as the straight rope lets them; the kinetic energy they lose is the most any law may lose.',
    'angular-momentum-sum': 'angular-momentum-sum: keeps the sum of the sandbag\'s angular momentum about the pivot and the lid\'s about its hinge. It loses less kinetic energy than the rope law, and on some machines can even gain some.',
    'kinetic-energy': 'kinetic-energy: keeps the kinetic energy: an elastic jerk, nothing lost. The lid leaves faster than under the rope law.',
    'linear-momentum': 'linear-momentum: keeps the linear momentum of the sandbag and the lid\'s centre. It can make energy out of nothing: the paper calls it unphysical.',
  };

  function paragraph(parent, text, tag = 'p') {
    const p = document.createElement(tag);
    p.textContent = text;
    parent.append(p);
    return p;
  }

  function showWhy(box, current) {
    box.textContent = '';
    paragraph(box, T('What each impact law keeps and loses'), 'h3');
    paragraph(box, T('When the rope snaps straight (or the sandbag lands), the speeds jump in no time. The paper offers four laws for the jump; each keeps something else:'));
    const list = document.createElement('ul');
    for (const law of Object.keys(kLawWords)) {
      const li = paragraph(list, T(kLawWords[law]), 'li');
      if (law === current) li.append(` ${T('(this run\'s law)')}`);
    }
    box.append(list);
    paragraph(box, T('A real rope stretches: the answer of a stiff rope'), 'h3');
    paragraph(box, T('A stiff rope that stretches gives none of the four in general: it gives the rope law followed by a rebound. The rope springs back with Newton\'s restitution e(ζ), which depends only on the rope\'s damping ratio ζ: e = 1 for an undamped rope (an elastic bounce), e = 0.135 at ζ = 1, almost 0 for a well damped rope (the rope law). That is why "the rope that does not stretch" can change when the lid opens: a rope that stretches springs back.'));
    const zeta = document.createElement('div');
    zeta.className = 'zeta';
    zeta.innerHTML = '<label for="zeta"></label><input id="zeta" type="range" min="0" max="100" step="1" value="50"><output id="zeta-out" for="zeta"></output>';
    zeta.querySelector('label').textContent = T('rope\'s damping ratio ζ');
    box.append(zeta);
    const table = document.createElement('table');
    table.id = 'zeta-table';
    box.append(table);
    paragraph(box, T('The lid\'s speed right after the first jerk, from runs of this machine by the library: under each law, and under the rope law with the rebound e(ζ) (restitution.rope).'), 'p').className = 'note';
    paragraph(box, T('Why the lid latches (the radio machines)'), 'h3');
    paragraph(box, T('With a radio, the lid latches open at the angle where it counts as open and the rope is let go. The latch is an impact: it stops the lid at once, and the lid\'s kinetic energy goes into the latch. The timeline shows the energy before and after it and the latch\'s impulse on the lid, and the energy bars count it with the impacts\' losses. In the built machine (Konstanz) the seesaw then lands on the floor and the sandbag slides to the end stop: those impacts lose energy too, and the floor and the stop hold them (their reactions in the forces).'));
    paragraph(box, T('Would the students\' machine switch the radio on? (Konstanz)'), 'h3');
    paragraph(box, T('No. The machine students build opens its lid, but its balloon is a real party balloon: its rubber skin and ribbon weigh about 2 g, and the air drags on it. Its lift is small and the skin takes more than half of it: when the string is straight it pulls about 0.02 N, and the switch needs 0.03 N. So the radio stays off. The paper\'s sketch jokes that the machine may not do its job; with a real balloon it does not. The paper\'s balloon has no skin and no drag: that idealised machine is examples/konstanz-ideal.toml (load it with Open file…), and there the radio comes on.'));
    const fix = paragraph(box, T('What makes it work: a bigger balloon and a lighter switch. A balloon of 0.11 m radius (filled to 22 cm, it still fits the box) and a switch of 0.01 N (a foil flap a third as stiff) switch the radio on in 99.5 % of builds (docs/extensions.md).'));
    const tryIt = document.createElement('a');
    tryIt.id = 'konstanz-fix';
    tryIt.href = '#machine=konstanz&balloon.radius=0.11&radio.switch_force=0.01';
    tryIt.textContent = T('Try it: the build that works');
    fix.append(' ', tryIt);
    paragraph(box, T('Why energies can be negative'), 'h3');
    paragraph(box, T('Potential energy is measured from a chosen zero: here the pivot\'s height (the lid: lying flat). A sandbag below the pivot has negative potential energy, so the machine\'s energy E can be below zero. Only differences matter: what is lost at an impact is the same whatever the zero.'));

    const input = $('zeta');
    const laws = {};
    const lidSpeed = (r) => {
      if (!r || !r.ok) return null;
      const jerk = r.events.find((e) => e.type === 'rope_taut' && e.impact);
      return jerk ? Math.abs(jerk.state.dphi_l) * 180 / Math.PI : null;
    };
    const show = async () => {
      const z = Number(input.value) / 10;
      const e = restitution(z);
      const text = T('ζ = {z}: e(ζ) = {e}', { z: num(z, 2), e: fixed(e, 3) });
      $('zeta-out').textContent = text;
      input.setAttribute('aria-valuetext', text);
      const withRebound = lidSpeed(await why.run([`run.impact_law=rope`, `restitution.rope=${e}`]));
      const rows = [[T('rope law with the rebound e(ζ)'), withRebound]].concat(Object.keys(kLawWords).map((law) => [law, laws[law]]));
      table.textContent = '';
      const head = table.insertRow();
      for (const h of [T('law'), T('lid\'s speed after the jerk [°/s]')]) { const th = document.createElement('th'); th.textContent = h; head.append(th); }
      for (const [name, v] of rows) {
        const row = table.insertRow();
        row.insertCell().textContent = name;
        row.insertCell().textContent = v === null || v === undefined ? T('no jerk') : fixed(v, 1);
      }
      $('why').dataset.ready = 'true';
    };
    (async () => {
      for (const law of Object.keys(kLawWords)) laws[law] = lidSpeed(await why.run([`run.impact_law=${law}`]));
      await show();
    })();
    input.addEventListener('change', show);
    input.addEventListener('input', () => {
      const z = Number(input.value) / 10;
      $('zeta-out').textContent = T('ζ = {z}: e(ζ) = {e}', { z: num(z, 2), e: fixed(restitution(z), 3) });
    });
  }

  // ---- the QR code ---------------------------------------------------------------------------------
  // Dark modules on white with the standard's quiet zone of four modules: it scans on any screen.
  function showQr(link) {
    const box = $('qr-code');
    box.textContent = '';
    let qr = null;
    for (const level of ['M', 'L']) {
      try {
        qr = qrcode(0, level);
        qr.addData(link, 'Byte');
        qr.make();
        break;
      } catch (e) {
        qr = null;
      }
    }
    if (!qr) {
      $('qr-note').textContent = T('This link is too long for a QR code ({n} characters): use Copy link.', { n: link.length });
    } else {
      const n = qr.getModuleCount(), quiet = 4, size = n + 2 * quiet;
      let path = '';
      for (let r = 0; r < n; ++r) for (let c = 0; c < n; ++c) if (qr.isDark(r, c)) path += `M${c + quiet} ${r + quiet}h1v1h-1z`;
      box.innerHTML = `<svg xmlns="http://www.w3.org/2000/svg" viewBox="0 0 ${size} ${size}" shape-rendering="crispEdges" role="img"><rect width="${size}" height="${size}" fill="#fff"/><path d="${path}" fill="#000"/></svg>`;
      box.firstChild.setAttribute('aria-label', T('QR code of the link'));
      $('qr-note').textContent = link;
    }
    $('qr-dialog').showModal();
  }

  window.whatnextTeach = {
    bars,
    restitution,
    showQr,
    // The "why" for the machine shown; `run(extraSets)` runs it with more --set values.
    why(run, current) {
      why = { run };
      showWhy($('why-text'), current);
    },
  };
})();
