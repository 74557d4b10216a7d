// State of the hybrid automaton: a discrete part (which contacts hold) and a fixed-size continuous
// vector whose meaning the discrete part decides, plus the observable snapshot derived from both.
#pragma once

#include <array>
#include <string_view>

namespace whatnext {

// The modes of docs/model.md §4. M1/M2: sandbag falling (rope slack/taut); M3: on the seesaw, rope slack;
// M4: on the seesaw, rope taut, lid swinging; M5: on the seesaw, rope taut, lid resting.
enum class Mode { M1 = 1, M2, M3, M4, M5 };
std::string_view to_string(Mode mode);

// Energy booked at the jumps (docs/extensions.md "Energy ledger"); the flows' losses are
// integrated in the continuous state instead. Marks hold the values at the last booking.
struct Books {
  double initial_total = 0.0;  // machine and balloon at t = 0 [J]
  double impacts = 0.0;        // machine energy lost in impacts (and the radio's latch) [J]
  double balloon_catch = 0.0;  // balloon energy lost when the lid forces its velocity [J]
  double lid_push = 0.0;       // work of the (one-way) lid contact on the balloon, to the mark [J]
  double machine_mark = 0.0, balloon_v_mark = 0.0, balloon_e_mark = 0.0, drag_mark = 0.0;
  double balloon_vx_mark = 0.0;  // a balloon smaller than the box moves sideways too
};

// A guard that is zero where a smooth piece starts but known to turn negative at once, because a
// contact was just released (or a force just appeared): g(t) ~ lead (t - t0)^order with lead < 0.
// order 0: an ordinary guard. The integrators look for its next zero past the start; until the
// guard leaves the band |g| <= floor (rounding) it counts as zero, so it fires only beyond it.
struct GuardStart {
  int order = 0;
  double lead = 0.0;
  double floor = 0.0;
};
constexpr int kGuardSlots = 20;

struct Discrete {
  bool on_seesaw = false;     // sandbag on the arm (massless seesaw: once landed, for good)
  bool taut = false;          // rope straight
  bool lid_resting = true;    // lid lying at its lowest angle phiL0
  bool balloon_stuck = true;  // balloon pressed against the lid
  // A balloon smaller than the box (docs/extensions.md): while it touches the lid, held in the
  // corner by the far wall or its top (else sliding along the lid); out of the box for good.
  bool balloon_held = true;
  bool balloon_out = false;
  int balloon_side = 1;       // held by the far wall (+1) or by the hinge's wall (-1)
  bool balloon_edge = false;  // out, rolling round the lid's free edge (its slots: the angle, rate)
  bool fallen_off = false;    // sandbag slid off the arm's end: it never lands again
  bool latched = false;       // radio: lid latched open after lid_open, rope slack for good
  bool heavy = false;         // the seesaw has inertia (copied from the machine at the start)
  // The built machine's contacts (docs/extensions.md): the sandbag held at the arm's end by the
  // stop; the seesaw standing on the floor with its left (+1) or right (-1) end; the sandbag on
  // the floor (it never lands on the arm again).
  bool at_stop = false;
  int grounded = 0;
  bool bag_on_floor = false;
  // Coulomb friction (docs/extensions.md "Friction"): the sandbag sticks on the arm, or slips along
  // it in the direction of bag_slip (+1 outwards, -1 towards the pivot; 0 where no friction acts).
  bool bag_stuck = false;
  int bag_slip = 0;
  // Coulomb torques: the seesaw held on its pivot, or turning (+1 phiS' > 0, -1); the lid likewise.
  bool seesaw_stuck = false;
  int seesaw_slip = 0;
  bool lid_stuck = false;
  int lid_slip = 0;
  double parked_seesaw = 0.0;  // seesaw angle while nothing moves it (M1) [rad]
  int side = 1;                // R's side of the line P-E, for the inverse closure phiS(phiL)
  // On the rope's closure (lid swinging on a straight rope, something with inertia on the seesaw)
  // the angle integrated is the seesaw's, or the lid's near the lid's dead centre (|k| large).
  bool lid_chart = false;
  // A rope that stretches (docs/impact.md): longer than l_R and pulling as a spring-damper. The rope
  // contact (taut) stays open then; the mode names it as straight.
  bool stretched = false;
  // ... slack again but still longer than l_R: the spring's energy goes as the span shrinks to l_R.
  bool rope_relaxing = false;
  std::array<GuardStart, kGuardSlots> armed{};  // for the smooth piece that starts here
  Books books;

  Mode mode() const { return mode_of(on_seesaw, taut || stretched, lid_resting); }
  static Mode mode_of(bool on, bool taut, bool resting) {
    if (!on) return taut ? Mode::M2 : Mode::M1;
    if (!taut) return Mode::M3;
    return resting ? Mode::M5 : Mode::M4;
  }
  // While the sandbag rides a taut rope, or a seesaw with inertia, its motion is polar (r, phiS);
  // otherwise Cartesian (on a massless seesaw with the rope slack that is free fall).
  // The stop and the floor make a massless seesaw's motion polar too: the sandbag at a fixed r, or
  // the arm at a fixed angle.
  bool polar() const { return on_seesaw && (taut || heavy || at_stop || grounded != 0); }
  // The seesaw held at its angle (by the floor or its pivot's friction); the lid likewise (by the
  // box or its hinge's friction).
  bool seesaw_held() const { return grounded != 0 || seesaw_stuck; }
  bool lid_held() const { return lid_resting || lid_stuck; }
};

// Continuous state. Cartesian layout: x, h, x', h' of the sandbag; polar layout: r, phiS, r', phiS'
// (r, phiL, r', phiL' in the lid chart, and likewise the seesaw slots below).
// Then phiL, phiL' (unused while the lid is slaved to the seesaw or resting), then the balloon's
// height and rate (unused while it is stuck under the lid); then a seesaw with inertia's angle and
// rate while the sandbag is off it; then the energy dissipated so far by the damped pivot, the
// damped lid hinge and the balloon's air drag (zero rates unless those switches are on).
// A balloon smaller than the box: while it slides along the lid its two slots hold the distance
// along the lid of the point it touches and its rate; while free its height and vertical rate,
// with its x (from the hinge) and horizontal rate in slots 13 and 14. Then the heat of Coulomb
// friction, and the energy a rope that stretches has lost (its damper, docs/impact.md).
using State = std::array<double, 17>;
namespace slot {
constexpr int x = 0, h = 1, vx = 2, vh = 3;
constexpr int r = 0, phi_s = 1, dr = 2, dphi_s = 3;
constexpr int phi_l = 4, dphi_l = 5, balloon_h = 6, balloon_v = 7;
constexpr int seesaw_phi = 8, seesaw_dphi = 9;
constexpr int lost_pivot = 10, lost_hinge = 11, lost_drag = 12;
constexpr int balloon_x = 13, balloon_vx = 14;
constexpr int lost_friction = 15;
constexpr int lost_rope = 16;
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
  double balloon_x = 0, balloon_vx = 0;       // ... and from the hinge sideways (not a CSV column)
  double balloon_limit = 0, balloon_limit_rate = 0;
  double tension = 0;  // rope tension [N]
  double sandbag_kinetic = 0, sandbag_potential = 0, lid_kinetic = 0, lid_potential = 0;
  double normal_force = 0;  // arm on the sandbag [N] (0 when off the arm)
  double box_reaction = 0;  // box on the resting lid [N m] (0 when swinging)
  // The built machine's reactions (not CSV columns): the end stop on the sandbag along the arm, the
  // floor on the seesaw's end that stands on it, the floor on the sandbag [N] (0 where none acts).
  double stop_reaction = 0, floor_reaction = 0, bag_floor_reaction = 0;
  // ... and its contacts, for the mode's words (viz::mode_words): the sandbag held by the end stop
  // or lying on the floor, the seesaw standing on the floor, the rope let go at the radio's latch.
  bool at_stop = false, bag_on_floor = false, seesaw_on_floor = false, rope_let_go = false;
  // Energy ledger (docs/extensions.md). Potentials: zero at the pivot level (sandbag, seesaw), at
  // the hinge (lid) and, for the balloon's net lift, at the hinge level.
  double seesaw_kinetic = 0, seesaw_potential = 0, balloon_kinetic = 0, balloon_potential = 0;
  double lost_impacts = 0, lost_balloon_catch = 0;                         // booked at jumps
  double dissipated_pivot = 0, dissipated_hinge = 0, dissipated_drag = 0;  // integrated
  double dissipated_friction = 0;  // Coulomb friction's heat, integrated
  double lid_push_work = 0;        // work done on the balloon by the lid that does not feel it
  double rope_potential = 0, dissipated_rope = 0;  // a rope that stretches: its spring, its damper
  double initial_total = 0;
  // The machine: sandbag, lid and seesaw (the balloon does not act on it).
  double energy() const {
    return sandbag_kinetic + sandbag_potential + lid_kinetic + lid_potential + seesaw_kinetic +
           seesaw_potential + rope_potential;
  }
  double total_energy() const { return energy() + balloon_kinetic + balloon_potential; }
  double dissipated() const {
    return dissipated_pivot + dissipated_hinge + dissipated_drag + dissipated_friction + dissipated_rope;
  }
  double lost() const { return lost_impacts + lost_balloon_catch; }
  // initial = now + lost + dissipated - work put in by the lid's push on the balloon.
  double ledger_residual() const {
    return initial_total - (total_energy() + lost() + dissipated() - lid_push_work);
  }
};

// What a Snapshot holds of where everything is (Observer::Detail::positions), alone.
struct Positions {
  double t = 0.0, x = 0.0, h = 0.0, phi_s = 0.0, phi_l = 0.0, balloon_limit = 0.0, balloon_h = 0.0;
  Mode mode = Mode::M1;
  bool rope_taut = false;
  double balloon_x = 0.0;  // the balloon's centre from the hinge sideways
};

}  // namespace whatnext
