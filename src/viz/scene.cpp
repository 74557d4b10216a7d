// The scene's geometry: where each part of the machine is drawn (scene.hpp). Pure geometry in
// metres, shared by the animation's view and its frames.
#include "scene.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "whatnext/events.hpp"
#include "whatnext/units.hpp"
#include "whatnext/viz/animation.hpp"

namespace whatnext::viz::scene {

// ---- the slack rope and string: a parabola sagging under its chord, as long as the rope ----
std::vector<Vec2> sag_curve(Vec2 a, Vec2 b, double length, int n) {
  std::vector<Vec2> pts;
  const double chord = norm(b - a);
  auto point = [&](double s, double d) { return a + s * (b - a) + Vec2{0.0, -4.0 * d * s * (1.0 - s)}; };
  auto arc = [&](double d) {
    double len = 0.0;
    Vec2 prev = a;
    for (int i = 1; i <= n; ++i) {
      const Vec2 p = point(static_cast<double>(i) / n, d);
      len += norm(p - prev);
      prev = p;
    }
    return len;
  };
  double d = 0.0;
  if (chord < length - 1e-9) {
    double lo = 0.0, hi = length;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (arc(mid) < length ? lo : hi) = mid;
    }
    d = 0.5 * (lo + hi);
  }
  for (int i = 0; i <= n; ++i) pts.push_back(point(static_cast<double>(i) / n, d));
  return pts;
}

namespace {
// Is a point inside the box, under its lid (or under the box's top while the lid is open)?
bool in_box(const Machine& m, Vec2 lid_edge, Vec2 p) {
  const Vec2 hinge = m.hinge;
  if (p.x <= hinge.x || p.x >= hinge.x + 2.0 * m.lid_half_length) return false;
  double top = hinge.h;
  if (lid_edge.x > hinge.x + 1e-9 && p.x <= lid_edge.x) {
    top = std::max(top, hinge.h + (p.x - hinge.x) * (lid_edge.h - hinge.h) / (lid_edge.x - hinge.x));
  }
  return p.h < top;
}
}  // namespace

// The slack rope from the seesaw's end a to the lid's edge e, as long as the rope: a parabola under
// its chord, unless that would hang through the lid into the box. Then the rope lies on the lid
// from its edge back towards the hinge and hangs from the hinge (or, with less rope to spare, runs
// straight from the seesaw to a point on the lid).
std::vector<Vec2> slack_rope(const Machine& m, Vec2 a, Vec2 e, double length) {
  std::vector<Vec2> pts = sag_curve(a, e, length);
  // The ends are tied to the seesaw and to the lid's edge, which lies on the lid's line: only the
  // points between them can hang into the box (an end counted "under the lid" by a rounding error
  // drew the slack rope straight and along the open lid).
  if (std::none_of(pts.begin() + 1, pts.end() - 1, [&](Vec2 p) { return in_box(m, e, p); })) return pts;
  const Vec2 hinge = m.hinge;
  const double rest = length - norm(e - hinge);
  if (rest >= norm(a - hinge)) {
    pts = sag_curve(a, hinge, rest);
    pts.push_back(e);
    return pts;
  }
  // |e - p| + |p - a| = length for p between e (too short) and the hinge (too long).
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    const Vec2 p = e + mid * (hinge - e);
    (norm(e - p) + norm(p - a) < length ? lo : hi) = mid;
  }
  return {a, e + lo * (hinge - e), e};
}

// The balloon's string from its knot to the radio switch. While the knot is inside the box the
// string runs over the box's far wall and hangs from there with what is left of it.
// The string's length counts from the balloon's centre (as the radio's switch condition does), so
// it is drawn from the point of the balloon's skin that faces where it goes, with r_B less.
std::vector<Vec2> string_path(const Machine& m, Vec2 balloon) {
  const Vec2 corner{m.hinge.x + 2.0 * m.lid_half_length, m.hinge.h};
  const bool over_wall = balloon.h < corner.h && m.radio_switch.x > corner.x;
  const Vec2 target = over_wall ? corner : m.radio_switch;
  const Vec2 dir = target - balloon;
  const double dist = norm(dir);
  const Vec2 knot = dist > 0.0 ? balloon + (m.balloon_radius / dist) * dir : balloon;
  const double length = std::max(0.0, m.string_length - m.balloon_radius);
  if (!over_wall) return sag_curve(knot, m.radio_switch, length);
  std::vector<Vec2> pts{knot};
  const double rest = std::max(0.0, length - norm(corner - knot));
  for (Vec2 p : sag_curve(corner, m.radio_switch, rest)) pts.push_back(p);
  return pts;
}

double landing_distance(const Scenario& sc) {
  return std::fabs(sc.start.sandbag_x) / std::max(0.2, std::cos(sc.start.seesaw_angle));
}

// Where the model has it: the box's centre for the paper's balloon, anywhere in the plane for one
// smaller than the box (docs/extensions.md "A balloon smaller than the box").
Vec2 balloon_centre(const Machine& m, const Snapshot& s) {
  return {m.hinge.x + s.balloon_x, m.hinge.h + s.balloon_h};
}

Vec2 seesaw_end(const Machine& m, double phi_s) { return RopeGeometry(m).seesaw_end(phi_s); }
Vec2 lid_end(const Machine& m, double phi_l) { return m.hinge + polar(2.0 * m.lid_half_length, phi_l); }

// The rope let go at the seesaw's end: hanging from the lid's edge e straight down into the open
// box (the radio's latch holds the lid short of 90 deg, so e is above the box); what reaches the
// floor lies on it, folded between the walls. Beside the box it would lie on the ground, away from it.
std::vector<Vec2> hanging_rope(const Machine& m, Vec2 e, double length) {
  const double floor = m.floor_height();
  const double drop = std::clamp(e.h - floor, 0.0, length);
  std::vector<Vec2> pts{e, {e.x, e.h - drop}};
  double rest = length - drop;
  const double x0 = m.hinge.x, x1 = m.hinge.x + 2.0 * m.lid_half_length;
  if (rest <= 0.0) return pts;
  if (e.x < x0 || e.x > x1) {
    pts.push_back({e.x < x0 ? e.x - rest : e.x + rest, floor});
    return pts;
  }
  double x = e.x;
  for (bool right = true; rest > 0.0; right = !right) {
    const double along = std::min(rest, right ? x1 - x : x - x0);
    x += right ? along : -along;
    rest -= along;
    pts.push_back({x, floor});
  }
  return pts;
}

RadioBox radio_box(const Machine& m) {
  const double w = 0.36 * std::max(0.5, 2.0 * m.lid_half_length);
  const double g = m.floor_height();
  const double top = m.radio_switch.h - 0.03;
  const double bottom = top - g > 0.08 ? g : top - 0.25 * w * 2.0;
  return {m.radio_switch.x - 0.5 * w, m.radio_switch.x + 0.5 * w, bottom, top};
}

double endless_arm(const Scenario& sc) {
  return std::max(sc.machine.seesaw_right_arm, 1.2 * landing_distance(sc));
}

double drawn_arm(double left_arm, double endless, double farthest) {
  return std::isfinite(left_arm) ? left_arm : std::max(endless, farthest + 0.1);
}

double drawn_arm(const Recording& rec, double endless, double t) {
  double far = 0.0;
  for (std::size_t i = 0; i < rec.states.size() && rec.states[i].t <= t; ++i) {
    if (rec.states[i].on_seesaw) far = std::max(far, rec.states[i].r);
  }
  return drawn_arm(rec.scenario.machine.seesaw_left_arm, endless, far);
}

double stop_height(double scale) { return std::max(0.08, 10.0 / scale); }

Release release_of(const Recording& rec) {
  Release r;
  if (!rec.scenario.machine.radio) return r;
  for (const Event& e : rec.result.events) {
    if (e.type == EventType::lid_open) {
      r.latch = e.t;
      break;
    }
  }
  // Once pulled off the seesaw's end the rope stays off, even where a seesaw swinging back
  // brings its end near enough again.
  const RopeGeometry geo(rec.scenario.machine);
  for (auto it = std::lower_bound(rec.states.begin(), rec.states.end(), r.latch,
                                  [](const Snapshot&q, double t) { return q.t < t; });
       it != rec.states.end(); ++it) {
    if (beyond_rope(geo, *it)) {
      r.off = it->t;
      break;
    }
  }
  return r;
}

bool beyond_rope(const RopeGeometry& geo, const Snapshot& s) {
  return geo.span(s.phi_s, s.phi_l) > kSpanTolerance * geo.rope_length();
}

StillParts still_parts(const Machine& m) {
  StillParts p;
  const double g = m.floor_height(), rl = m.lid_half_length;
  const Vec2 hinge = m.hinge;
  const RadioBox radio = radio_box(m);
  p.ground = g;
  p.floor = m.floor;
  // The paper's model has no floor but under the pivot's stand, the box and the radio (the
  // sandbag's arm is endless and may dip below them).
  p.floor_pieces = {std::pair{-0.15, 0.15}, std::pair{hinge.x - 0.05, hinge.x + 2 * rl + 0.05},
                    std::pair{radio.x0 - 0.05, radio.x1 + 0.05}};
  p.stand = {Vec2{0.0, 0.0}, Vec2{-0.07, g}, Vec2{0.07, g}};
  p.box_corner = hinge;
  p.box_side = 2 * rl;
  p.walls = {hinge, Vec2{hinge.x, g}, Vec2{hinge.x + 2 * rl, g}, Vec2{hinge.x + 2 * rl, hinge.h}};
  p.radio = radio;
  p.dial = {0.5 * (radio.x0 + radio.x1), 0.5 * (radio.h0 + radio.h1)};
  p.dial_radius = 0.3 * (radio.x1 - radio.x0);
  p.dial_squash = std::min(1.0, (radio.h1 - radio.h0) / (radio.x1 - radio.x0));
  p.radio_post = {Vec2{m.radio_switch.x, radio.h1}, m.radio_switch};
  p.notes = {0.5 * (radio.x0 + radio.x1), radio.h1 + 0.08};
  return p;
}

MovingParts moving_parts(const Machine& m, const Snapshot& s, const Release& release, double arm,
                         double stop_height) {
  MovingParts p;
  p.hinge = m.hinge;
  p.lid_end = lid_end(m, s.phi_l);
  p.arm_left = polar(-arm, s.phi_s);
  p.arm_right = seesaw_end(m, s.phi_s);
  p.end_stop = m.end_stop;
  p.stop_top = p.arm_left + polar(stop_height, s.phi_s + 0.5 * units::kPi);
  p.rope = rope_at(m, s, release);
  p.sandbag = {s.x, s.h};
  p.balloon = balloon_centre(m, s);
  p.balloon_radius = m.balloon_radius;
  p.string = string_path(m, p.balloon);
  return p;
}

std::vector<Vec2> rope_at(const Machine& m, const Snapshot& s, const Release& release) {
  const RopeGeometry geo(m);
  const Vec2 r = geo.seesaw_end(s.phi_s), e = geo.lid_edge(s.phi_l);
  if (s.rope_taut) return {r, e};
  // Before the latch the model keeps the span within the rope's length (to its tolerance; a frame
  // between two recorded taut states, its angles interpolated, has the ends up to 3e-5 m too far
  // apart in example 3, a hundredth of a pixel): the slack rope sags, or is straight at full stretch.
  if (s.t < release.latch) return slack_rope(m, r, e, m.rope_length);
  // After it nothing holds the rope: off the seesaw's end since release.off, or now.
  if (s.t >= release.off || beyond_rope(geo, s)) return hanging_rope(m, e, m.rope_length);
  // Within the tolerance of the rope's length: straight, and a hair short of the seesaw's end.
  const double span = norm(r - e);
  if (span > m.rope_length) return {e + (m.rope_length / span) * (r - e), e};
  return slack_rope(m, r, e, m.rope_length);
}

}  // namespace whatnext::viz::scene

namespace whatnext::viz {

std::vector<Vec2> rope_path(const Recording& rec, const Snapshot& s) {
  return scene::rope_at(rec.scenario.machine, s, scene::release_of(rec));
}

}  // namespace whatnext::viz
