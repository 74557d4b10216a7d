// The mode automaton of MODEL.md: flows, guards and jumps, each written once.
// It knows nothing of integrators; simulate.cpp couples it to one.
#pragma once

#include <array>
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
  double energy(const Kinematics& k) const;

 private:
  struct Polar {
    double ddr, ddphi_s, phi_l;
    Transfer tr;
  };
  Polar taut_accelerations(double r, double phi_s, double dr, double dphi_s) const;
  double lid_free_acceleration(double phi_l) const;
  double lid_rope_torque(const Kinematics& k) const;
  bool lid_lifts_now(double r, double phi_s) const;
  double balloon_acceleration() const { return a_b_; }

  // Pieces of jumps, each used by several events.
  void impact(HybridState& hs, const Kinematics& before) const;
  void to_cartesian(HybridState& hs, const Kinematics& k) const;
  Event make_event(EventType type, const HybridState& hs, Mode before) const;
  void settle(HybridState& hs, std::vector<Event>& out) const;
  void release_balloon_if_lid_jumped(HybridState& hs, double limit_rate_before,
                                     std::vector<Event>& out) const;

  Scenario sc_;
  RopeGeometry rope_;
  BalloonLimit limit_;
  double g_, m_s_, m_l_, i_l_, r_l_, a_b_, phi_l0_, vertical_;
};

}  // namespace whatnext
