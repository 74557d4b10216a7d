// The scene: where each part of the machine is drawn, in metres (x to the right, h up, origin at the
// seesaw's pivot). The one table of drawing geometry: the animation's view frames it, its frames
// draw it part by part (src/viz/draw_machine.cpp). No Cairo here, only geometry.
#pragma once

#include <array>
#include <limits>
#include <string_view>
#include <utility>
#include <vector>

#include "whatnext/geometry.hpp"
#include "whatnext/vec2.hpp"
#include "whatnext/viz/animation.hpp"  // Rgb
#include "whatnext/viz/recording.hpp"

namespace whatnext::viz::scene {

// The parts' colours, all on the GIF's palette (the sandbag's and the balloon's are public:
// animation.hpp). The page paints with the same ones, by the names of kColourNames, and its icon
// (web/src/icon.svg) names its shapes by them too (test_viz checks its colours).
constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kDark{51, 42, 51}, kGrey{96, 96, 96},
    kMidGrey{160, 160, 160}, kLightGrey{224, 224, 224}, kSeesaw{153, 85, 51}, kBoxWall{153, 127, 51},
    kBoxInside{255, 255, 204}, kLid{51, 85, 153}, kRadio{51, 42, 102}, kDial{204, 212, 255},
    kEventRed{204, 0, 0}, kBagText{153, 85, 0}, kCursor{0, 85, 204};
struct NamedColour {
  std::string_view name;
  Rgb rgb;
};
inline constexpr NamedColour kColourNames[] = {{"sandbag", kSandbagColour},
                                               {"balloon", kBalloonColour},
                                               {"seesaw", kSeesaw},
                                               {"boxWall", kBoxWall},
                                               {"boxInside", kBoxInside},
                                               {"lid", kLid},
                                               {"radio", kRadio},
                                               {"dial", kDial},
                                               {"dark", kDark},
                                               {"grey", kGrey},
                                               {"midGrey", kMidGrey},
                                               {"ground", kLightGrey},
                                               {"eventRed", kEventRed},
                                               {"bagText", kBagText}};

// The sandbag's drawn radius [m] (a frame draws it at least 6 px wide; the model has a point).
constexpr double kSandbagRadius = 0.05;
// A span up to this many rope lengths counts as the rope's length: the taut rope's closure holds
// the span to rounding, and the slack rope drawn straight is then no visible bit longer.
constexpr double kSpanTolerance = 1.0 + 1e-9;

// Where the model has the balloon's centre: the box's centre for the paper's balloon, anywhere in
// the plane for one smaller than the box (docs/extensions.md "A balloon smaller than the box").
Vec2 balloon_centre(const Machine& m, const Snapshot& s);

// The seesaw's right end (where the rope is tied) and the lid's free edge, at these angles.
Vec2 seesaw_end(const Machine& m, double phi_s);
Vec2 lid_end(const Machine& m, double phi_l);

// The radio: its body stands on the ground under the switch (or hangs below a switch that is lower).
struct RadioBox {
  double x0, x1, h0, h1;
};
RadioBox radio_box(const Machine& m);

// How far out the sandbag lands on the arm, roughly: the arm drawn before it lands reaches there.
double landing_distance(const Scenario& sc);

// A slack rope or string: a parabola sagging under its chord from a to b, as long as `length`.
std::vector<Vec2> sag_curve(Vec2 a, Vec2 b, double length, int n = 48);
// The slack rope from the seesaw's end a to the lid's edge e (sagging, or lying on the lid).
std::vector<Vec2> slack_rope(const Machine& m, Vec2 a, Vec2 e, double length);
// The rope let go at the seesaw's end, hanging from the lid's edge e into the open box.
std::vector<Vec2> hanging_rope(const Machine& m, Vec2 e, double length);
// The balloon's string from the balloon's skin to the radio's switch (over the box's wall while
// the balloon is in the box).
std::vector<Vec2> string_path(const Machine& m, Vec2 balloon);

// The endless arm's drawn length before the sandbag lands: long enough to catch it.
double endless_arm(const Scenario& sc);
// Drawn length of the left arm: a finite arm (`left_arm`, Machine::seesaw_left_arm) as it is; the
// model's endless arm `endless` long, or 0.1 m beyond the farthest the sandbag has been out on it
// (`farthest`, 0 before it lands). It does not shrink when the sandbag leaves it (the radio's
// latch sets it free). The animation and the page both draw with this.
double drawn_arm(double left_arm, double endless, double farthest);
// The same at time t of a recorded run.
double drawn_arm(const Recording& rec, double endless, double t);
// How high the end stop is drawn above the arm [m] at `scale` pixels per metre: above the sandbag
// drawn at the arm's end (kSandbagRadius), so that both show, and at least 10 px.
double stop_height(double scale);
// Is the seesaw's end farther from the lid's edge than the rope reaches?
bool beyond_rope(const RopeGeometry& geo, const Snapshot& s);

// With the radio, lid_open latches the lid and lets the rope go for good: when that is (latch),
// and the time of the first recorded state at or after it with the seesaw's end beyond the rope's
// reach (off: the rope has come off the seesaw's end then, for good). Infinity for none.
struct Release {
  double latch = std::numeric_limits<double>::infinity();
  double off = std::numeric_limits<double>::infinity();
};
Release release_of(const Recording& rec);
// The rope in state s as drawn (rope_path in animation.hpp), from the run's release.
std::vector<Vec2> rope_at(const Machine& m, const Snapshot& s, const Release& release);

// The parts that never move.
struct StillParts {
  double ground = 0.0;  // the box's bottom [m]
  bool floor = false;   // the built machine's floor runs across the whole picture
  // Without it, pieces of floor [x0, x1] under the pivot's stand, the box and the radio.
  std::array<std::pair<double, double>, 3> floor_pieces{};
  std::array<Vec2, 3> stand{};  // the pivot's stand: a triangle from the pivot to the ground
  Vec2 box_corner{};            // the box's inside: a square from its top left corner (the hinge)
  double box_side = 0.0;        //   down and to the right
  std::array<Vec2, 4> walls{};  // the box's walls and floor, from the hinge round to the far top
  RadioBox radio{};
  Vec2 dial{};                       // the radio's dial: its centre,
  double dial_radius = 0.0;          //   its radius for a square radio [m],
  double dial_squash = 1.0;          //   and the factor for a flat one
  std::array<Vec2, 2> radio_post{};  // from the radio's top up to the switch, where the string is tied
  Vec2 notes{};                      // where the notes rise from once the radio is on
};
StillParts still_parts(const Machine& m);

// The parts that move, in one state of the run.
struct MovingParts {
  Vec2 hinge{}, lid_end{};       // the whole lid (the rope is tied at its knot)
  Vec2 arm_left{}, arm_right{};  // the seesaw, its left arm as long as drawn_arm
  bool end_stop = false;         // an edge standing up from the left arm's end,
  Vec2 stop_top{};               //   above the sandbag drawn there
  std::vector<Vec2> rope;        // rope_path
  Vec2 sandbag{};                // the simulated point
  Vec2 balloon{};                // the balloon's centre
  double balloon_radius = 0.0;
  std::vector<Vec2> string;  // string_path
};
// `arm`: the left arm's drawn length; `stop_height`: how high the end stop stands [m].
MovingParts moving_parts(const Machine& m, const Snapshot& s, const Release& release, double arm,
                         double stop_height);

}  // namespace whatnext::viz::scene
