// Guards: when the smooth motion must stop for an event, and each guard's rounding band.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

// --- guards ------------------------------------------------------------------------------------

void Model::guards(const Discrete& d, const State& y, GuardValues& g, GuardValues* rates, int only,
                   Workspace* ws) const {
  g.fill(kInactive);
  if (rates) rates->fill(std::numeric_limits<double>::quiet_NaN());
  const Kinematics k = guard_kinematics(d, y, ws);
  balloon_guards(d, y, k, g, rates);
  // The radio's wait: only the balloon matters now; the built machine's seesaw and sandbag still
  // move on its stop and floor. A seesaw with inertia swings on, and must not swing round
  // (docs/model.md §6: no somersaults, whatever happens meanwhile).
  if (d.latched && !c_.built) {
    if (d.heavy) g[kGuardSeesawVertical] = seesaw_vertical_gap(k);
    return;
  }

  open_contact_gaps(d, k, g);
  const bool forces = closed_forces_wanted(d, only);
  const bool open = !(d.on_seesaw && d.taut && d.lid_resting);
  // Made in place (a conditional of two prvalues): assigned, its 700 bytes were copied at every
  // step; unused, it is default-initialized (System{} would zero all of it).
  const auto unused = [] {
    contact::System s;
    return s;
  };
  const contact::System sys = forces || (rates && open) ? contact_system(d, k) : unused();
  if (rates && open) open_contact_rates(d, k, sys, *rates);
  if (forces) closed_contact_forces(d, k, sys, g);
  slip_guards(d, k, g);
  if (c_.contacts > 3) built_guards(d, k, sys, g, rates);
  linkage_guards(d, k, g, only);
  // The lid's opening has the lid's rate: a lid that just reaches the vertical between two steps
  // is then seen by the Hermite cubic of the guard's values and rates.
  if (rates && !d.latched) (*rates)[kGuardLidOpen] = k.dphi_l;
  if (c_.stretchy) stretchy_guards(d, k, g, rates);
}

WHATNEXT_STAGE void Model::balloon_guards(const Discrete& d, const State& y, const Kinematics& k,
                                          GuardValues& g, GuardValues* rates) const {
  if (c_.radio) g[kGuardRadioOn] = radio_gap(k);
  if (c_.small) {
    small_balloon_guards(d, k, g, rates);
  } else if (d.balloon_stuck) {
    g[kGuardBalloon] =
        limit_.acceleration_at(k.cos_l, k.sin_l, k.dphi_l, k.ddphi_l) - balloon_acceleration(k.balloon_v);
  } else if (!d.latched) {
    g[kGuardBalloon] = y[slot::balloon_h] - limit_.height_at(k.cos_l, k.sin_l);
  }
  if (rates && !c_.small && !d.balloon_stuck && !d.latched) {
    (*rates)[kGuardBalloon] = y[slot::balloon_v] - limit_.rate_at(k.sin_l, k.dphi_l);
  }
}

WHATNEXT_STAGE void Model::open_contact_gaps(const Discrete& d, const Kinematics& k, GuardValues& g) const {
  // Open contacts: their gaps, negative while open.
  if (!d.on_seesaw && !d.fallen_off && !d.bag_on_floor) g[kGuardBag] = -height_above_arm(k);
  const Vec2 u_s{k.cos_s, k.sin_s}, u_l{k.cos_l, k.sin_l};
  if (!d.taut && !d.latched) g[kGuardRope] = rope_.span(u_s, u_l) - rope_.rope_length();
  if (!d.lid_resting && !d.latched) g[kGuardLid] = c_.phi_l0 - k.phi_l;
}

WHATNEXT_STAGE bool Model::closed_forces_wanted(const Discrete& d, int only) const {
  // Closed contacts' guards are minus their forces. A massless seesaw held by one contact alone
  // carries no force through it at all (identically zero: no guard).
  // The stop and the floor carry forces on a massless seesaw as well (a pendulum's rod, a seesaw
  // standing on its end).
  // So do the pivot's and the hinge's friction holding the seesaw or the lid.
  const bool held = d.at_stop || d.grounded != 0 || d.seesaw_stuck || d.lid_stuck;
  const bool loaded = c_.heavy || (d.on_seesaw && d.taut) || held;
  return loaded && (d.on_seesaw || d.taut || held) &&
         (only < 0 || only == kGuardBag || only == kGuardRope || only == kGuardLid || only == kGuardStop ||
          only == kGuardFloor || only == kGuardBagSlip || only == kGuardPivotSlip || only == kGuardHingeSlip);
}

WHATNEXT_STAGE void Model::open_contact_rates(const Discrete& d, const Kinematics& k,
                                              const contact::System& sys, GuardValues& rates) const {
  // An open contact's guard is minus its gap, so its rate is minus the gap's rate W_i . v.
  if (!d.on_seesaw && !d.fallen_off && !d.bag_on_floor) rates[kGuardBag] = -sys.rate(kBag, sys.velocity);
  if (!d.taut && !d.latched) rates[kGuardRope] = -sys.rate(kRope, sys.velocity);
  if (!d.lid_resting && !d.latched) rates[kGuardLid] = -k.dphi_l;
}

WHATNEXT_STAGE void Model::closed_contact_forces(const Discrete& d, const Kinematics& k,
                                                 const contact::System& sys, GuardValues& g) const {
  // The forces that make the flow's own accelerations (k has them).
  contact::PerContact f;
  if (!contact::multipliers_for(sys, active_set(d), accelerations(d, k), f)) return;
  // Held by sandbag and rope together, a massless seesaw's arm pushes with the tension times the
  // coupling k (torque balance), so the sandbag's guard is the sign of k and the rope's the tension.
  // The sign of k is that of -W_RS (the rope's gap gradient along phiS), which stays finite where k
  // passes through infinity at the lid's dead centre.
  if (d.on_seesaw && (c_.heavy || d.taut)) g[kGuardBag] = c_.heavy ? -f[kBag] : sys.normal[kRope][2];
  if (d.taut) g[kGuardRope] = -f[kRope];
  if (d.lid_resting && d.taut) g[kGuardLid] = -f[kLid];
  if (d.at_stop) g[kGuardStop] = -f[kStop];
  if (d.grounded != 0) g[kGuardFloor] = -f[d.grounded > 0 ? kFloorLeft : kFloorRight];
  // Sticking: how far the friction force it takes exceeds mu times the arm's push.
  if (d.bag_stuck) g[kGuardBagSlip] = std::fabs(f[kBagSlip]) - c_.mu * f[kBag];
  if (d.seesaw_stuck) g[kGuardPivotSlip] = std::fabs(f[kPivotSlip]) - coulomb_hold(d, k, kPivotSlip);
  if (d.lid_stuck) g[kGuardHingeSlip] = std::fabs(f[kHingeSlip]) - coulomb_hold(d, k, kHingeSlip);
}

WHATNEXT_STAGE void Model::slip_guards(const Discrete& d, const Kinematics& k, GuardValues& g) const {
  // Slipping: minus the slip's speed, zero where it stops.
  if (d.seesaw_slip != 0) g[kGuardPivotSlip] = -d.seesaw_slip * k.dphi_s;
  if (d.lid_slip != 0) g[kGuardHingeSlip] = -d.lid_slip * k.dphi_l;
  // Only the polar layouts have an arm that pushes.
  if (c_.friction && d.polar() && !d.bag_stuck && !d.at_stop && d.bag_slip != 0)
    g[kGuardBagSlip] = -d.bag_slip * k.dr;
}

WHATNEXT_STAGE void Model::linkage_guards(const Discrete& d, const Kinematics& k, GuardValues& g,
                                          int only) const {
  if (!d.latched)
    g[kGuardLidOpen] = k.phi_l - c_.vertical;  // a lid resting at or past it is open from the start
  if (on_closure(d)) {
    // The lid's dead centre: it reaches the rope's line (the rope would touch the hinge and then
    // run through the box). Crossed at a finite rate in the lid chart, so found exactly.
    const Vec2 u_s{k.cos_s, k.sin_s}, u_l{k.cos_l, k.sin_l};
    if (only < 0 || only == kGuardRopeLocked) g[kGuardRopeLocked] = rope_.lid_side_of_rope(u_s, u_l);
    // Integrate the angle that moves slower: switch charts at |k| = 2 (seesaw) or 1/2 (lid).
    g[kGuardChart] = d.lid_chart ? std::fabs(1.0 / k.transfer.k) - 2.0 : std::fabs(k.transfer.k) - 2.0;
  } else if (d.taut && !d.lid_held() && !d.latched && !d.seesaw_held()) {
    // The massless seesaw following the lid: R on the line from the pivot to E, where the seesaw
    // would have to turn infinitely fast.
    g[kGuardRopeLocked] = std::fabs(rope_.cos_rho(k.phi_l)) - (1.0 - 1e-9);
  }
  if (d.polar()) {
    g[kGuardAtPivot] = -k.r;
  } else if (d.on_seesaw) {
    // A free-falling sandbag can only leave the left arm through the pivot's vertical line.
    g[kGuardAtPivot] = k.x;
  }
  // No somersaults (the paper allows only |phiS| < 90 deg): a seesaw that turns vertical either way
  // ends the model, whatever it carries (docs/model.md §6). Only the parked massless seesaw (M1),
  // which nothing moves, is left out: its angle is the input's.
  const bool seesaw_moves = d.on_seesaw || d.heavy || d.taut;
  if (seesaw_moves) g[kGuardSeesawVertical] = seesaw_vertical_gap(k);
  if (d.on_seesaw && c_.arm < kNoEnd && !c_.stop) g[kGuardArmEnd] = k.r - c_.arm;
}

WHATNEXT_STAGE void Model::built_guards(const Discrete& d, const Kinematics& k, const contact::System& sys,
                                        GuardValues& g, GuardValues* rates) const {
  // The open gaps of the stop and the floor; their forces while closed are set with the others'.
  if (c_.stop && d.on_seesaw && !d.at_stop) {
    g[kGuardStop] = k.r - c_.arm;
    if (rates) (*rates)[kGuardStop] = k.dr;
  }
  if (!c_.floor) return;
  // The seesaw's end nearer the floor (only a seesaw that moves can reach it).
  const bool seesaw_moves = d.on_seesaw || d.heavy || d.taut;
  if (d.grounded == 0 && seesaw_moves) {
    const double left = -c_.arm * k.sin_s - c_.h_floor,
                 right = sc_.machine.seesaw_right_arm * k.sin_s - c_.h_floor;
    const int i = left <= right ? kFloorLeft : kFloorRight;
    g[kGuardFloor] = -std::fmin(left, right);
    if (rates && sys.contacts > 3) (*rates)[kGuardFloor] = -sys.rate(i, sys.velocity);
  }
  if (!d.on_seesaw && !d.bag_on_floor) {
    g[kGuardBagFloor] = c_.h_floor - k.h;
    if (rates) (*rates)[kGuardBagFloor] = -k.vh;
  }
}

double Model::guard_floor(Guard g, const Discrete& d) const {
  // A thousand times what rounding leaves in each kind of value, on this machine's scale.
  const double len = c_.length_scale, weight = (c_.m_s + c_.m_l + sc_.machine.seesaw_mass) * c_.g;
  switch (g) {
    case kGuardBag:
      if (!d.on_seesaw) return 1e-12 * len;
      return c_.heavy ? 1e-10 * weight : 1e-12;  // the arm's push, or the sign of k
    case kGuardRope: return d.taut ? 1e-10 * weight : 1e-12 * len;
    case kGuardLid: return d.lid_resting ? 1e-10 * weight * len : 1e-12;
    case kGuardStop: return d.at_stop ? 1e-10 * weight : 1e-12 * len;
    case kGuardFloor: return d.grounded != 0 ? 1e-10 * weight : 1e-12 * len;
    case kGuardBagFloor:
    case kGuardRopeRelaxed: return 1e-12 * len;
    case kGuardBagSlip: return d.bag_stuck ? 1e-10 * weight : 1e-12 * len;
    case kGuardPivotSlip: return d.seesaw_stuck ? 1e-10 * weight * len : 1e-12;
    case kGuardHingeSlip: return d.lid_stuck ? 1e-10 * weight * len : 1e-12;
    case kGuardBalloon: return d.balloon_stuck ? 1e-10 * c_.g : 1e-12 * len;
    case kGuardBalloonCorner:
    case kGuardBalloonEscape: return 1e-12 * len;
    default: return 0.0;
  }
}

}  // namespace whatnext
