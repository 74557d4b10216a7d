// Drawing one frame of the animation with Cairo, part by part: the machine's parts from the scene's
// geometry (draw_machine.cpp) and the texts around it (frame_text.cpp). render_frame
// (animation.cpp) calls them in order, which is the order of the parts in front of each other; each
// sets the colour and line width it needs and leaves them set.
#pragma once

#include <cairo.h>

#include <string>
#include <string_view>
#include <vector>

#include "scene.hpp"
#include "whatnext/events.hpp"
#include "whatnext/viz/animation.hpp"

namespace whatnext::viz::draw {

// The drawing's colours: the scene's (scene.hpp), which the page paints with too.
using scene::kBagText, scene::kBlack, scene::kBoxInside, scene::kBoxWall, scene::kCursor, scene::kDark,
    scene::kDial, scene::kEventRed, scene::kGrey, scene::kLid, scene::kLightGrey, scene::kMidGrey,
    scene::kRadio, scene::kSeesaw, scene::kWhite;

inline void set(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

// Paths in metres on a Cairo context, through the view's world-to-pixel mapping.
struct Pen {
  cairo_t* cr;
  const View& v;
  Pixel px(Vec2 p) const { return to_pixel(v, p); }
  void move(Vec2 p) const;
  void line(Vec2 p) const;
  void width_m(double metres, double min_px) const;  // a line width in metres, at least min_px
  void polyline(const std::vector<Vec2>& pts) const;
  void circle(Vec2 c, double radius_px) const;
};

// ---- the machine (draw_machine.cpp), in the order a frame draws it ----
// The floor: pieces of it, or the built machine's floor across the picture with the ground below.
void floor(const Pen& pen, const scene::StillParts& still);
void stand(const Pen& pen, const scene::StillParts& still);
void box_inside(const Pen& pen, const scene::StillParts& still);
void balloon(const Pen& pen, const scene::MovingParts& moving);  // with its string
void walls(const Pen& pen, const scene::StillParts& still);      // in front of the balloon
void radio(const Pen& pen, const scene::StillParts& still);
void notes(const Pen& pen, const scene::StillParts& still);  // the radio plays
void lid(const Pen& pen, const scene::MovingParts& moving);
void seesaw(const Pen& pen, const scene::MovingParts& moving);
void rope(const Pen& pen, const scene::MovingParts& moving);
// The sandbag if it is in the picture; returns whether it is, and its pixel in `at`.
bool sandbag(const Pen& pen, const scene::MovingParts& moving, Pixel& at);
// An arrow at the picture's edge, from the pivot towards the sandbag's pixel `bag` beyond it.
void sandbag_arrow(const Pen& pen, Pixel bag);

// ---- the texts (frame_text.cpp) ----
// The band above the machine: time and mode; the event (in red) on a held frame, else the speed;
// the distance of a sandbag beyond the picture.
void caption(cairo_t* cr, const View& v, const Recording& rec, const std::vector<EventGroup>& groups,
             const Frame& frame, bool bag_visible);
// The bar below the machine: the whole run, its events named under their ticks, this frame's time.
void time_bar(cairo_t* cr, const View& v, const Recording& rec, const std::vector<EventGroup>& groups,
              const Frame& frame);

}  // namespace whatnext::viz::draw
