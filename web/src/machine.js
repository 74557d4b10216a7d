// The machine drawn to scale on a canvas, with the parts, colours and conventions of the
// animation that `whatnext animate` writes (src/viz/scene.cpp, the scene's geometry): x to the right, h up, metres,
// origin at the seesaw's pivot. A second run can be drawn as a ghost over the first.
(function () {
  'use strict';

  const colour = {
    sandbag: 'rgb(204,127,0)',  // the pixel test looks for this one
    balloon: 'rgb(255,42,51)',
    seesaw: 'rgb(153,85,51)',
    boxWall: 'rgb(153,127,51)',
    boxInside: 'rgb(255,255,204)',
    lid: 'rgb(51,85,153)',
    radio: 'rgb(51,42,102)',
    dial: 'rgb(204,212,255)',
    dark: 'rgb(51,42,51)',
    grey: 'rgb(96,96,96)',
    midGrey: 'rgb(160,160,160)',
    ground: 'rgb(224,224,224)',  // below the built machine's floor (the pixel test looks for it)
    band: 'rgb(236,236,236)',
    eventRed: 'rgb(204,0,0)',
    bagText: 'rgb(153,85,0)',
    ghost: 'rgb(60,90,200)',
  };

  const add = (a, b) => ({ x: a.x + b.x, h: a.h + b.h });
  const sub = (a, b) => ({ x: a.x - b.x, h: a.h - b.h });
  const scale = (k, a) => ({ x: k * a.x, h: k * a.h });
  const norm = (a) => Math.hypot(a.x, a.h);
  const polar = (length, angle) => ({ x: length * Math.cos(angle), h: length * Math.sin(angle) });

  const seesawEnd = (m, phiS) => polar(m.seesaw_right_arm, phiS);
  const lidEdge = (m, phiL) => add(m.hinge, polar(2 * m.lid_half_length, phiL));
  // Where the rope is tied: the lid's free edge unless geometry.rope_on_lid ties it nearer the hinge.
  const ropeKnot = (m, phiL) => add(m.hinge, polar(m.rope_knot, phiL));
  const groundLevel = (m) => m.hinge.h - 2 * m.lid_half_length;
  // Where the model has it (src/viz/scene.cpp's balloon_centre): from the hinge, sideways and up.
  const balloonCentre = (m, s) => ({ x: m.hinge.x + s.balloon_x, h: m.hinge.h + s.balloon_h });

  // The radio stands on the ground under its switch (or hangs below a switch that is lower).
  function radioBox(m) {
    const w = 0.36 * Math.max(0.5, 2 * m.lid_half_length);
    const top = m.radio_switch.h - 0.03;
    const bottom = top - groundLevel(m) > 0.08 ? groundLevel(m) : top - 0.5 * w;
    return { x0: m.radio_switch.x - 0.5 * w, x1: m.radio_switch.x + 0.5 * w, h0: bottom, h1: top };
  }

  // A slack rope or string: a parabola sagging under its chord, as long as the rope.
  function sagCurve(a, b, length, n = 48) {
    const point = (s, d) => add(add(a, scale(s, sub(b, a))), { x: 0, h: -4 * d * s * (1 - s) });
    // The polyline's length, in plain numbers (it is evaluated 60 times a frame).
    const dx = b.x - a.x, dh = b.h - a.h;
    const arc = (d) => {
      let len = 0, ph = 0;
      for (let i = 1; i <= n; ++i) {
        const s = i / n, h = s * dh - 4 * d * s * (1 - s);
        len += Math.hypot(dx / n, h - ph);
        ph = h;
      }
      return len;
    };
    let d = 0;
    if (norm(sub(b, a)) < length - 1e-9) {
      let lo = 0, hi = length;
      for (let it = 0; it < 60; ++it) {
        const mid = 0.5 * (lo + hi);
        if (arc(mid) < length) lo = mid; else hi = mid;
      }
      d = 0.5 * (lo + hi);
    }
    const pts = [];
    for (let i = 0; i <= n; ++i) pts.push(point(i / n, d));
    return pts;
  }

  // Is a point inside the box, under its lid (or under the box's top while the lid is open)?
  function inBox(m, edge, p) {
    const hinge = m.hinge;
    if (p.x <= hinge.x || p.x >= hinge.x + 2 * m.lid_half_length) return false;
    let top = hinge.h;
    if (edge.x > hinge.x + 1e-9 && p.x <= edge.x) {
      top = Math.max(top, hinge.h + (p.x - hinge.x) * (edge.h - hinge.h) / (edge.x - hinge.x));
    }
    return p.h < top;
  }

  // The slack rope from the seesaw's end a to the lid's edge e, as `whatnext animate` draws it
  // (src/viz/scene.cpp): a parabola under its chord, as long as the rope, unless that would
  // hang through the lid into the box. Then the rope lies on the lid from its edge back towards the
  // hinge and hangs from the hinge (or, with less rope to spare, runs straight from the seesaw to
  // a point on the lid).
  function slackRope(m, a, e, length) {
    const pts = sagCurve(a, e, length);
    // The ends are tied to the seesaw and the lid's edge, on the lid's line: only the points between
    // them can hang into the box (an end counted "under the lid" by rounding drew the rope straight).
    if (!pts.slice(1, -1).some((p) => inBox(m, e, p))) return pts;
    const hinge = m.hinge;
    const rest = length - norm(sub(e, hinge));
    if (rest >= norm(sub(a, hinge))) return [...sagCurve(a, hinge, rest), e];
    // |e - p| + |p - a| = length for p between e (too short) and the hinge (too long).
    let lo = 0, hi = 1;
    for (let it = 0; it < 60; ++it) {
      const mid = 0.5 * (lo + hi);
      const p = add(e, scale(mid, sub(hinge, e)));
      if (norm(sub(e, p)) + norm(sub(p, a)) < length) lo = mid; else hi = mid;
    }
    return [a, add(e, scale(lo, sub(hinge, e))), e];
  }

  // The rope let go at the seesaw's end, as `whatnext animate` draws it: hanging from the lid's edge
  // e straight down into the open box; what reaches the floor lies on it, folded between the walls
  // (beside the box it would lie on the ground, away from it).
  function hangingRope(m, e, length) {
    const floor = groundLevel(m);
    const drop = Math.min(Math.max(e.h - floor, 0), length);
    const pts = [e, { x: e.x, h: e.h - drop }];
    let rest = length - drop;
    const x0 = m.hinge.x, x1 = m.hinge.x + 2 * m.lid_half_length;
    if (rest <= 0) return pts;
    if (e.x < x0 || e.x > x1) return [...pts, { x: e.x < x0 ? e.x - rest : e.x + rest, h: floor }];
    let x = e.x;
    for (let right = true; rest > 0; right = !right) {
      const along = Math.min(rest, right ? x1 - x : x - x0);
      x += right ? along : -along;
      rest -= along;
      pts.push({ x, h: floor });
    }
    return pts;
  }

  // A span up to this many rope lengths counts as the rope's length (the taut rope's closure holds
  // it to rounding), as in the animation.
  const kSpanTolerance = 1 + 1e-9;
  const beyondRope = (m, phiS, phiL) => norm(sub(seesawEnd(m, phiS), ropeKnot(m, phiL))) > kSpanTolerance * m.rope_length;

  // With the radio the rope is let go for good at lid_open (the latch): when that is, and the first
  // sample after it with the seesaw's end farther from the lid's edge than the rope is long (a heavy
  // seesaw swings on); Infinity for none. Worked out once for each run.
  const releases = new WeakMap();
  function release(run) {
    let r = releases.get(run);
    if (r) return r;
    const m = run.machine, s = run.samples;
    const latch = m.radio ? run.events.find((e) => e.type === 'lid_open') : undefined;
    r = { latch: latch ? latch.t : Infinity, off: Infinity };
    for (let i = 0; i < s.t.length; ++i) {
      if (s.t[i] >= r.latch && beyondRope(m, s.phi_s[i], s.phi_l[i])) { r.off = s.t[i]; break; }
    }
    releases.set(run, r);
    return r;
  }

  // The rope as drawn in state s of a run (src/viz/scene.cpp's rope_path): straight when taut,
  // else slack. Before the latch the model keeps its ends within the rope's length. After it, once
  // the seesaw's end has been farther from the lid's edge than the rope reaches, the rope is off the
  // seesaw for good and hangs from the lid's edge; within the tolerance it is straight, a hair short
  // of the seesaw's end: never longer than the rope.
  function ropePath(run, s) {
    const m = run.machine, length = m.rope_length;
    const a = seesawEnd(m, s.phi_s), b = ropeKnot(m, s.phi_l);
    if (s.rope_taut) return [a, b];
    const r = release(run);
    if (s.t < r.latch) return slackRope(m, a, b, length);
    if (s.t >= r.off || beyondRope(m, s.phi_s, s.phi_l)) return hangingRope(m, b, length);
    const span = norm(sub(a, b));
    if (span > length) return [add(b, scale(length / span, sub(a, b))), b];
    return slackRope(m, a, b, length);
  }

  // The balloon's string from the balloon's skin to the radio's switch; while the balloon is in
  // the box it runs over the box's far wall and hangs from there.
  function stringPath(m, balloon) {
    const corner = { x: m.hinge.x + 2 * m.lid_half_length, h: m.hinge.h };
    const overWall = balloon.h < corner.h && m.radio_switch.x > corner.x;
    const target = overWall ? corner : m.radio_switch;
    const dir = sub(target, balloon);
    const dist = norm(dir);
    const knot = dist > 0 ? add(balloon, scale(m.balloon_radius / dist, dir)) : balloon;
    const length = Math.max(0, m.string_length - m.balloon_radius);
    if (!overWall) return sagCurve(knot, m.radio_switch, length);
    const rest = Math.max(0, length - norm(sub(corner, knot)));
    return [knot, ...sagCurve(corner, m.radio_switch, rest)];
  }

  function landingDistance(m) {
    return Math.abs(m.start.sandbag_x) / Math.max(0.2, Math.cos(m.start.seesaw_angle));
  }

  // Left arm as drawn: a finite arm as it is; the paper's endless arm long enough to hold the
  // sandbag, and before the landing long enough to catch it.
  function drawnArm(m, endless, s) {
    if (Number.isFinite(m.seesaw_left_arm)) return m.seesaw_left_arm;
    return s.on_seesaw ? Math.max(endless, s.r + 0.1) : endless;
  }

  // The state at time t: continuous quantities interpolated between the recorded states around
  // t, the contacts and the mode from the last recorded state at or before t (after an event at t).
  const kContinuous = ['x', 'h', 'r', 'phi_s', 'phi_l', 'balloon_h', 'balloon_x', 'tension', 'energy'];
  const kDiscrete = ['on_seesaw', 'rope_taut', 'mode', 'lid_resting', 'balloon_stuck'];
  function stateAt(samples, t) {
    const ts = samples.t;
    let lo = 0, hi = ts.length;  // first index with ts[i] > t
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (ts[mid] <= t) lo = mid + 1; else hi = mid;
    }
    const i = Math.max(0, lo - 1), j = lo;
    const s = { t };
    const w = j < ts.length && ts[j] > ts[i] && t > ts[i] ? (t - ts[i]) / (ts[j] - ts[i]) : 0;
    for (const k of kContinuous) s[k] = w > 0 ? samples[k][i] + (samples[k][j] - samples[k][i]) * w : samples[k][i];
    for (const k of kDiscrete) s[k] = samples[k][i];
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
    const m = run.machine, s = run.samples;
    const leftArm = Math.max(m.seesaw_right_arm, 1.2 * landingDistance(m));
    const reach = reachOf(m);
    const box = { x0: Infinity, x1: -Infinity, h0: Infinity, h1: -Infinity, leftArm };
    const put = (p) => {
      if (!Number.isFinite(p.x) || !Number.isFinite(p.h)) return;
      box.x0 = Math.min(box.x0, p.x); box.x1 = Math.max(box.x1, p.x);
      box.h0 = Math.min(box.h0, p.h); box.h1 = Math.max(box.h1, p.h);
    };
    const g = groundLevel(m), rl = m.lid_half_length;
    put({ x: 0, h: 0 }); put({ x: -0.15, h: g }); put({ x: 0.15, h: g });
    put({ x: m.hinge.x - 0.05, h: g }); put({ x: m.hinge.x + 2 * rl + 0.05, h: m.hinge.h });
    put(add(m.hinge, { x: 0, h: 2 * rl }));
    const radio = radioBox(m);
    put({ x: radio.x0 - 0.05, h: radio.h0 }); put({ x: radio.x1 + 0.05, h: radio.h1 + 0.05 });
    if (run.events.some((e) => e.type === 'radio_on')) put({ x: radio.x1, h: radio.h1 + 0.25 });  // the notes
    const n = s.t.length, every = Math.max(1, Math.floor(n / 4000));
    for (let i = 0; i < n; i += (s.event[i] >= 0 ? 1 : every)) {
      const phiS = s.phi_s[i];
      put(seesawEnd(m, phiS));
      put(lidEdge(m, s.phi_l[i]));
      // Below the floor the left arm and the sandbag have left the machine (the model has no floor
      // for them): they leave the picture there.
      const shown = Math.min(drawnArm(m, leftArm, { on_seesaw: s.on_seesaw[i], r: s.r[i] }), reach);
      const armEnd = polar(-shown, phiS);
      put({ x: armEnd.x, h: Math.max(armEnd.h, g) });
      if (Math.hypot(s.x[i], s.h[i]) <= reach) put({ x: s.x[i], h: Math.max(s.h[i], g) });
      const c = balloonCentre(m, { balloon_h: s.balloon_h[i], balloon_x: s.balloon_x[i] });
      if (c.h - m.hinge.h <= reach) {
        put(add(c, { x: m.balloon_radius, h: m.balloon_radius }));
        put(sub(c, { x: m.balloon_radius, h: m.balloon_radius }));
      }
    }
    if (m.radio) {
      for (const i of [0, n - 1]) {
        for (const p of stringPath(m, balloonCentre(m, { balloon_h: s.balloon_h[i], balloon_x: s.balloon_x[i] }))) {
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
  function drawStill(ctx, v, m, radioOn, radioPlaying) {
    const p = painter(ctx, v);
    const g = groundLevel(m), rl = m.lid_half_length, radio = radioBox(m);
    if (m.floor) {
      const y = toPixel(v, { x: 0, h: g }).y;
      ctx.fillStyle = colour.ground;
      ctx.fillRect(0, y, v.width, v.height - y);
    }
    ctx.strokeStyle = colour.midGrey;
    p.width(0.01, 2);
    const pieces = m.floor ? [[(0 - v.ox) / v.scale, (v.width - v.ox) / v.scale]]
      : [[-0.15, 0.15], [m.hinge.x - 0.05, m.hinge.x + 2 * rl + 0.05], [radio.x0 - 0.05, radio.x1 + 0.05]];
    for (const [a, b] of pieces) p.line([{ x: a, h: g }, { x: b, h: g }]);
    ctx.fillStyle = colour.grey;
    ctx.beginPath();
    for (const q of [{ x: 0, h: 0 }, { x: -0.07, h: g }, { x: 0.07, h: g }].map((w) => toPixel(v, w))) ctx.lineTo(q.x, q.y);
    ctx.closePath();
    ctx.fill();
    ctx.fillStyle = colour.boxInside;
    p.rect(m.hinge.x, g, m.hinge.x + 2 * rl, m.hinge.h);

    ctx.save();
    if (!radioOn) ctx.globalAlpha = 0.3;  // Kermit's radio, not part of this run
    ctx.fillStyle = colour.radio;
    p.rect(radio.x0, radio.h0, radio.x1, radio.h1);
    ctx.fillStyle = colour.dial;
    const w = radio.x1 - radio.x0, hgt = radio.h1 - radio.h0;
    p.circle({ x: 0.5 * (radio.x0 + radio.x1), h: 0.5 * (radio.h0 + radio.h1) }, 0.3 * w * v.scale * Math.min(1, hgt / w));
    ctx.fill();
    ctx.strokeStyle = colour.dark;
    p.width(0.012, 2);
    p.line([{ x: m.radio_switch.x, h: radio.h1 }, m.radio_switch]);
    if (radioPlaying) {  // notes above the radio, where extent keeps room, as in the animation
      ctx.fillStyle = colour.radio;
      ctx.font = `bold ${Math.max(12, 0.12 * v.scale)}px sans-serif`;
      ctx.textAlign = 'center';
      const q = toPixel(v, { x: 0.5 * (radio.x0 + radio.x1), h: radio.h1 + 0.08 });
      ctx.fillText('\u266A \u266B', q.x, q.y);
    }
    ctx.restore();
  }

  function drawWalls(ctx, v, m) {
    const p = painter(ctx, v), g = groundLevel(m), rl = m.lid_half_length;
    ctx.strokeStyle = colour.boxWall;
    p.width(0.02, 3);
    p.line([m.hinge, { x: m.hinge.x, h: g }, { x: m.hinge.x + 2 * rl, h: g }, { x: m.hinge.x + 2 * rl, h: m.hinge.h }]);
  }

  function drawBalloon(ctx, v, m, s, ghost, radioOn) {
    const p = painter(ctx, v), c = balloonCentre(m, s);
    if (radioOn || !ghost) {
      ctx.save();
      if (!radioOn) ctx.globalAlpha = 0.3;
      ctx.strokeStyle = ghost ? colour.ghost : colour.grey;
      ctx.lineWidth = 1.5;
      p.line(stringPath(m, c));
      ctx.restore();
    }
    p.circle(c, m.balloon_radius * v.scale);
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

  // How high the end stop stands above the arm [m]: above the sandbag drawn at the arm's end (its
  // radius is 0.05 m), so that both show (src/viz/scene.cpp has it so too).
  const kStopHeight = 0.08;

  // Lid, seesaw, rope and sandbag. Returns where the sandbag is on the canvas. The built machine
  // stands on its floor: nothing of these is drawn below it (a sandbag lying there, a point in
  // the model, is half a disc; the seesaw's end resting there a cut bar).
  function drawMoving(ctx, v, run, s, ghost) {
    const m = run.machine, p = painter(ctx, v);
    ctx.save();
    if (m.floor) {
      ctx.beginPath();
      ctx.rect(0, 0, v.width, toPixel(v, { x: 0, h: groundLevel(m) }).y);
      ctx.clip();
    }
    ctx.lineCap = 'round';
    ctx.lineJoin = 'round';
    ctx.strokeStyle = ghost ? colour.ghost : colour.lid;
    p.width(0.025, 3);
    p.line([m.hinge, lidEdge(m, s.phi_l)]);
    if (!ghost) {
      ctx.fillStyle = 'black';
      p.circle(m.hinge, Math.max(2, 0.012 * v.scale));
      ctx.fill();
    }
    const arm = drawnArm(m, v.leftArm, s);
    ctx.strokeStyle = ghost ? colour.ghost : colour.seesaw;
    p.width(0.03, 4);
    p.line([polar(-arm, s.phi_s), seesawEnd(m, s.phi_s)]);
    if (m.end_stop) {  // the end stop: an edge standing up from the left arm's end, as in the animation
      const end = polar(-arm, s.phi_s);
      p.line([end, add(end, polar(Math.max(kStopHeight, 10 / v.scale), s.phi_s + Math.PI / 2))]);
    }
    if (!ghost) {
      ctx.fillStyle = 'black';
      p.circle({ x: 0, h: 0 }, Math.max(2.5, 0.015 * v.scale));
      ctx.fill();
    }
    // The rope: straight when taut; slack, sagging or lying on the lid; let go, hanging from the lid.
    ctx.strokeStyle = ghost ? colour.ghost : colour.dark;
    ctx.lineWidth = Math.max(1.5, 0.008 * v.scale);
    if (ghost) ctx.setLineDash([6, 4]);
    p.line(ropePath(run, s));
    ctx.setLineDash([]);
    // The sandbag, centred on the simulated point.
    const bag = toPixel(v, { x: s.x, h: s.h });
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
    ctx.save();
    ctx.fillStyle = 'white';
    ctx.fillRect(0, 0, v.width, v.height);
    ctx.beginPath();
    ctx.rect(0, v.top, v.width, v.height - v.top);
    ctx.clip();
    const radioPlaying = run.radioOnAt !== null && s.t >= run.radioOnAt;
    drawStill(ctx, v, m, m.radio, radioPlaying);
    for (const g of ghosts) inColour(g, () => drawBalloon(ctx, v, g.run.machine, g.state, true, g.run.machine.radio));
    drawBalloon(ctx, v, m, s, false, m.radio);
    drawWalls(ctx, v, m);
    for (const g of ghosts) {
      ctx.save();
      ctx.globalAlpha = 0.6;
      inColour(g, () => drawMoving(ctx, v, g.run, g.state, true));
      ctx.restore();
    }
    const bag = drawMoving(ctx, v, run, s, false);
    ctx.restore();
    // The sandbag and the balloon beyond the picture: an arrow at its edge, the distance in the
    // caption.
    const inPicture = (q, r) => q.x >= -r && q.x <= v.width + r && q.y >= v.top - r && q.y <= v.height + r;
    const visible = inPicture(bag, bag.radius);
    const arrow = Math.max(10, 0.7 * font);
    if (!visible) drawFar(ctx, v, { x: 0, h: 0 }, { x: s.x, h: s.h }, colour.sandbag, arrow);
    const balloon = balloonCentre(m, s), boxTop = { x: balloon.x, h: m.hinge.h };
    const balloonVisible = inPicture(toPixel(v, balloon), m.balloon_radius * v.scale);
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
    return { ...bag, far: far.join(' · ') };
  }

  window.whatnextMachine = { draw, extent, makeView, toPixel, stateAt, ropePath, colour };
})();
