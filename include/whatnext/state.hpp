// State of the hybrid automaton: a discrete part (which contacts hold) and a fixed-size continuous
// vector whose meaning the discrete part decides, plus the observable snapshot derived from both.
#pragma once

#include <array>
#include <string_view>

namespace whatnext {

// MODEL.md's modes. M1/M2: sandbag falling (rope slack/taut); M3: on the seesaw, rope slack;
// M4: on the seesaw, rope taut, lid swinging; M5: on the seesaw, rope taut, lid resting.
enum class Mode { M1 = 1, M2, M3, M4, M5 };
std::string_view to_string(Mode mode);

struct Discrete {
  bool on_seesaw = false;      // sandbag has landed (it never leaves: MODEL.md)
  bool taut = false;           // rope straight
  bool lid_resting = true;     // lid lying at its lowest angle phiL0
  bool balloon_stuck = true;   // balloon pressed against the lid
  double parked_seesaw = 0.0;  // seesaw angle while nothing moves it (M1) [rad]

  Mode mode() const {
    if (!on_seesaw) return taut ? Mode::M2 : Mode::M1;
    if (!taut) return Mode::M3;
    return lid_resting ? Mode::M5 : Mode::M4;
  }
  // While the sandbag rides a taut rope its motion is polar (r, phiS); otherwise Cartesian.
  bool polar() const { return on_seesaw && taut; }
};

// Continuous state. Cartesian layout: x, h, x', h' of the sandbag; polar layout: r, phiS, r', phiS'.
// Then phiL, phiL' (unused while the lid is slaved to the seesaw or resting), then the balloon's
// height and rate (unused while it is stuck under the lid).
using State = std::array<double, 8>;
namespace slot {
constexpr int x = 0, h = 1, vx = 2, vh = 3;
constexpr int r = 0, phi_s = 1, dr = 2, dphi_s = 3;
constexpr int phi_l = 4, dphi_l = 5, balloon_h = 6, balloon_v = 7;
}  // namespace slot

struct HybridState {
  double t = 0.0;
  Discrete d;
  State y{};
};

// Everything an observer may want at one instant, in SI units and radians.
struct Snapshot {
  double t = 0.0;
  Mode mode = Mode::M1;
  bool on_seesaw = false, rope_taut = false, lid_resting = true, balloon_stuck = true;
  double x = 0, h = 0, vx = 0, vh = 0;        // sandbag position and velocity
  double r = 0, dr = 0;                       // distance from the pivot and its rate
  double phi_s = 0, dphi_s = 0;               // seesaw
  double phi_l = 0, dphi_l = 0, ddphi_l = 0;  // lid
  double balloon_h = 0, balloon_v = 0;        // balloon centre, from the hinge level
  double balloon_limit = 0, balloon_limit_rate = 0;
  double tension = 0;                         // rope tension [N]
  double sandbag_kinetic = 0, sandbag_potential = 0, lid_kinetic = 0, lid_potential = 0;
  double energy() const { return sandbag_kinetic + sandbag_potential + lid_kinetic + lid_potential; }
};

}  // namespace whatnext
