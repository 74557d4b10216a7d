// A rope that stretches (docs/impact.md): a one-sided spring-damper in place of the rope's contact.
//
// While the sandbag rides the paper's massless seesaw the rope is no contact of the contact problem:
// once longer than l_R it pulls with
//     T = k (span - l_R) + c span'
// until that reaches zero (rope_slack): it never pushes (a rope buckles). The pull acts as a
// generalised force Q = -T d span/dq on phiS and phiL. The seesaw has no inertia, so the arm's push on the
// sandbag balances the rope's torque, N r = -Q_S: the seesaw and sandbag swing as a point mass m_S r^2
// (docs/extensions.md's J with I_S = 0). "Stretched" is a discrete flag, set and cleared by guards (rope_taut
// where the span passes l_R, rope_slack where the pull reaches zero), no impact: every smooth piece has a
// smooth force (with damping T jumps to c span' at the taut instant).
//
// Energy: the spring's (1/2) k (span - l_R)^2 counts in the machine's energy; what the rope turns
// into heat, (T - k s) s' with s = span - l_R > 0, is integrated in slot::lost_rope. With the
// damper pulling that is c s'^2; slack while still longer than l_R (the damper would have had to
// push), the spring's energy given up without work, -k s s' > 0: the law never gains energy.
//
// A seesaw with mass carries the pull itself, loaded or not: the pull's torque joins its equation.
// The unloaded massless seesaw cannot stretch the rope (nothing on it has inertia): there the rope
// stays the inextensible contact, which carries no force on it (it follows the lid, M2, as before).
#include <cmath>
#include <limits>

#include "model.hpp"
#include "model_internal.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext {

using namespace model_detail;

Model::RopePull Model::rope_pull(const Discrete& d, const Kinematics& k) const {
  RopePull p;
  const double rh = sc_.machine.seesaw_right_arm, knot = sc_.machine.rope_knot();
  const Vec2 r{rh * k.cos_s, rh * k.sin_s}, el{knot * k.cos_l, knot * k.sin_l};
  const Vec2 dv = r - (rope_.hinge() + el);  // D = R - E
  const double span = norm(dv);
  if (!(span > 0.0)) return p;
  const Vec2 r_s{-r.h, r.x}, e_l{-el.h, el.x};                       // dR/dphiS, dE/dphiL
  const double ds = dot(dv, r_s) / span, dl = -dot(dv, e_l) / span;  // d span / d phiS, d phiL
  p.stretch = span - rope_.rope_length();
  p.rate = ds * k.dphi_s + dl * k.dphi_l;
  // No clamp at zero inside the piece: the guard ends the pull where it reaches zero, so the flow
  // stays smooth (the stiff integrator's Jacobian sees the spring, not a corner).
  if (d.stretched) p.tension = c_.k_rope * p.stretch + c_.c_rope * p.rate;
  p.q_s = -p.tension * ds;
  p.q_l = -p.tension * dl;
  return p;
}

Model::RopePull Model::heavy_pull(const Discrete& d, double phi_s, double dphi_s, double phi_l,
                                  double dphi_l) const {
  if (!c_.stretchy || !c_.heavy || !d.stretched || !spring_rope(d)) return {};
  Kinematics k;
  k.cos_s = std::cos(phi_s), k.sin_s = std::sin(phi_s), k.cos_l = std::cos(phi_l), k.sin_l = std::sin(phi_l);
  // A seesaw held (on the floor, or by its pivot's friction) still has the rope pull the lid: what
  // the seesaw's end gives is the floor's or the pivot's, and the heat is the damper's on that pull.
  k.dphi_s = d.seesaw_held() ? 0.0 : dphi_s;
  k.dphi_l = d.lid_resting ? 0.0 : dphi_l;
  RopePull p = rope_pull(d, k);
  if (d.lid_resting) p.q_l = 0.0;  // the box holds the lid (its lifting is a guard)
  return p;
}

bool Model::relaxing(const HybridState& hs) const {
  // Beyond its guard's rounding band only: a rope let go within it has no corner left worth a piece.
  if (!spring_rope(hs.d) || hs.d.stretched) return false;
  return rope_pull(hs.d, kinematics(hs.d, hs.y, false)).stretch > guard_floor(kGuardRopeRelaxed, hs.d);
}

double Model::rope_energy(const Kinematics& k) const {
  if (k.rope_let_go) return 0.0;  // what it held was booked at the latch (an impact's loss)
  const double s = rope_.span(Vec2{k.cos_s, k.sin_s}, Vec2{k.cos_l, k.sin_l}) - rope_.rope_length();
  return s > 0.0 ? 0.5 * c_.k_rope * s * s : 0.0;
}

void Model::stretchy_flow(const Discrete& d, const State& y, State& dy, Workspace* ws) const {
  if (!spring_rope(d)) return;
  const Kinematics k = kinematics(d, y, true, ws);
  const RopePull p = rope_pull(d, k);
  // Slack but still longer than l_R (it let go where its damper would have pushed), the spring's
  // energy goes as the span shrinks: booked as lost (-k s s').
  dy[slot::lost_rope] = (p.tension - c_.k_rope * std::fmax(p.stretch, 0.0)) * p.rate;
  if (!d.stretched) return;
  // A seesaw with inertia: the pull's torques are in its and the lid's swings already (heavy_pull).
  if (c_.heavy) return;
  if (k.r > 0.0) {
    // The sandbag in Cartesian free fall (M3) on the massless seesaw, pushed by the arm with
    // N = -Q_S / r along the arm's normal (-sin phiS, cos phiS).
    const double push = -p.q_s / (k.r * c_.m_s);
    dy[slot::vx] += -push * k.sin_s;
    dy[slot::vh] += push * k.cos_s;
  }
  if (!d.lid_resting) dy[slot::dphi_l] += p.q_l / c_.i_l;
}

void Model::stretchy_kinematics(const Discrete& d, Kinematics& k) const {
  if (!spring_rope(d)) return;
  const RopePull p = rope_pull(d, k);
  if (c_.heavy) return;  // in the swings already (heavy_pull)
  if (k.r > 0.0) {
    // phiS = atan2(-h, -x): the arm's push adds -N / (m r) = Q_S / (m r^2) to the free fall's phiS''.
    k.ddphi_s += p.q_s / (c_.m_s * k.r * k.r);
  }
  if (!d.lid_resting) k.ddphi_l += p.q_l / c_.i_l;
}

void Model::stretchy_accelerations(const Discrete& d, const Kinematics& k, contact::Coords& a) const {
  if (c_.heavy || !spring_rope(d) || !(k.r > 0.0)) return;  // the heavy seesaw's are in k already
  const double push = -rope_pull(d, k).q_s / (k.r * c_.m_s);
  a[0] += -push * k.sin_s;
  a[1] += push * k.cos_s;
}

void Model::stretchy_force(const Discrete& d, const Kinematics& k, contact::System& s) const {
  // The contact problem sees the pull as a force like gravity: a decision at an event (the lid
  // lifting, the arm's push) is made with it.
  if (!spring_rope(d)) return;
  const RopePull p = rope_pull(d, k);
  s.force[2] += p.q_s;
  s.force[3] += p.q_l;
}

void Model::stretchy_guards(const Discrete& d, const Kinematics& k, GuardValues& g,
                            GuardValues* rates) const {
  if (!spring_rope(d)) return;
  // The rope pulls while k s + c s' > 0 with s = span - l_R: both its ends as guards, in metres
  // (divided by k). Pulling, it goes slack when that pull reaches zero (s = 0 without damping, s > 0
  // with it: the damper would have to push). Slack, it pulls again when s >= 0 and the pull would
  // be positive: min(s, s + (c/k) s') crosses zero (at s = 0 on an ordinary tightening, where s'
  // > 0; before s = 0 returns, if the ends are driven apart while still stretched).
  const RopePull p = rope_pull(d, k);
  const double tau = c_.c_rope / c_.k_rope, pull = p.stretch + tau * p.rate;
  if (d.stretched) {
    g[kGuardRope] = -pull;
    if (rates) (*rates)[kGuardRope] = c_.c_rope > 0.0 ? std::numeric_limits<double>::quiet_NaN() : -p.rate;
  } else {
    g[kGuardRope] = std::fmin(p.stretch, pull);
    if (rates) (*rates)[kGuardRope] = p.rate >= 0.0 ? p.rate : std::numeric_limits<double>::quiet_NaN();
    if (d.rope_relaxing) g[kGuardRopeRelaxed] = -p.stretch;
    return;
  }
  // The box lets the lid go when the pull's torque outweighs the lid.
  if (d.lid_resting) g[kGuardLid] = lid_lift(k, p);
  // The arm pushes the sandbag with N = T (d span/d phiS) / r: it would have to pull where the
  // linkage's k turns negative (the massless seesaw then cannot hold the rope).
  const double rh = sc_.machine.seesaw_right_arm, knot = sc_.machine.rope_knot();
  const Vec2 r{rh * k.cos_s, rh * k.sin_s};
  const Vec2 dv = r - (rope_.hinge() + Vec2{knot * k.cos_l, knot * k.sin_l});
  // (A seesaw with inertia carries the pull itself: its arm's push is the contact problem's.)
  if (p.tension > 0.0 && !c_.heavy) g[kGuardBag] = -dot(dv, Vec2{-r.h, r.x});
}

double Model::lid_lift(const Kinematics& k, const RopePull& p) const {
  return p.q_l - c_.m_l * c_.g * c_.r_l * k.cos_l;
}

bool Model::stretchy_jump(Guard fired, HybridState& hs, const Kinematics& k0, Mode before,
                          std::vector<Event>& out) const {
  if (fired == kGuardBag) {
    throw SimulationError(
        "the stretched rope would pull the sandbag off the massless seesaw (the linkage's k < 0), which the "
        "model of a rope that stretches does not cover (docs/impact.md)");
  }
  // The rope starts or stops pulling. No impact, nothing jumps.
  Discrete& d = hs.d;
  d.stretched = !d.stretched;
  out.push_back(make_event(d.stretched ? EventType::rope_taut : EventType::rope_slack, hs, before, d.mode()));
  if (d.stretched && c_.c_rope > 0.0 && (d.lid_resting || (c_.heavy && d.on_seesaw))) {
    // A damped rope pulls c s' at once: the contacts it loads or unloads (the lid on the box, the
    // sandbag on a seesaw with inertia, friction's sticking) are decided now with it, as after an
    // impact (nothing changes where all of them still hold).
    resolve(hs, kinematics(d, hs.y), d.lid_resting ? kLid : kBag, Trend::releasing, out);
  }
  // The guard starts at zero and turns negative (without damping at the span's rate).
  const RopePull p = rope_pull(d, k0);
  const double lead = c_.c_rope > 0.0 ? 0.0 : -std::fabs(p.rate);
  d.armed[kGuardRope] = lead < 0.0 ? GuardStart{1, lead} : GuardStart{1, kUnknownLead};
  d.armed[kGuardRope].floor = guard_floor(kGuardRope, d);
  return false;
}

void Model::stretched_rope_left(HybridState& hs, std::vector<Event>& out) const {
  // Nothing with inertia holds the unloaded massless seesaw's end (a seesaw with mass carries the
  // spring itself): when the sandbag leaves it (off the arm's end, or lifting off) with the rope
  // longer than l_R, the spring pulls the seesaw back to l_R in no time. The rope is then the
  // inextensible contact again, and its closing is an impact (rope_taut, with its energy before
  // and after) whose loss is the spring's (1/2) k s^2: the contact problem decides whether the
  // rope holds the seesaw to the lid after it.
  Discrete& d = hs.d;
  if (c_.heavy || d.latched) return;
  if (d.on_seesaw && spring_rope(d) && !d.stretched) {
    // The sandbag has landed on a seesaw that followed the lid (the rope at l_R): where the arm now
    // drives the rope's ends apart the spring pulls from this instant, not a moment later (a rope
    // longer than l_R that does not pull would store energy that nothing gave it).
    const Kinematics k = kinematics(d, hs.y);
    const RopePull p = rope_pull(d, k);
    if (p.rate > 0.0 && p.stretch >= 0.0 && p.stretch <= kContact)
      stretchy_jump(kGuardRope, hs, k, d.mode(), out);
    return;
  }
  if (d.on_seesaw || d.taut) return;
  const Kinematics k = kinematics(d, hs.y);
  if (!(rope_.span(k.phi_s, k.phi_l) > rope_.rope_length())) return;
  // The seesaw turns to where the rope is l_R long, the lid stays: the lid has inertia.
  d.stretched = false;
  d.side = RopeGeometry::side_of(rope_.lid_edge(k.phi_l), rope_.seesaw_end(k.phi_s));
  double phi_s = k.phi_s;
  if (!rope_.seesaw_angle_for(k.phi_l, d.side, phi_s)) return;
  d.parked_seesaw = phi_s;
  const std::size_t first = out.size();
  resolve(hs, kinematics(d, hs.y), kRope, Trend::closing, out);
  if (out.size() == first || out[first].type != EventType::rope_taut || !d.taut) {
    throw SimulationError(
        "the rope let go of the unloaded massless seesaw while longer than l_R, which the "
        "model of a rope that stretches does not cover (docs/impact.md)");
  }
  // No velocity jumps (the seesaw has no inertia, the lid feels no impulse): the positions do.
  Event& e = out[first];
  e.impact = true;
  e.energy_before = energy(k);
  e.impulse = {};
  e.law = ImpactLaw::rope;
}

void Model::stretchy_modes(bool was_stretched, const Discrete& d, std::vector<Event>& out,
                           std::size_t first) {
  // While the spring pulls, M3 (on the arm, the rope's contact open) is M4 or M5: the lid's contact
  // after each event follows from the events in order, and the pull from rope_taut and rope_slack.
  // (Off the seesaw, M1 is M2: a seesaw with inertia stretches the rope whatever it carries.)
  if (!(was_stretched || d.stretched)) return;
  auto named = [](Mode m, bool resting) {
    return m == Mode::M3 ? (resting ? Mode::M5 : Mode::M4) : (m == Mode::M1 ? Mode::M2 : m);
  };
  bool pulls = was_stretched;
  for (std::size_t i = first; i < out.size(); ++i) {
    Event& e = out[i];
    const bool rests_before =
        e.mode_before == Mode::M5 || (i > first ? out[i - 1].mode_after == Mode::M5 : false);
    const bool rests_after =
        e.type == EventType::lid_rests || (e.type != EventType::lid_lifts && rests_before);
    const bool pulls_after =
        e.type == EventType::rope_taut ? true : (e.type == EventType::rope_slack ? false : pulls);
    if (pulls) e.mode_before = named(e.mode_before, rests_before);
    if (pulls_after) e.mode_after = named(e.mode_after, rests_after);
    pulls = pulls_after;
  }
}

void Model::stretchy_snapshot(const Discrete& d, const Kinematics& k, const State& y, Snapshot& s) const {
  s.rope_taut = d.taut || d.stretched;
  s.rope_potential = rope_energy(k);
  s.dissipated_rope = y[slot::lost_rope];
  if (spring_rope(d)) {
    // At the slack the pull is zero within rounding: written as zero. A pull below that would be
    // a rope that pushes, and is shown as it is.
    const double t = rope_pull(d, k).tension,
                 rounding = 1e-10 * (c_.m_s + c_.m_l + sc_.machine.seesaw_mass) * c_.g;
    s.tension = t < 0.0 && t >= -rounding ? 0.0 : t;
  }
}

}  // namespace whatnext
