// The machine as a hybrid automaton: flows, guards and jumps, each written once.
// Which contacts hold (sandbag on the arm, rope taut, lid on the box) is decided at every event by
// one mechanism, the complementarity problems of contact.hpp; the modes M1-M5 are names of the
// resulting contact sets. It knows nothing of integrators; simulate.cpp couples it to one.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <string_view>
#include <vector>

#include "constants.hpp"
#include "contact.hpp"
#include "contact_table.hpp"
#include "workspace.hpp"
#include "whatnext/events.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/params.hpp"
#include "whatnext/state.hpp"

namespace whatnext {

static_assert(kGuardCount <= kGuardSlots, "Discrete::armed holds every guard");
using GuardValues = std::array<double, kGuardCount>;
constexpr double kInactive = -std::numeric_limits<double>::infinity();
// Guards whose value at or past zero at the start of a smooth piece means "happens now"
// (stops, and a stuck balloon the lid already leaves); the others are contacts, decided there.
bool fires_at_once(Guard g);

static_assert(kContactCount <= contact::kMaxContacts, "the contact problem holds every contact");

// Full kinematics at one instant, whatever the layout of the continuous state.
struct Kinematics {
  double x = 0, h = 0, vx = 0, vh = 0;
  double r = 0, dr = 0, ddr = 0, phi_s = 0, dphi_s = 0, ddphi_s = 0;  // ddr: on the arm only
  double phi_l = 0, dphi_l = 0, ddphi_l = 0;
  double balloon_h = 0, balloon_v = 0;  // the balloon's centre from the hinge level
  // A balloon smaller than the box: its centre's x from the hinge and rate; q and q' along the lid
  // while it touches it (geometry.hpp SmallBalloon).
  double balloon_x = 0, balloon_vx = 0, balloon_q = 0, balloon_dq = 0;
  Transfer transfer;         // valid while the rope is taut
  bool rope_let_go = false;  // the radio's latch let the rope go for good: it stores no energy
  double cos_s = 1, sin_s = 0, cos_l = 1, sin_l = 0;  // of phi_s and phi_l, computed once
};

class Model {
 public:
  explicit Model(const Scenario& scenario);

  const Scenario& scenario() const { return sc_; }
  const RopeGeometry& rope() const { return rope_; }
  const BalloonLimit& balloon_limit() const { return limit_; }

  // Start state: the contacts that touch at t = 0 are decided like those at any event; a rope or a
  // sandbag that touches but lets go at once is reported in out (at t = 0).
  HybridState initial(std::vector<Event>& out) const;

  // Flow: dy/dt in the discrete state d. ws: the integration's workspace (workspace.hpp); without
  // one, a fresh one: the same numbers.
  void flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const;
  void flow(const Discrete& d, const State& y, State& dy) const;
  // Guard values in the discrete state d, and, if asked, their rates where they are gaps of open
  // contacts (NaN elsewhere: not known). With only >= 0, g[only] is all the caller reads (root
  // finding), and what no other guard needs is skipped.
  void guards(const Discrete& d, const State& y, GuardValues& g, GuardValues* rates = nullptr, int only = -1,
              Workspace* ws = nullptr) const;
  // Jump for the guard that fired at hs.t; every resulting event is appended to out in the order
  // it happens (all at hs.t). Returns true when the run ends. The events' after, energy_after
  // and (unless an impact) energy_before are the state the motion goes on with once every event
  // of the instant is decided: simulate() fills them in then, once for all of them. ws: as in kinematics().
  bool jump(Guard fired, HybridState& hs, std::vector<Event>& out, Workspace* ws = nullptr) const;
  bool jump_contacts(Guard fired, HybridState& hs, std::vector<Event>& out, Workspace* ws = nullptr) const;
  // The run ends at t_max.
  void timeout(HybridState& hs, std::vector<Event>& out) const;
  // The rounding band of a guard in d (see GuardStart): values within it count as zero.
  double guard_floor(Guard g, const Discrete& d) const;
  void built_guards(const Discrete& d, const Kinematics& k, const contact::System& sys, GuardValues& g,
                    GuardValues* rates) const;

  // rates = false: where everything is (x, h, r, phiS, phiL with their cos and sin, the balloon's
  // height), the same numbers, without the rates, accelerations and the linkage's k (all zero).
  // ws: the integration's workspace, or null (computed afresh): the same numbers.
  Kinematics kinematics(const Discrete& d, const State& y, bool rates = true, Workspace* ws = nullptr) const;
  // What the guards read: kinematics() with rates, but phiS left NaN where only its cos and sin
  // follow from the state (the sandbag's fall, the lid's chart): no guard reads the angle itself,
  // and its atan2 was 4 % of a sweep.
  Kinematics guard_kinematics(const Discrete& d, const State& y, Workspace* ws) const;
  // How the continuous state is laid out, decided by the contacts alone (kinematics.cpp):
  // polar (r, phiS) while the sandbag rides the seesaw with something to carry it, else Cartesian.
  enum class Layout {
    carried_slack,      // a heavy seesaw carries the sandbag, the rope slack
    grounded_carrying,  // the seesaw stands on the floor, the sandbag slides on its fixed arm
    held_by_rope,       // M5: the resting lid holds the seesaw through the rope
    on_rope,            // M4: the lid on the straight rope, the seesaw's angle integrated
    on_rope_by_lid,     // M4 near the lid's dead centre: the lid's angle integrated
    falling_on_seesaw,  // M3 on a massless seesaw: free fall, the seesaw turns with the sandbag
    unloaded_heavy,     // the sandbag off a heavy seesaw, which swings on its own (or on the rope)
    following_lid,      // M2: the unloaded massless seesaw follows the lid on the rope
    parked              // M1: nothing moves the unloaded massless seesaw
  };
  static Layout layout(const Discrete& d);
  // full = false: positions only (Observer::Detail::positions), no rates, forces nor energies.
  Snapshot snapshot(double t, const Discrete& d, const State& y, bool full = true,
                    Workspace* ws = nullptr) const;
  Snapshot snapshot(const HybridState& hs, Workspace* ws = nullptr) const {
    return snapshot(hs.t, hs.d, hs.y, true, ws);
  }
  // A snapshot's positions alone (Observer::Detail::positions), the same bits, for writers that
  // read nothing else: no Snapshot of 50 numbers made and copied per sample.
  Positions positions(double t, const Discrete& d, const State& y) const;
  // The contact problem at this instant: masses, forces, the contacts' gap gradients and
  // curvatures in the coordinates (x, h, phiS, phiL).
  contact::System contact_system(const Discrete& d, const Kinematics& k) const;
  void built_contacts(contact::System& s, const Kinematics& k) const;
  // Forces of the closed contacts in d (arm on sandbag [N], rope tension [N], box on lid [N m]),
  // from the contact problem; false where d's contacts do not determine them (then all zero).
  bool contact_forces(const Discrete& d, const Kinematics& k, contact::PerContact& force) const;
  // The accelerations of (x, h, phiS, phiL) in k (from kinematics() with rates): the motion the
  // flow integrates, from which the contact forces follow (contact::multipliers_for).
  contact::Coords accelerations(const Discrete& d, const Kinematics& k) const;
  // The machine's energy: sandbag, lid and seesaw.
  double energy(const Kinematics& k) const;
  // The balloon's: (1/2) m_B v^2 - m_B a_B h (its net lift as a potential).
  double balloon_energy(double h, double v) const;
  double balloon_energy(const Kinematics& k) const;
  // The height the balloon's centre may reach under the lid (the snapshot's balloon_limit) and its rate.
  double balloon_limit_height(const Kinematics& k) const;
  double balloon_limit_rate(const Kinematics& k) const;
  // The balloon's upward acceleration at speed v (lift, weights and air drag): the flow, the
  // balloon guard and the jumps all use this one function.
  double balloon_acceleration(double v) const { return c_.a_b - c_.drag * v * std::fabs(v); }
  // The lid's angular acceleration while it swings free of the rope and the box, with the hinge's
  // damper and an extra torque q_l (friction, a stretched rope's pull): the flow's.
  double lid_free_acceleration(double phi_l, double dphi_l, double q_l = 0.0) const;
  // A balloon smaller than the box, which slides along the lid and flies in the plane.
  bool small_balloon() const { return c_.small; }

 private:
  // The seesaw's swing (workspace.hpp Swing), from ws's memo where it holds these arguments.
  // q_s, q_l: the slipping pivot's and hinge's Coulomb torques (0 without friction).
  Swing swing(Workspace& ws, bool on, bool taut, double r, double phi_s, double dr, double dphi_s,
              double q_s = 0.0, double q_l = 0.0) const;
  LidSwing swing_by_lid(Workspace& ws, bool on, double r, double phi_l, double dr, double dphi_l, int side,
                        double q_s = 0.0, double q_l = 0.0) const;
  Swing compute_swing(bool on, bool taut, double r, double phi_s, double dr, double dphi_s, double q_s = 0.0,
                      double q_l = 0.0) const;
  LidSwing compute_swing_by_lid(bool on, double r, double phi_l, double dr, double dphi_l, int side,
                                double q_s = 0.0, double q_l = 0.0) const;
  static void lid_chart(Kinematics& k, const LidSwing& p, double phi_l, double dphi_l, bool seesaw_angle);
  struct KinematicsPass;  // kinematics.cpp: one evaluation, stage by stage
  Kinematics kinematics_pass(const Discrete& d, const State& y, bool rates, Workspace* ws,
                             bool seesaw_angle) const;
  // The lid swings on the straight rope, driven through it by something with inertia.
  static bool on_closure(const Discrete& d) {
    return d.taut && !d.lid_held() && !d.latched && (d.on_seesaw || d.heavy) && !d.seesaw_held();
  }
  double lid_free_acceleration_at(double cos_l, double dphi_l, double q_l) const;  // cos phiL known
  // r'' of the sandbag on the arm (eq. 5): gravity along the arm and the centrifugal term.
  double along_arm_acceleration(double r, double sin_s, double dphi_s) const {
    return c_.g * sin_s + r * dphi_s * dphi_s;
  }
  double radio_gap(const Kinematics& k) const;
  // guards() in stages (guards.cpp), called in this order.
  void balloon_guards(const Discrete& d, const State& y, const Kinematics& k, GuardValues& g,
                      GuardValues* rates) const;
  void open_contact_gaps(const Discrete& d, const Kinematics& k, GuardValues& g) const;
  bool closed_forces_wanted(const Discrete& d, int only) const;  // only: as in guards()
  void open_contact_rates(const Discrete& d, const Kinematics& k, const contact::System& sys,
                          GuardValues& rates) const;
  void closed_contact_forces(const Discrete& d, const Kinematics& k, const contact::System& sys,
                             GuardValues& g) const;
  void slip_guards(const Discrete& d, const Kinematics& k, GuardValues& g) const;
  void linkage_guards(const Discrete& d, const Kinematics& k, GuardValues& g, int only) const;
  // A balloon smaller than the box (balloon.cpp, docs/extensions.md).
  struct BalloonForces {
    double lid = 0.0, wall = 0.0;  // the lid's and the wall's (or its corner's) push per unit mass
  };
  BalloonForces small_balloon_forces(const Discrete& d, const Kinematics& k) const;
  Vec2 small_balloon_force(const Kinematics& k) const;  // lift and drag per unit mass
  // The wall that holds it (Discrete::balloon_side): its q limit; false where it does not.
  bool small_balloon_wall(int side, double cos_l, double sin_l, SmallBalloon::Limit& lim) const {
    if (side > 0) return sb_.limit(cos_l, sin_l, lim);
    sb_.hinge(cos_l, sin_l, lim);
    return true;
  }
  double small_balloon_slide(const Kinematics& k) const;  // q'' sliding along the lid
  // psi'' rolling round the lid's free edge E, and the edge's push (per unit mass) there.
  double small_balloon_roll(const Kinematics& k, double psi) const;
  double small_balloon_edge_push(const Kinematics& k, double psi, double dpsi) const;
  void small_balloon_guards(const Discrete& d, const Kinematics& k, GuardValues& g, GuardValues* rates) const;
  void small_balloon_jump(Guard fired, HybridState& hs, const Kinematics& k0, Mode before,
                          std::vector<Event>& out) const;
  void small_balloon_free(HybridState& hs, const Kinematics& k) const;
  void small_balloon_settle(HybridState& hs, Mode before, std::vector<Event>& out) const;
  void small_balloon_after_lid_jump(HybridState& hs, const Kinematics& k0, std::vector<Event>& out) const;
  // The flow's stages: the sandbag on the arm in polar form, or flying in Cartesian form.
  void polar_flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const;
  void cartesian_flow(const Discrete& d, const State& y, State& dy, Workspace& ws) const;
  void dissipation(const Discrete& d, const Kinematics& k, State& dy) const;
  // Coulomb friction (contact_problem.cpp): the slip's tangent in the contact problem, and the
  // sandbag's acceleration along the arm from friction while it slips (the arm's push per unit
  // mass, N/m = g cos phiS - 2 r' phiS' - r phiS'', times mu, against the slip).
  void friction_contacts(const Discrete& d, contact::System& s, const Kinematics& k) const;
  double bag_friction(int slip, double r, double dr, double cos_s, double dphi_s, double ddphi_s) const {
    return -c_.mu * slip * (c_.g * cos_s - 2.0 * dr * dphi_s - r * ddphi_s);
  }
  // The sandbag's height above the arm's line and its distance along it from the pivot.
  static double height_above_arm(const Kinematics& k);
  // Negative while |phiS| < c_.vertical, from cos phiS alone (guard_kinematics has no phiS).
  double seesaw_vertical_gap(const Kinematics& k) const { return c_.cos_vertical - k.cos_s; }
  static double along_arm(const Kinematics& k);

  // Contact changes. How the contact that triggered them tends: touching, letting go (its force
  // vanished) or forced off (the sandbag past the arm's end).
  enum class Trend { closing, releasing, forced_off };
  // Decides the contacts after an event: an impact on velocities if some touching contact is
  // closing, then the contacts that carry the motion on; updates hs and reports the changes.
  void resolve(HybridState& hs, const Kinematics& k_event, int trigger, Trend trend,
               std::vector<Event>& out) const;
  // What the decision's phases hand on to each other (contact_decision.cpp).
  struct Decision {
    int trigger = -1;
    Trend trend = Trend::closing;
    contact::Set s0 = 0;                 // closed before the event
    contact::Set touch = 0;              // touching at the event (closed, or open with zero gap)
    Kinematics k0;                       // the event's state, moved onto the touching contacts
    contact::System sys;                 // the contact problem there
    contact::Choice ch;                  // its preferences and tolerances
    contact::Impact imp;                 // the inelastic impact
    contact::Coords u{};                 // velocities after the impact (by the chosen law)
    contact::PerContact rate{};          // gap rates after it
    bool impacted = false;               // some impulse beyond rounding
    ImpactLaw law = ImpactLaw::rope;     // the law the velocities follow
    std::string_view law_note;           // why that is not the run's impact_law, where it is not
    contact::Set bounced = 0;            // the floor's contacts that gave an impulse and bounced off
    contact::Set held = 0;               // touching with zero gap rate after the impact
    Kinematics k1;                       // the state with the impact's velocities
    contact::Motion mot;                 // the motion on accelerations
    contact::Set s2 = 0;                 // the contacts that carry the motion on
    GuardStart released[kContactCount];  // how each contact's gap opens if it is released
    Kinematics k2;                       // the state the motion goes on from
    // A rope that stretches pulls k s + c s' >= 0: an impact that changes s' so that the pull would
    // be negative lets it go at that instant (its force's side of the complementarity); one that
    // makes a slack rope still longer than l_R pull (k s + c s' > 0) has it pull from that instant.
    bool rope_let_go = false, rope_pulls = false;
    bool impulsive(int i) const {  // friction's impulse may have either sign
      return contact::has(imp.impulsive, i) &&
             (is_friction(i) ? std::fabs(imp.impulse[i]) : imp.impulse[i]) > ch.impulse_tol;
    }
  };
  Decision decide_touching(const Discrete& d, const Kinematics& k_event, int trigger, Trend trend) const;
  void impact_on_velocities(const Discrete& d, Decision& x, double t) const;
  void apply_impact_law(Decision& x) const;
  void hold_after_impact(Decision& x) const;
  bool slip_is_rounding(const Decision& x, int i) const;
  void motion_on_accelerations(const Discrete& d, Decision& x, double t) const;
  void enter_contacts(HybridState& hs, const Decision& x) const;
  void report_changes(HybridState& hs, const Decision& x, Mode before, std::vector<Event>& out) const;
  std::array<double, 6> impulses(const Decision& x) const;
  contact::Set touching(const Discrete& d, const Kinematics& k) const;
  contact::Set touching_built(const Discrete& d, const Kinematics& k) const;
  // d with exactly the contacts of s closed (the rest of d as it was).
  static Discrete with_contacts(Discrete d, contact::Set s);
  void rebound(Decision& x) const;  // restitution on the floor (impact_on_velocities)
  // The positions moved onto the touching contacts (their gaps exactly zero), velocities kept.
  Kinematics touch_exactly(const Discrete& d, contact::Set touch, Kinematics k) const;
  contact::Choice choice(const Discrete& d, const contact::System& sys, const Kinematics& k, int trigger,
                         Trend trend) const;
  // The chosen impact law's velocities for a rope impulse (docs/model.md §7); false where they are
  // not finite (then the perfectly inelastic ones stand).
  // note: set where the law itself falls back to the rope law.
  bool law_velocity(const Kinematics& k, bool bag, contact::Coords& u,
                    std::string_view* note = nullptr) const;
  void set_contacts(Discrete& d, contact::Set s, const Kinematics& k) const;
  // The slips' signs the contact problem decided, where friction acts on something that moves.
  void take_slips(Discrete& d, const std::array<int, contact::kMaxContacts>& slip) const;
  static contact::Set active_set(const Discrete& d);
  // Writes the continuous state for hs.d's layout from full kinematics.
  void place(HybridState& hs, const Kinematics& k) const;
  static Kinematics with_velocity(Kinematics k, const contact::Coords& u);
  Event make_event(EventType type, HybridState& hs, Mode before, Mode after) const;
  // initial() in stages (jumps.cpp): what touches at rest at t = 0 (k: the start's positions), how
  // the guards of what touches but lets go open, and those let-gos as events at t = 0.
  contact::Set start_touching(const Discrete& d, Kinematics& k) const;
  void arm_start_releases(Discrete& d, contact::Set touch, const contact::Motion& mot,
                          double accel_tol) const;
  void report_start_releases(HybridState& hs, contact::Set touch, contact::Set active,
                             std::vector<Event>& out) const;
  // jump_contacts() for the guards that change no contact: the balloon's, the chart's, the ends'.
  bool jump_without_contacts(Guard fired, HybridState& hs, const Kinematics& k0, double limit_rate0,
                             Mode before, std::vector<Event>& out) const;
  void release_balloon_if_lid_jumped(HybridState& hs, const Kinematics& k0, double limit_rate_before,
                                     const Books& opened, std::vector<Event>& out) const;
  void free_balloon(HybridState& hs, const Kinematics& k, double v) const;
  // The balloon guard fired: a stuck balloon left behind, or a free one caught by the lid.
  void balloon_meets_lid(HybridState& hs, const Kinematics& k0, double limit_rate0, Mode before,
                         std::vector<Event>& out) const;
  // lid_open with the radio on: the lid latches open and the story goes on with the balloon.
  void latch_open(HybridState& hs, const Kinematics& k0, double limit_rate0, Mode before,
                  std::vector<Event>& out) const;
  // Ledger: fold the continuous phase into the books, then book what a jump changed.
  void open_books(HybridState& hs, const Kinematics& k) const;
  void book(HybridState& hs, Workspace* ws = nullptr) const;
  double lid_push_now(const Discrete& d, const Kinematics& k, const State& y) const;

  Scenario sc_;
  const Constants c_;  // constants.hpp: every number the model reads, taken once
  RopeGeometry rope_;
  BalloonLimit limit_;
  SmallBalloon sb_;
  // The Coulomb torques of a slipping pivot and hinge, against their slip (docs/extensions.md).
  double pivot_coulomb(const Discrete& d) const { return -c_.t_p * d.seesaw_slip; }
  // The most a sticking pivot (i = kPivotSlip) or hinge (kHingeSlip) holds: its Coulomb torque and,
  // while the taut rope couples the two and the other is free to turn, the other's through the
  // linkage's k (phiL' = k phiS'): T_p + |k| T_h, or T_h + T_p / |k| (docs/extensions.md).
  double coulomb_hold(const Discrete& d, const Kinematics& k, int i) const;
  double hinge_coulomb(const Discrete& d) const { return -c_.t_h * d.lid_slip; }
  double grounded_angle(int side) const { return side > 0 ? c_.grounded_left : c_.grounded_right; }
  void ground(Kinematics& k, int side, bool carries) const;

  // A rope that stretches (stretchy_rope.cpp, docs/impact.md): a one-sided spring-damper instead of
  // the rope's contact while the sandbag rides the massless seesaw; its pull is a generalised force.
  struct RopePull {
    double stretch = 0, rate = 0, tension = 0;  // span - l_R [m], its rate [m/s], the pull [N]
    double q_s = 0, q_l = 0;                    // the pull's torques on the seesaw and the lid [N m]
  };
  // A seesaw with inertia stretches the rope whatever it carries; the massless one only with the
  // sandbag on it (docs/impact.md).
  bool spring_rope(const Discrete& d) const { return c_.stretchy && !d.latched && (d.on_seesaw || c_.heavy); }
  RopePull rope_pull(const Discrete& d, const Kinematics& k) const;
  // Slack but still longer than l_R after a jump (Discrete::rope_relaxing).
  bool relaxing(const HybridState& hs) const;
  // The stretched rope's pull on a seesaw with inertia that it turns (zero otherwise), from the
  // angles and rates alone: its torques join the swings' like the Coulomb torques.
  RopePull heavy_pull(const Discrete& d, double phi_s, double dphi_s, double phi_l, double dphi_l) const;
  // What the swings add to the weights' and dampers' torques on the seesaw and the lid: the
  // slipping pivot's and hinge's Coulomb torques and a stretched rope's pull on a seesaw with
  // inertia (both zero on the paper's machine). One place for the flows and the kinematics.
  struct Torques {
    double seesaw = 0.0, lid = 0.0;
  };
  Torques extra_torques(const Discrete& d, double phi_s, double dphi_s, double phi_l, double dphi_l) const {
    Torques t;
    if (!c_.friction && !c_.pulls_heavy) return t;
    const RopePull rope = c_.pulls_heavy ? heavy_pull(d, phi_s, dphi_s, phi_l, dphi_l) : RopePull{};
    t.seesaw = pivot_coulomb(d) + rope.q_s, t.lid = hinge_coulomb(d) + rope.q_l;
    return t;
  }
  double rope_energy(const Kinematics& k) const;
  void stretchy_flow(const Discrete& d, const State& y, State& dy, Workspace* ws) const;
  void stretchy_kinematics(const Discrete& d, Kinematics& k) const;
  void stretchy_accelerations(const Discrete& d, const Kinematics& k, contact::Coords& a) const;
  void stretchy_force(const Discrete& d, const Kinematics& k, contact::System& s) const;
  double lid_lift(const Kinematics& k, const RopePull& p) const;  // minus the box's push on the lid
  void stretchy_guards(const Discrete& d, const Kinematics& k, GuardValues& g, GuardValues* rates) const;
  bool stretchy_jump(Guard fired, HybridState& hs, const Kinematics& k0, Mode before,
                     std::vector<Event>& out) const;
  // The sandbag has left the massless seesaw with the rope longer than l_R: the rope takes the
  // unloaded seesaw back to l_R at once, an impact that takes the spring's energy.
  void stretched_rope_left(HybridState& hs, std::vector<Event>& out) const;
  static void stretchy_modes(bool was_stretched, const Discrete& d, std::vector<Event>& out,
                             std::size_t first);
  void stretchy_snapshot(const Discrete& d, const Kinematics& k, const State& y, Snapshot& s) const;
};

}  // namespace whatnext
