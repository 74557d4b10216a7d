// What one integration keeps between evaluations of the model, so that the model stays const.
//
// Design: a Model is the machine's constants and its laws, built once from the scenario and never
// changed (as MuJoCo's mjModel, or Drake's const System). What changes during a run lives in the
// run: the continuous and discrete state (HybridState) and this workspace, owned by the one
// simulate() call that integrates (its Runner), handed to flow(), guards() and kinematics() by
// pointer (as Drake's Context, or MuJoCo's mjData). A null workspace computes everything afresh:
// the same numbers, bit for bit, for a caller on another thread, a test, or a jump (rare: a memo
// there saves nothing). One Model may then serve any number of threads at once.
//
// It holds memos only: each hands back what it computed last for the same arguments, so that no
// result depends on whether it was used.
#pragma once

#include <cmath>
#include <limits>

#include "whatnext/geometry.hpp"

namespace whatnext {

// The seesaw's angular acceleration with whatever it carries (J phiS'' = Q, docs/extensions.md),
// and the lid's angle on the rope's closure when the rope is taut (Model::swing).
struct Swing {
  double ddr, ddphi_s;       // r'' [m/s^2] (on the arm only), phiS'' [rad/s^2]
  RopeGeometry::Linkage lk;  // the seesaw's cos and sin always; the rest while taut
};
// The same motion on the rope's closure in the lid's chart: phiL integrated, phiS = S(phiL).
struct LidSwing {
  double ddr, ddphi_l;  // r'' [m/s^2], phiL'' [rad/s^2]
  RopeGeometry::Linkage lk;
};

// The last result of a function of six numbers and some flags.
template <class Result>
struct Memo {
  bool valid = false;
  int flags = 0;
  double args[6] = {0, 0, 0, 0, 0, 0};
  Result value{};
};

// cos and sin of an angle that stays put for a while (a resting lid, a parked seesaw: every guard
// evaluation of the sandbag's fall took a sincos of each): the last angle's.
struct Trig {
  double angle = std::numeric_limits<double>::quiet_NaN(), cos = 1.0, sin = 0.0;
};

struct Workspace {
  // The flow's last stage (FSAL) and the guards at the step's end ask for the swing of the same
  // state: the last one computed, handed out again for identical arguments.
  Memo<Swing> swing;
  Memo<LidSwing> lid_swing;
  Trig seesaw, lid;  // of phiS and phiL
};

// cos and sin of angle, from last when it is the same angle (last null: computed afresh).
inline void trig(Trig* last, double angle, double& c, double& s) {
  if (!last) {
    c = std::cos(angle), s = std::sin(angle);
    return;
  }
  if (!(last->angle == angle)) last->angle = angle, last->cos = std::cos(angle), last->sin = std::sin(angle);
  c = last->cos, s = last->sin;
}

}  // namespace whatnext
