// The machine's parts drawn with Cairo from the scene's geometry (scene.hpp): colours, line widths
// and the smallest sizes in pixels live here, where each part is lives in the scene.
#include <algorithm>
#include <cmath>
#include <limits>

#include "draw_frame.hpp"
#include "whatnext/units.hpp"

namespace whatnext::viz::draw {

void Pen::move(Vec2 p) const {
  const Pixel q = px(p);
  cairo_move_to(cr, q.x, q.y);
}
void Pen::line(Vec2 p) const {
  const Pixel q = px(p);
  cairo_line_to(cr, q.x, q.y);
}
void Pen::width_m(double metres, double min_px) const {
  cairo_set_line_width(cr, std::max(min_px, metres * v.scale));
}
void Pen::polyline(const std::vector<Vec2>& pts) const {
  move(pts.front());
  for (std::size_t i = 1; i < pts.size(); ++i) line(pts[i]);
}
void Pen::circle(Vec2 c, double radius_px) const {
  const Pixel q = px(c);
  cairo_new_sub_path(cr);
  cairo_arc(cr, q.x, q.y, radius_px, 0.0, 2.0 * units::kPi);
}

// The paper's model has no floor but pieces of it under the pivot's stand, the box and the radio
// (the sandbag's arm is endless and may dip below them); the built machine's floor (floor.enabled)
// runs across the picture, with the ground below it.
void floor(const Pen& pen, const scene::StillParts& still) {
  cairo_t* cr = pen.cr;
  const View& v = pen.v;
  set(cr, kMidGrey);
  pen.width_m(0.01, 2.0);
  if (still.floor) {
    const Pixel q = pen.px({0.0, still.ground});
    set(cr, kLightGrey);
    cairo_rectangle(cr, 0, q.y, v.width, v.bottom - q.y);
    cairo_fill(cr);
    set(cr, kMidGrey);
    cairo_move_to(cr, 0, q.y);
    cairo_line_to(cr, v.width, q.y);
    cairo_stroke(cr);
    return;
  }
  for (auto [a, b] : still.floor_pieces) {
    pen.move({a, still.ground});
    pen.line({b, still.ground});
    cairo_stroke(cr);
  }
}

void stand(const Pen& pen, const scene::StillParts& still) {
  set(pen.cr, kGrey);
  pen.move(still.stand[0]);
  pen.line(still.stand[1]);
  pen.line(still.stand[2]);
  cairo_close_path(pen.cr);
  cairo_fill(pen.cr);
}

void box_inside(const Pen& pen, const scene::StillParts& still) {
  set(pen.cr, kBoxInside);
  const Pixel corner = pen.px(still.box_corner);
  cairo_rectangle(pen.cr, corner.x, corner.y, still.box_side * pen.v.scale, still.box_side * pen.v.scale);
  cairo_fill(pen.cr);
}

void balloon(const Pen& pen, const scene::MovingParts& moving) {
  set(pen.cr, kGrey);
  cairo_set_line_width(pen.cr, 1.5);
  pen.polyline(moving.string);
  cairo_stroke(pen.cr);
  set(pen.cr, kBalloonColour);
  pen.circle(moving.balloon, moving.balloon_radius * pen.v.scale);
  cairo_fill(pen.cr);
}

void walls(const Pen& pen, const scene::StillParts& still) {
  set(pen.cr, kBoxWall);
  pen.width_m(0.02, 3.0);
  pen.move(still.walls[0]);
  for (std::size_t i = 1; i < still.walls.size(); ++i) pen.line(still.walls[i]);
  cairo_stroke(pen.cr);
}

// The radio with its switch, where the balloon's string is tied.
void radio(const Pen& pen, const scene::StillParts& still) {
  cairo_t* cr = pen.cr;
  const scene::RadioBox& radio = still.radio;
  set(cr, kRadio);
  const Pixel corner = pen.px({radio.x0, radio.h1});
  cairo_rectangle(cr, corner.x, corner.y, (radio.x1 - radio.x0) * pen.v.scale,
                  (radio.h1 - radio.h0) * pen.v.scale);
  cairo_fill(cr);
  set(cr, kDial);
  pen.circle(still.dial, still.dial_radius * pen.v.scale * still.dial_squash);
  cairo_fill(cr);
  set(cr, kDark);
  pen.width_m(0.012, 2.0);
  pen.move(still.radio_post[0]);
  pen.line(still.radio_post[1]);
  cairo_stroke(cr);
}

// Notes rising from the radio once it is on (above it, where make_view keeps room). Leaves the
// bold font selected (render_frame draws it inside a saved state).
void notes(const Pen& pen, const scene::StillParts& still) {
  cairo_t* cr = pen.cr;
  set(cr, kRadio);
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
  cairo_set_font_size(cr, std::max(10.0, 0.12 * pen.v.scale));
  cairo_text_extents_t ext;
  cairo_text_extents(cr, "\u266A \u266B", &ext);
  const Pixel q = pen.px(still.notes);
  cairo_move_to(cr, q.x - 0.5 * ext.x_advance, q.y);
  cairo_show_text(cr, "\u266A \u266B");
}

// The lid on its hinge: the whole lid (the rope is tied at its knot).
void lid(const Pen& pen, const scene::MovingParts& moving) {
  set(pen.cr, kLid);
  pen.width_m(0.025, 3.0);
  pen.move(moving.hinge);
  pen.line(moving.lid_end);
  cairo_stroke(pen.cr);
  set(pen.cr, kBlack);
  pen.circle(moving.hinge, std::max(2.0, 0.012 * pen.v.scale));
  cairo_fill(pen.cr);
}

// The seesaw on its pivot, with the end stop standing up from the left arm's end if there is one.
void seesaw(const Pen& pen, const scene::MovingParts& moving) {
  set(pen.cr, kSeesaw);
  pen.width_m(0.03, 4.0);
  pen.move(moving.arm_left);
  pen.line(moving.arm_right);
  if (moving.end_stop) {
    pen.move(moving.arm_left);
    pen.line(moving.stop_top);
  }
  cairo_stroke(pen.cr);
  set(pen.cr, kBlack);
  pen.circle({0.0, 0.0}, std::max(2.5, 0.015 * pen.v.scale));
  cairo_fill(pen.cr);
}

// The rope: straight when taut; slack, sagging or lying on the lid; let go, hanging from the lid.
void rope(const Pen& pen, const scene::MovingParts& moving) {
  set(pen.cr, kDark);
  cairo_set_line_width(pen.cr, std::max(1.5, 0.008 * pen.v.scale));
  pen.polyline(moving.rope);
  cairo_stroke(pen.cr);
}

// The sandbag, centred on the simulated point.
bool sandbag(const Pen& pen, const scene::MovingParts& moving, Pixel& at) {
  const View& v = pen.v;
  const Pixel bag = pen.px(moving.sandbag);
  at = bag;
  const double bag_r = std::max(6.0, scene::kSandbagRadius * v.scale);
  const bool visible =
      bag.x >= -bag_r && bag.x <= v.width + bag_r && bag.y >= v.top - bag_r && bag.y <= v.bottom + bag_r;
  if (!visible) return false;
  set(pen.cr, kSandbagColour);
  cairo_new_sub_path(pen.cr);
  cairo_arc(pen.cr, bag.x, bag.y, bag_r, 0.0, 2.0 * units::kPi);
  cairo_fill_preserve(pen.cr);
  set(pen.cr, kDark);
  cairo_set_line_width(pen.cr, 1.0);
  cairo_stroke(pen.cr);
  return true;
}

// An arrow at the edge of the picture, pointing from the pivot to the sandbag far out.
void sandbag_arrow(const Pen& pen, Pixel bag) {
  cairo_t* cr = pen.cr;
  const View& v = pen.v;
  const Pixel o = pen.px({0.0, 0.0});
  const double dx = bag.x - o.x, dy = bag.y - o.y, len = std::hypot(dx, dy);
  const double ux = dx / len, uy = dy / len;
  double tmax = std::numeric_limits<double>::infinity();
  if (ux > 0) tmax = std::min(tmax, (v.width - 12 - o.x) / ux);
  if (ux < 0) tmax = std::min(tmax, (12 - o.x) / ux);
  if (uy > 0) tmax = std::min(tmax, (v.bottom - 12 - o.y) / uy);
  if (uy < 0) tmax = std::min(tmax, (v.top + 12 - o.y) / uy);
  const double tx = o.x + ux * tmax, ty = o.y + uy * tmax;
  set(cr, kSandbagColour);
  cairo_move_to(cr, tx, ty);
  cairo_line_to(cr, tx - 14 * ux - 7 * uy, ty - 14 * uy + 7 * ux);
  cairo_line_to(cr, tx - 14 * ux + 7 * uy, ty - 14 * uy - 7 * ux);
  cairo_close_path(cr);
  cairo_fill(cr);
}

}  // namespace whatnext::viz::draw
