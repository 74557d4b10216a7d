// The mode automaton of MODEL.md: flows, guards and jumps, each written once.
// It knows nothing of integrators; simulate.cpp couples it to one.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <vector>

#include "whatnext/events.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/params.hpp"
#include "whatnext/state.hpp"

namespace whatnext {

// Guard functions: each fires when its value crosses from negative to >= 0.
// Inactive guards read -infinity. The order is the priority for events found in the same step.
enum Guard : int {
  kGuardLands,
  kGuardRopeTaut,
  kGuardRopeSlack,
  kGuardLidRests,
  kGuardLidLifts,
  kGuardBalloonCaught,
  kGuardBalloonFree,
  kGuardLidOpen,
  kGuardSeesawVertical,
  kGuardAtPivot,
  kGuardRopeLocked,
  kGuardFallsOff,  // extensions (docs/extensions.md) come last: ties keep MODEL.md's priorities
  kGuardLeaves,
  kGuardRadioOn,
  kGuardCount
};
using GuardValues = std::array<double, kGuardCount>;
constexpr double kInactive = -std::numeric_limits<double>::infinity();
EventType event_of(Guard g);

// Full kinematics at one instant, whatever the layout of the continuous state.
struct Kinematics {
  double x = 0, h = 0, vx = 0, vh = 0;
  double r = 0, dr = 0, phi_s = 0, dphi_s = 0, ddphi_s = 0;
  double phi_l = 0, dphi_l = 0, ddphi_l = 0;
  double balloon_h = 0, balloon_v = 0;  // the balloon's centre from the hinge level
  Transfer transfer;  // valid while the rope is taut
};

class Model {
 public:
  explicit Model(const Scenario& scenario);

  const Scenario& scenario() const { return sc_; }
  const RopeGeometry& rope() const { return rope_; }
  const BalloonLimit& balloon_limit() const { return limit_; }

  // Start state (MODEL.md "Start"); events at t = 0 (none in a usual start) are appended to out.
  HybridState initial(std::vector<Event>& out) const;

  // Flow: dy/dt in the discrete state d.
  void flow(const Discrete& d, const State& y, State& dy) const;
  // Guard values in the discrete state d.
  void guards(const Discrete& d, const State& y, GuardValues& g) const;
  // Jump for the guard that fired at hs.t; every resulting event (the fired one first, then any
  // that follow at the same instant) is appended to out. Returns true when the run ends.
  bool jump(Guard fired, HybridState& hs, std::vector<Event>& out) const;
  // The run ends at t_max.
  void timeout(HybridState& hs, std::vector<Event>& out) const;

  Kinematics kinematics(const Discrete& d, const State& y) const;
  Snapshot snapshot(const HybridState& hs) const;
  // The machine's energy: sandbag, lid and seesaw.
  double energy(const Kinematics& k) const;
  // The balloon's: (1/2) m_B v^2 - m_B a_B h (its net lift as a potential).
  double balloon_energy(double h, double v) const;
  // The balloon's upward acceleration at speed v (lift, weights and air drag): the flow, the
  // balloon_free guard and the jumps all use this one function.
  double balloon_acceleration(double v) const { return a_b_ - drag_ * v * std::fabs(v); }

 private:
  // The seesaw's angular acceleration with whatever it carries (J phiS'' = Q, docs/extensions.md),
  // and the lid's angle on the rope's closure when the rope is taut.
  struct Swing {
    double ddr, ddphi_s, phi_l;
    Transfer tr;
  };
  Swing swing(bool on, bool taut, double r, double phi_s, double dr, double dphi_s) const;
  double lid_free_acceleration(double phi_l, double dphi_l) const;
  double lid_rope_torque(const Kinematics& k) const;
  // Torque of sandbag and seesaw weights about the pivot, over g (+ = left arm down).
  double seesaw_load(bool on, double r, double phi_s) const;
  bool lid_lifts_now(bool on, double r, double phi_s) const;
  double normal_force(const Kinematics& k) const;
  double radio_gap(double balloon_h) const;
  void dissipation(const Discrete& d, const Kinematics& k, State& dy) const;

  // Pieces of jumps, each used by several events.
  void impact(HybridState& hs, const Kinematics& before, bool bag, bool rope) const;
  // Writes the continuous state for hs.d's layout from full kinematics.
  void place(HybridState& hs, const Kinematics& k) const;
  void set_seesaw_rate(HybridState& hs, double rate) const;
  Event make_event(EventType type, HybridState& hs, Mode before) const;
  void settle(HybridState& hs, std::vector<Event>& out) const;
  void release_balloon_if_lid_jumped(HybridState& hs, double limit_rate_before,
                                     const Books& opened, std::vector<Event>& out) const;
  void free_balloon(HybridState& hs, const Kinematics& k, double v) const;
  // Ledger: fold the continuous phase into the books, then book what a jump changed.
  void open_books(HybridState& hs, const Kinematics& k) const;
  void book(HybridState& hs) const;
  double lid_push_now(const Discrete& d, const Kinematics& k, const State& y) const;

  Scenario sc_;
  RopeGeometry rope_;
  BalloonLimit limit_;
  double g_, m_s_, m_l_, i_l_, r_l_, a_b_, phi_l0_, vertical_;
  // Extensions (zero or infinite: MODEL.md's machine).
  double drag_, m_b_, i_s_, w_s_, c_p_, c_l_, arm_;
  bool heavy_, radio_;
  Vec2 switch_;
  double string_, balloon_x_;
};

}  // namespace whatnext
