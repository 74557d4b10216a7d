// The animation's view: the world-to-pixel mapping that frames the machine over the whole run.
#include <algorithm>
#include <cmath>
#include <limits>

#include "scene.hpp"
#include "whatnext/viz/animation.hpp"

namespace whatnext::viz {

namespace {

using scene::balloon_centre;
using scene::radio_box;
using scene::RadioBox;
using scene::string_path;

// Distance from the pivot beyond which the view no longer follows the sandbag.
double follow_radius(const Recording& rec, double left_arm) {
  const Machine& m = rec.scenario.machine;
  return 2.2 * std::max({m.seesaw_right_arm, left_arm, norm(m.hinge) + 2.0 * m.lid_half_length});
}

struct Bounds {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, h0 = x0, h1 = -x0;
  void add(Vec2 p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.h)) return;
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), h0 = std::min(h0, p.h), h1 = std::max(h1, p.h);
  }
};

// The machine's parts that never move, and room for the notes of a radio that comes on.
void add_still(Bounds& box, const Recording& rec) {
  const Machine& m = rec.scenario.machine;
  const double g = m.floor_height(), rl = m.lid_half_length;
  box.add({0.0, 0.0});
  box.add({-0.15, g});
  box.add({0.15, g});
  box.add({m.hinge.x - 0.05, g});
  box.add({m.hinge.x + 2.0 * rl + 0.05, m.hinge.h});
  box.add(m.hinge + Vec2{0.0, 2.0 * rl});
  const RadioBox radio = radio_box(m);
  box.add({radio.x0 - 0.05, radio.h0});
  box.add({radio.x1 + 0.05, radio.h1 + 0.05});
  if (rec.result.outcome().type == EventType::radio_on) box.add({radio.x1, radio.h1 + 0.25});  // notes
}

// The moving parts over the whole run, and the sandbag while it falls onto the arm or stays on the
// part of the arm drawn at its shortest (left_arm); the balloon as far as `follow` above the box.
void add_run(Bounds& box, const Recording& rec, double left_arm, double follow) {
  const Machine& m = rec.scenario.machine;
  const RopeGeometry geo(m);
  bool landed = false;
  const double bag = scene::kSandbagRadius;
  for (const Snapshot& s : rec.states) {
    box.add(geo.seesaw_end(s.phi_s));
    box.add(geo.lid_edge(s.phi_l));                              // the rope's knot
    box.add(m.hinge + polar(2.0 * m.lid_half_length, s.phi_l));  // the lid's free edge
    box.add(polar(-left_arm, s.phi_s));
    landed = landed || s.on_seesaw;
    if (!landed || std::hypot(s.x, s.h) <= left_arm) {
      box.add({s.x - bag, s.h - bag});
      box.add({s.x + bag, s.h + bag});
    }
    const Vec2 c = balloon_centre(m, s);
    if (c.h - m.hinge.h <= follow) {
      box.add(c + Vec2{m.balloon_radius, m.balloon_radius});
      box.add(c - Vec2{m.balloon_radius, m.balloon_radius});
    }
  }
  for (const Snapshot* s : {&rec.states.front(), &rec.states.back()}) {
    for (Vec2 p : string_path(m, balloon_centre(m, *s))) box.add(p);
  }
}

// Text above, the time bar with its event names below, the machine (box) in between, centred at
// the largest scale that fits; height 0: as high as the machine needs at this width.
void fit(View& v, const Bounds& box, int width, int height) {
  v.font = std::clamp(height > 0 ? std::min(width / 40.0, height / 30.0) : width / 40.0, 9.0, 22.0);
  v.top = static_cast<int>(std::lround(2.7 * v.font));
  const int below = static_cast<int>(std::lround(3.3 * v.font));
  if (height <= 0) {
    const double needed = (box.h1 - box.h0) * width / (box.x1 - box.x0);
    height = static_cast<int>(std::lround(v.top + needed + below));
    height = std::clamp(height, static_cast<int>(0.45 * width), static_cast<int>(1.25 * width));
    height += height % 2;  // even, as H.264 wants
  }
  v.height = height;
  v.bottom = height - below;
  const double area_w = width, area_h = v.bottom - v.top;
  v.scale = std::min(area_w / (box.x1 - box.x0), area_h / (box.h1 - box.h0));
  v.origin_x = 0.5 * area_w - 0.5 * (box.x0 + box.x1) * v.scale;
  v.origin_y = v.top + 0.5 * area_h + 0.5 * (box.h0 + box.h1) * v.scale;
}

}  // namespace

Pixel to_pixel(const View& v, Vec2 p) { return {v.origin_x + p.x * v.scale, v.origin_y - p.h * v.scale}; }

View make_view(const Recording& rec, int width, int height) {
  View v;
  v.width = width;
  v.left_arm = scene::endless_arm(rec.scenario);
  Bounds box;
  add_still(box, rec);
  add_run(box, rec, v.left_arm, follow_radius(rec, v.left_arm));
  const double pad = 0.04 * std::max(box.x1 - box.x0, box.h1 - box.h0);
  box.x0 -= pad, box.x1 += pad, box.h0 -= pad, box.h1 += pad;
  fit(v, box, width, height);
  return v;
}

}  // namespace whatnext::viz
