// The machine drawn to scale on a canvas, with the parts, colours and conventions of the
// animation that `whatnext animate` writes (both from src/viz/scene.cpp): x to the right, h up,
// metres, origin at the seesaw's pivot. A second run can be drawn as a ghost over the first. What
// is the page's own: how it frames the machine (extent), the arrows to parts beyond the picture
// and the caption.
(function () {
  'use strict';

  // The parts' colours are the animation's (src/viz/scene.hpp), from the library (useLibrary);
  // these two are the page's own: the caption's band and the outline of a run compared.
  const colour = {
    band: 'rgb(236,236,236)',
    ghost: 'rgb(60,90,200)',
  };

  const add = (a, b) => ({ x: a.x + b.x, h: a.h + b.h });
  const sub = (a, b) => ({ x: a.x - b.x, h: a.h - b.h });
  const norm = (a) => Math.hypot(a.x, a.h);
  const polar = (length, angle) => ({ x: length * Math.cos(angle), h: length * Math.sin(angle) });

  // Where each part is drawn is the library's: src/viz/scene.cpp, the table `whatnext animate`
  // draws from, through the WebAssembly module on this thread (app.js hands it over once it is
  // loaded). So the page and the animation draw the same points: the rope (taut, sagging, lying on
  // the lid, let go at the radio's latch), the lid, the seesaw and its end stop, the balloon and
  // its string, the radio, the stand, the box and the floor.
  let library = null;
  function useLibrary(module) {
    library = module;
    Object.assign(colour, module.colours());
  }

  // The scene of state s of a run, its left arm `arm` long and its end stop `stopHeight` high [m].
  function scene(run, s, arm, stopHeight) {
    const r = library.scene(run.input, s, arm, stopHeight, run.release);
    if (!r.ok) throw new Error(r.message);
    return r;
  }

  // The seesaw's end, the lid's edge and the balloon at every sample of a run (extent's points),
  // asked of the library once for each run.
  const traces = new WeakMap();
  function trace(run) {
    let t = traces.get(run);
    if (!t) {
      const s = run.samples;
      t = library.sceneTrace(run.input, s.phi_s, s.phi_l, s.balloon_x, s.balloon_h);
      if (!t.ok) throw new Error(t.message);
      traces.set(run, t);
    }
    return t;
  }

  // How high the end stop stands above the arm [m] at the view's scale, as the animation draws it
  // (the library's stopHeight); `extent` asks for the parts that stand still, where it is not drawn.
  const stopHeight = (v) => library.stopHeight(v.scale);

  // The first sample after time t (samples.t is sorted; n if none).
  function firstAfter(ts, t) {
    let lo = 0, hi = ts.length;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (ts[mid] <= t) lo = mid + 1; else hi = mid;
    }
    return lo;
  }

  // How far out the sandbag has been on the arm at or before each sample (0 before it lands),
  // once per run.
  const farthests = new WeakMap();
  function farthestOf(run) {
    let f = farthests.get(run);
    if (!f) {
      const s = run.samples, n = s.t.length;
      f = new Float64Array(n);
      let far = 0;
      for (let i = 0; i < n; ++i) {
        if (s.on_seesaw[i]) far = Math.max(far, s.r[i]);
        f[i] = far;
      }
      farthests.set(run, f);
    }
    return f;
  }
  // ... up to time t: at the last sample at or before it.
  function farthestAt(run, t) {
    const k = firstAfter(run.samples.t, t) - 1;
    return k < 0 ? 0 : farthestOf(run)[k];
  }

  // The left arm as drawn, as the animation draws it (the library's drawnArm): a finite arm as it
  // is; the endless arm `endless` long, or a little beyond the farthest the sandbag has been out on
  // it so far.
  const drawnArm = (run, endless, farthest) => library.drawnArm(run.machine.seesaw_left_arm, endless, farthest);

  // The state at time t: continuous quantities interpolated between the recorded states around
  // t, the contacts and the mode from the last recorded state at or before t (after an event at t).
  const kContinuous = ['x', 'h', 'r', 'phi_s', 'phi_l', 'balloon_h', 'balloon_x', 'tension', 'energy',
                       'vx', 'vh', 'dphi_l', 'normal_force', 'stop_reaction', 'floor_reaction', 'bag_floor_reaction'];
  const kDiscrete = ['on_seesaw', 'rope_taut', 'mode', 'lid_resting', 'balloon_stuck',
                     'at_stop', 'bag_on_floor', 'seesaw_on_floor', 'rope_let_go'];
  function stateAt(samples, t) {
    const ts = samples.t;
    const j = firstAfter(ts, t), i = Math.max(0, j - 1);
    const s = { t };
    const w = j < ts.length && ts[j] > ts[i] && t > ts[i] ? (t - ts[i]) / (ts[j] - ts[i]) : 0;
    for (const k of kContinuous) {
      if (!samples[k]) continue;
      s[k] = w > 0 ? samples[k][i] + (samples[k][j] - samples[k][i]) * w : samples[k][i];
    }
    for (const k of kDiscrete) if (samples[k]) s[k] = samples[k][i];
    return s;
  }

  // The i-th recorded state.
  function sampleAt(samples, i) {
    const s = { t: samples.t[i] };
    for (const k of [...kContinuous, ...kDiscrete]) if (samples[k]) s[k] = samples[k][i];
    return s;
  }

  // How far from the pivot the picture follows the seesaw's left arm, the sandbag and the balloon:
  // the machine's own size (its right arm, or the box's far side), so that the machine fills the
  // picture, as a teacher projecting it wants to see it.
  const reachOf = (m) => Math.max(1.5 * m.seesaw_right_arm, norm(m.hinge) + 2 * m.lid_half_length);

  // The region to show: the machine itself over the run (the pivot's stand, the box with its lid,
  // the radio, the balloon, the seesaw's right arm) and, of the left arm, the sandbag and the
  // balloon, what stays within reachOf(m) of the pivot. Farther out (an endless arm, a sandbag
  // that slides or flies far, a balloon on a long string) a part leaves the picture; an arrow at
  // the edge points to the sandbag or the balloon, and the caption says how far (draw).
  function extent(run) {
    const m = run.machine, s = run.samples, n = s.t.length;
    const still = library.stopHeight(Infinity);
    const first = scene(run, sampleAt(s, 0), 0, still), last = scene(run, sampleAt(s, n - 1), 0, still);
    // The left arm before the sandbag lands: long enough to catch it, as the animation draws it.
    const leftArm = first.endlessArm;
    const reach = reachOf(m);
    const box = { x0: Infinity, x1: -Infinity, h0: Infinity, h1: -Infinity, leftArm };
    const put = (p) => {
      if (!Number.isFinite(p.x) || !Number.isFinite(p.h)) return;
      box.x0 = Math.min(box.x0, p.x); box.x1 = Math.max(box.x1, p.x);
      box.h0 = Math.min(box.h0, p.h); box.h1 = Math.max(box.h1, p.h);
    };
    const g = first.ground, radio = first.radio, walls = first.walls, rl = m.lid_half_length;
    put({ x: 0, h: 0 }); put({ x: -0.15, h: g }); put({ x: 0.15, h: g });
    put({ x: walls[0].x - 0.05, h: g }); put({ x: walls[3].x + 0.05, h: walls[3].h });
    put(add(m.hinge, { x: 0, h: 2 * rl }));  // the lid upright
    put({ x: radio.x0 - 0.05, h: radio.h0 }); put({ x: radio.x1 + 0.05, h: radio.h1 + 0.05 });
    if (run.events.some((e) => e.type === 'radio_on')) put({ x: radio.x1, h: radio.h1 + 0.25 });  // the notes
    const tr = trace(run), far = farthestOf(run), every = Math.max(1, Math.floor(n / 4000));
    for (let i = 0; i < n; i += (s.event[i] >= 0 ? 1 : every)) {
      put({ x: tr.seesawX[i], h: tr.seesawH[i] });
      put({ x: tr.lidX[i], h: tr.lidH[i] });
      // Below the floor the left arm and the sandbag have left the machine (the model has no floor
      // for them): they leave the picture there.
      const shown = Math.min(drawnArm(run, leftArm, far[i]), reach);
      const armEnd = polar(-shown, s.phi_s[i]);
      put({ x: armEnd.x, h: Math.max(armEnd.h, g) });
      if (Math.hypot(s.x[i], s.h[i]) <= reach) put({ x: s.x[i], h: Math.max(s.h[i], g) });
      const c = { x: tr.balloonX[i], h: tr.balloonH[i] };
      if (c.h - m.hinge.h <= reach) {
        put(add(c, { x: m.balloon_radius, h: m.balloon_radius }));
        put(sub(c, { x: m.balloon_radius, h: m.balloon_radius }));
      }
    }
    if (m.radio) {
      for (const end of [first, last]) {
        for (const p of end.string) {
          if (norm(sub(p, m.radio_switch)) <= reach) put({ x: p.x, h: Math.max(p.h, g) });
        }
      }
    }
    const pad = 0.05 * Math.max(box.x1 - box.x0, box.h1 - box.h0);
    box.x0 -= pad; box.x1 += pad; box.h0 -= pad; box.h1 += pad;
    return box;
  }

  // World to canvas pixels: the extent fitted below the caption band, the same scale on both axes.
  function makeView(run, width, height, top) {
    const box = extent(run);
    const areaH = Math.max(1, height - top);
    const k = Math.max(1e-9, Math.min(width / (box.x1 - box.x0), areaH / (box.h1 - box.h0)));
    return {
      width, height, top, scale: k, leftArm: box.leftArm,
      ox: 0.5 * width - 0.5 * (box.x0 + box.x1) * k,
      oy: top + 0.5 * areaH + 0.5 * (box.h0 + box.h1) * k,
    };
  }

  const toPixel = (v, p) => ({ x: v.ox + p.x * v.scale, y: v.oy - p.h * v.scale });

  function painter(ctx, v) {
    const px = (p) => toPixel(v, p);
    return {
      line(points) {
        ctx.beginPath();
        points.forEach((p, i) => { const q = px(p); if (i) ctx.lineTo(q.x, q.y); else ctx.moveTo(q.x, q.y); });
        ctx.stroke();
      },
      circle(c, radius) {
        const q = px(c);
        ctx.beginPath();
        ctx.arc(q.x, q.y, radius, 0, 2 * Math.PI);
      },
      width(metres, minPx) { ctx.lineWidth = Math.max(minPx, metres * v.scale); },
      rect(x0, h0, x1, h1) {
        const a = px({ x: x0, h: h1 });
        ctx.fillRect(a.x, a.y, (x1 - x0) * v.scale, (h1 - h0) * v.scale);
      },
    };
  }

  // The parts that never move: floor, pivot stand, box, radio. The paper's model has no floor
  // but pieces of it under the stand, the box and the radio; the built machine's floor
  // (floor.enabled) runs across the picture with the ground below it, as in the animation.
  function drawStill(ctx, v, sc, radioOn, radioPlaying) {
    const p = painter(ctx, v);
    const g = sc.ground, radio = sc.radio, walls = sc.walls;
    if (sc.floor) {
      const y = toPixel(v, { x: 0, h: g }).y;
      ctx.fillStyle = colour.ground;
      ctx.fillRect(0, y, v.width, v.height - y);
    }
    ctx.strokeStyle = colour.midGrey;
    p.width(0.01, 2);
    const pieces = sc.floor ? [[{ x: (0 - v.ox) / v.scale, h: g }, { x: (v.width - v.ox) / v.scale, h: g }]] : sc.floorPieces;
    for (const piece of pieces) p.line(piece);
    ctx.fillStyle = colour.grey;
    ctx.beginPath();
    for (const q of sc.stand.map((w) => toPixel(v, w))) ctx.lineTo(q.x, q.y);
    ctx.closePath();
    ctx.fill();
    ctx.fillStyle = colour.boxInside;
    p.rect(walls[1].x, walls[1].h, walls[3].x, walls[3].h);

    ctx.save();
    if (!radioOn) ctx.globalAlpha = 0.3;  // Kermit's radio, not part of this run
    ctx.fillStyle = colour.radio;
    p.rect(radio.x0, radio.h0, radio.x1, radio.h1);
    ctx.fillStyle = colour.dial;
    p.circle(sc.dial, sc.dialRadius * v.scale * sc.dialSquash);
    ctx.fill();
    ctx.strokeStyle = colour.dark;
    p.width(0.012, 2);
    p.line(sc.radioPost);
    if (radioPlaying) {  // notes above the radio, where extent keeps room, as in the animation
      ctx.fillStyle = colour.radio;
      ctx.font = `bold ${Math.max(12, 0.12 * v.scale)}px sans-serif`;
      ctx.textAlign = 'center';
      const q = toPixel(v, sc.notes);
      ctx.fillText('\u266A \u266B', q.x, q.y);
    }
    ctx.restore();
  }

  function drawWalls(ctx, v, sc) {
    const p = painter(ctx, v);
    ctx.strokeStyle = colour.boxWall;
    p.width(0.02, 3);
    p.line(sc.walls);
  }

  function drawBalloon(ctx, v, sc, ghost, radioOn) {
    const p = painter(ctx, v);
    if (radioOn || !ghost) {
      ctx.save();
      if (!radioOn) ctx.globalAlpha = 0.3;
      ctx.strokeStyle = ghost ? colour.ghost : colour.grey;
      ctx.lineWidth = 1.5;
      p.line(sc.string);
      ctx.restore();
    }
    p.circle(sc.balloon, sc.balloonRadius * v.scale);
    paint(ctx, ghost, colour.balloon, null);
  }

  // Fills the path just made in the part's colour (with an outline if given); a ghost only
  // outlines it.
  function paint(ctx, ghost, fill, outline) {
    if (ghost) {
      ctx.strokeStyle = colour.ghost;
      ctx.lineWidth = 2;
      ctx.stroke();
      return;
    }
    ctx.fillStyle = fill;
    ctx.fill();
    if (outline) {
      ctx.strokeStyle = outline;
      ctx.lineWidth = 1;
      ctx.stroke();
    }
  }

  // Lid, seesaw, rope and sandbag. Returns where the sandbag is on the canvas. The built machine
  // stands on its floor: nothing of these is drawn below it (a sandbag lying there, a point in
  // the model, is half a disc; the seesaw's end resting there a cut bar).
  function drawMoving(ctx, v, sc, ghost) {
    const p = painter(ctx, v);
    ctx.save();
    if (sc.floor) {
      ctx.beginPath();
      ctx.rect(0, 0, v.width, toPixel(v, { x: 0, h: sc.ground }).y);
      ctx.clip();
    }
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    ctx.strokeStyle = ghost ? colour.ghost : colour.lid;
    p.width(0.025, 3);
    p.line([sc.hinge, sc.lidEnd]);
    if (!ghost) {
      ctx.fillStyle = 'black';
      p.circle(sc.hinge, Math.max(2, 0.012 * v.scale));
      ctx.fill();
    }
    ctx.strokeStyle = ghost ? colour.ghost : colour.seesaw;
    p.width(0.03, 4);
    p.line([sc.armLeft, sc.armRight]);
    if (sc.endStop) p.line([sc.armLeft, sc.stopTop]);  // an edge standing up from the left arm's end
    if (!ghost) {
      ctx.fillStyle = 'black';
      p.circle({ x: 0, h: 0 }, Math.max(2.5, 0.015 * v.scale));
      ctx.fill();
    }
    // The rope: straight when taut; slack, sagging or lying on the lid; let go, hanging from the lid.
    ctx.strokeStyle = ghost ? colour.ghost : colour.dark;
    ctx.lineWidth = Math.max(1.5, 0.008 * v.scale);
    if (ghost) ctx.setLineDash([6, 4]);
    p.line(sc.rope);
    ctx.setLineDash([]);
    // The sandbag, centred on the simulated point.
    const bag = toPixel(v, sc.sandbag);
    const radius = Math.max(6, 0.05 * v.scale);
    ctx.beginPath();
    ctx.arc(bag.x, bag.y, radius, 0, 2 * Math.PI);
    paint(ctx, ghost, colour.sandbag, colour.dark);
    ctx.restore();
    return { x: bag.x, y: bag.y, radius };
  }

  // An arrow at the edge of the picture, on the line from `from` towards a part beyond the picture
  // (its distance is in the caption), in the part's colour with a white rim; `size` in pixels.
  function drawFar(ctx, v, from, to, fill, size) {
    const o = toPixel(v, from), p = toPixel(v, to);
    const dx = p.x - o.x, dy = p.y - o.y, len = Math.hypot(dx, dy);
    if (!(len > 0)) return;
    const ux = dx / len, uy = dy / len, edge = 0.6 * size;
    let reach = Infinity;
    if (ux > 0) reach = Math.min(reach, (v.width - edge - o.x) / ux);
    if (ux < 0) reach = Math.min(reach, (edge - o.x) / ux);
    if (uy > 0) reach = Math.min(reach, (v.height - edge - o.y) / uy);
    if (uy < 0) reach = Math.min(reach, (v.top + edge - o.y) / uy);
    const tx = o.x + ux * reach, ty = o.y + uy * reach, back = 1.6 * size, half = 0.7 * size;
    ctx.beginPath();
    ctx.moveTo(tx, ty);
    ctx.lineTo(tx - back * ux - half * uy, ty - back * uy + half * ux);
    ctx.lineTo(tx - back * ux + half * uy, ty - back * uy - half * ux);
    ctx.closePath();
    ctx.lineJoin = 'round';
    ctx.lineWidth = 3;
    ctx.strokeStyle = 'white';
    ctx.stroke();
    ctx.fillStyle = fill;
    ctx.fill();
  }

  // The page's words where the page has them (strings.js), else English.
  const words = (english, args) => (window.whatnextStrings ? window.whatnextStrings.t(english, args)
                                    : english.replace(/\{(\w+)\}/g, (m, k) => args[k]));
  const number = (x) => {
    const text = String(Number(x.toPrecision(4)));
    return window.whatnextStrings ? window.whatnextStrings.decimals(text) : text;
  };

  // Splits text into at most n lines that fit the width, breaking between words (the last line
  // takes the rest).
  function wrap(ctx, text, width, n) {
    const lines = [];
    let rest = text.split(' ');
    while (lines.length < n - 1 && rest.length) {
      let k = rest.length;
      while (k > 1 && ctx.measureText(rest.slice(0, k).join(' ')).width > width) --k;
      if (k === rest.length) break;
      lines.push(rest.slice(0, k).join(' '));
      rest = rest.slice(k);
    }
    if (rest.length) lines.push(rest.join(' '));
    return lines;
  }

  // One picture: the main run at its state, the other run as a ghost, and the caption band
  // (time and mode; the event in red on an event's frame, on frame.lines lines at most).
  function draw(ctx, v, frame) {
    const { run, state: s, caption, event, font } = frame;
    // Other runs drawn as outlines, each in its colour (frame.ghost: one, in the ghost colour).
    const ghosts = frame.ghosts || (frame.ghost ? [frame.ghost] : []);
    const inColour = (g, fn) => {
      const was = colour.ghost;
      colour.ghost = g.colour || was;
      fn();
      colour.ghost = was;
    };
    const m = run.machine;
    // Each run's scene at its state, its left arm as long as the picture draws it.
    const sceneOf = (r, state) => scene(r, state, drawnArm(r, v.leftArm, farthestAt(r, state.t)), stopHeight(v));
    const sc = sceneOf(run, s);
    const ghostScenes = ghosts.map((g) => sceneOf(g.run, g.state));
    ctx.save();
    ctx.fillStyle = 'white';
    ctx.fillRect(0, 0, v.width, v.height);
    ctx.beginPath();
    ctx.rect(0, v.top, v.width, v.height - v.top);
    ctx.clip();
    const radioPlaying = run.radioOnAt !== null && s.t >= run.radioOnAt;
    drawStill(ctx, v, sc, m.radio, radioPlaying);
    ghosts.forEach((g, i) => inColour(g, () => drawBalloon(ctx, v, ghostScenes[i], true, g.run.machine.radio)));
    drawBalloon(ctx, v, sc, false, m.radio);
    drawWalls(ctx, v, sc);
    ghosts.forEach((g, i) => {
      ctx.save();
      ctx.globalAlpha = 0.6;
      inColour(g, () => drawMoving(ctx, v, ghostScenes[i], true));
      ctx.restore();
    });
    const bag = drawMoving(ctx, v, sc, false);
    ctx.restore();
    // The sandbag and the balloon beyond the picture: an arrow at its edge, the distance in the
    // caption.
    const inPicture = (q, r) => q.x >= -r && q.x <= v.width + r && q.y >= v.top - r && q.y <= v.height + r;
    const visible = inPicture(bag, bag.radius);
    const arrow = Math.max(10, 0.7 * font);
    if (!visible) drawFar(ctx, v, { x: 0, h: 0 }, { x: s.x, h: s.h }, colour.sandbag, arrow);
    const balloon = sc.balloon, boxTop = { x: balloon.x, h: m.hinge.h };
    const balloonVisible = inPicture(toPixel(v, balloon), sc.balloonRadius * v.scale);
    if (!balloonVisible) drawFar(ctx, v, boxTop, balloon, colour.balloon, arrow);
    const far = [];
    if (!visible) far.push(words('sandbag {d} m out', { d: number(Math.hypot(s.x, s.h)) }));
    if (!balloonVisible) far.push(words('balloon {d} m up', { d: number(balloon.h - m.hinge.h) }));

    // Caption band, as in the animation.
    ctx.fillStyle = event ? 'rgb(255,235,235)' : colour.band;
    ctx.fillRect(0, 0, v.width, v.top);
    const margin = 0.6 * font;
    const fit = (text, size, weight) => {
      ctx.font = `${weight} ${size}px sans-serif`;
      const w = ctx.measureText(text).width, room = v.width - 2 * margin;
      if (w > room) ctx.font = `${weight} ${size * room / w}px sans-serif`;
    };
    ctx.fillStyle = 'black';
    fit(caption[0], font, '600');
    ctx.fillText(caption[0], margin, 1.2 * font);
    // A sandbag beyond the picture: its distance at the right end of the second line, as the
    // animation writes it (next to the arrow it would cover the machine).
    let room = v.width - 2 * margin;
    if (far.length) {
      const out = far.join(' · ');
      ctx.font = `400 ${0.9 * font}px sans-serif`;
      const w = ctx.measureText(out).width, most = 0.45 * v.width;
      if (w > most) ctx.font = `400 ${0.9 * font * most / w}px sans-serif`;
      const used = Math.min(w, most);
      ctx.fillStyle = colour.bagText;
      ctx.fillText(out, v.width - margin - used, 2.35 * font);
      room -= used + font;
    }
    ctx.fillStyle = event ? colour.eventRed : colour.grey;
    const weight = event ? '600' : '400';
    ctx.font = `${weight} ${0.9 * font}px sans-serif`;
    wrap(ctx, caption[1], room, frame.lines || 1).forEach((line, i) => {
      ctx.font = `${weight} ${0.9 * font}px sans-serif`;
      const w = ctx.measureText(line).width;
      if (w > room) ctx.font = `${weight} ${0.9 * font * room / w}px sans-serif`;
      ctx.fillText(line, margin, (2.35 + 1.1 * i) * font);
    });
    if (event) {  // the event's frame, outlined as in the animation's held frames
      ctx.strokeStyle = colour.eventRed;
      ctx.lineWidth = 4;
      ctx.strokeRect(2, 2, v.width - 4, v.height - 4);
    }
    let forces = null;
    if (frame.forces) {
      ctx.save();
      ctx.beginPath();
      ctx.rect(0, v.top, v.width, v.height - v.top);
      ctx.clip();
      forces = drawForces(ctx, v, run, s, font, frame.impulses);
      ctx.restore();
    }
    return { ...bag, far: far.join(' · '), forces };
  }

  // ---- forces, velocities and impulses on the machine ----
  // The arrows are the library's (its `forces` export: the snapshot's tension, contact forces and
  // velocities, each placed where it acts); the page only scales them. One scale per run, stated
  // in the legend: the sandbag's weight is a fixed share of the picture, so that gravity, the arm's
  // push and the floor's reactions read against it; an arrow longer than kLongest of the picture
  // is cut short (marked with two bars) and its value says how much it is.
  const kArrowColour = { weight: 'rgb(0,110,40)', tension: 'rgb(110,40,150)', contact: 'rgb(0,85,204)',
                         velocity: 'rgb(200,90,0)', impulse: 'rgb(200,0,60)' };
  const kindOf = (what) => (what.startsWith('weight') ? 'weight' : what.startsWith('tension') ? 'tension'
    : what.startsWith('velocity') ? 'velocity' : what.startsWith('impulse') ? 'impulse' : 'contact');
  const kLongest = 0.38;
  function arrowsOf(run, s, v, impulses) {
    const state = Object.assign({}, s);
    const r = library.forces(run.input, state, drawnArm(run, v.leftArm, farthestAt(run, s.t)), stopHeight(v), run.release,
                             impulses || null);
    if (!r.ok) throw new Error(r.message);
    return r.arrows;
  }
  // Pixels per N, per m/s and per N s for a run in a view: the sandbag's weight a tenth of the
  // picture's height, its fastest speed and the largest impulse a quarter.
  const scales = new WeakMap();
  function scalesOf(run, v) {
    let k = scales.get(run);
    if (!k || k.height !== v.height) {
      const m = run.machine, s = run.samples, areaH = v.height - v.top;
      let speed = 0, impulse = 0;
      for (let i = 0; i < s.t.length; ++i) speed = Math.max(speed, Math.hypot(s.vx[i], s.vh[i]));
      // The lid's angular impulse is drawn at its edge, 2 r_L from the hinge (the library's forces).
      for (const e of run.events) if (e.impulses) for (const [key, j] of Object.entries(e.impulses)) impulse = Math.max(impulse, Math.abs(/lid/.test(key) ? j / (2 * m.lid_half_length) : j));
      const nice = (x) => { const p = Math.pow(10, Math.floor(Math.log10(x))); return [1, 2, 5, 10].map((f) => f * p).find((y) => y >= x * 0.999); };
      const weight = m.sandbag_mass * m.gravity;
      k = { height: v.height, force: 0.1 * areaH / weight, velocity: speed > 0 ? 0.25 * areaH / speed : 0,
            impulse: impulse > 0 ? 0.25 * areaH / impulse : 0 };
      // The legend's round values: N, m/s and N s that are about a tenth of the picture.
      k.legend = { force: nice(0.1 * areaH / k.force), velocity: k.velocity ? nice(0.1 * areaH / k.velocity) : 0,
                   impulse: k.impulse ? nice(0.1 * areaH / k.impulse) : 0 };
      scales.set(run, k);
    }
    return k;
  }
  function arrowShape(ctx, x0, y0, x1, y1, colour, width, cut) {
    const dx = x1 - x0, dy = y1 - y0, len = Math.hypot(dx, dy);
    if (len < 1) return;
    const ux = dx / len, uy = dy / len, head = Math.min(len * 0.5, 4 + 2.5 * width);
    ctx.save();
    ctx.lineCap = 'round';
    for (const [style, w] of [['white', width + 3], [colour, width]]) {
      ctx.strokeStyle = style;
      ctx.lineWidth = w;
      ctx.beginPath();
      ctx.moveTo(x0, y0);
      ctx.lineTo(x1 - ux * head * 0.8, y1 - uy * head * 0.8);
      ctx.stroke();
    }
    ctx.fillStyle = colour;
    ctx.beginPath();
    ctx.moveTo(x1, y1);
    ctx.lineTo(x1 - ux * head - uy * head * 0.55, y1 - uy * head + ux * head * 0.55);
    ctx.lineTo(x1 - ux * head + uy * head * 0.55, y1 - uy * head - ux * head * 0.55);
    ctx.closePath();
    ctx.fill();
    if (cut) {  // two bars across the shaft: longer than drawn
      const mx = x0 + dx * 0.5, my = y0 + dy * 0.5;
      ctx.strokeStyle = colour;
      ctx.lineWidth = 2;
      for (const d of [-3, 3]) {
        ctx.beginPath();
        ctx.moveTo(mx + ux * d - uy * 6, my + uy * d + ux * 6);
        ctx.lineTo(mx + ux * d + uy * 6, my + uy * d - ux * 6);
        ctx.stroke();
      }
    }
    ctx.restore();
  }
  // Draws the forces and velocities of state s (impulses: an impact's, flashed instead of them)
  // and returns what was drawn, [{what, value, unit}], for the page's words and its tests.
  function drawForces(ctx, v, run, s, font, impulses) {
    const k = scalesOf(run, v), drawn = [];
    const areaH = v.height - v.top, longest = kLongest * areaH;
    const list = impulses ? impulses.flatMap((imp) => arrowsOf(run, imp.state, v, imp.impulses)) : arrowsOf(run, s, v, null);
    ctx.save();
    ctx.font = `600 ${Math.max(11, 0.72 * font)}px sans-serif`;
    for (const a of list) {
      const kind = kindOf(a.what);
      const value = Math.hypot(a.vec.x, a.vec.h);
      const per = kind === 'velocity' ? k.velocity : kind === 'impulse' ? k.impulse : k.force;
      if (!(per > 0)) continue;
      const o = toPixel(v, a.at);
      let len = value * per;
      const cut = len > longest;
      if (cut) len = longest;
      if (len < 3) continue;
      const x1 = o.x + (a.vec.x / value) * len, y1 = o.y - (a.vec.h / value) * len;
      arrowShape(ctx, o.x, o.y, x1, y1, kArrowColour[kind], kind === 'impulse' ? 4 : 2.5, cut);
      const label = `${number(value)} ${a.unit}`;
      ctx.fillStyle = kArrowColour[kind];
      ctx.textAlign = x1 >= o.x ? 'left' : 'right';
      ctx.lineWidth = 3;
      ctx.strokeStyle = 'white';
      const lx = x1 + (x1 >= o.x ? 4 : -4), ly = y1 + (y1 > o.y ? font * 0.8 : -3);
      ctx.strokeText(label, lx, ly);
      ctx.fillText(label, lx, ly);
      drawn.push({ what: a.what, value, unit: a.unit, cut });
    }
    // The scale, in the picture's upper right corner (below the caption), clear of the floor.
    ctx.textAlign = 'left';
    let y = v.top + 1.0 * font;
    const bars = impulses ? [['impulse', k.legend.impulse, 'N s', k.impulse]]
      : [['weight', k.legend.force, 'N', k.force], ['velocity', k.legend.velocity, 'm/s', k.velocity]];
    for (const [kind, amount, unit, per] of bars) {
      if (!(per > 0) || !(amount > 0)) continue;
      const text = `${number(amount)} ${unit}`, x0 = v.width - 0.6 * font - ctx.measureText(text).width - 5 - amount * per;
      arrowShape(ctx, x0, y, x0 + amount * per, y, kArrowColour[kind], 2.5, false);
      ctx.fillStyle = kArrowColour[kind];
      ctx.fillText(text, x0 + amount * per + 5, y + 0.35 * font);
      y += 1.2 * font;
    }
    ctx.restore();
    return { arrows: drawn, legend: k.legend };
  }

  // The rope as drawn in state s of a run (scene.cpp's rope_at), for the page's tests.
  const ropePath = (run, s) => scene(run, s, 0, library.stopHeight(Infinity)).rope;

  window.whatnextMachine = { draw, extent, makeView, toPixel, stateAt, ropePath, colour, useLibrary, arrowColour: kArrowColour };
})();
