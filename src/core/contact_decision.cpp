// The contact decision at an event: which contacts touch, the impact on velocities, the motion on
// accelerations, and the report of what changed.
#include "model.hpp"

#include <cmath>
#include <cstdio>

#include "model_internal.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext {

using namespace model_detail;

// --- contact changes ---------------------------------------------------------------------------

contact::Set Model::touching(const Discrete& d, const Kinematics& k) const {
  // Open contacts whose gap is (numerically) closed as well: they take part in the decision.
  Set s = 0;
  if (d.latched && !c_.built) return s;
  if (!d.on_seesaw && !d.fallen_off && !d.bag_on_floor) {
    const double along = along_arm(k);
    if (std::fabs(height_above_arm(k)) <= kContact && along >= 0.0 && along <= c_.arm) s |= bit(kBag);
  }
  if (d.latched) return s | touching_built(d, k);  // the rope let go for good, the lid held open
  if (!d.taut && !spring_rope(d) &&
      std::fabs(rope_.span(k.phi_s, k.phi_l) - rope_.rope_length()) <= kContact &&
      rope_.lid_below_rope(k.phi_s, k.phi_l)) {
    s |= bit(kRope);
  }
  if (!d.lid_resting && k.phi_l - c_.phi_l0 <= kContact) s |= bit(kLid);
  if (c_.contacts > 3) s |= touching_built(d, k);
  return s;
}

contact::Set Model::touching_built(const Discrete& d, const Kinematics& k) const {
  Set s = 0;
  if (c_.stop && d.on_seesaw && !d.at_stop && std::fabs(c_.arm - along_arm(k)) <= kContact) s |= bit(kStop);
  if (!c_.floor) return s;
  if (d.grounded <= 0 && std::fabs(-c_.arm * k.sin_s - c_.h_floor) <= kContact) s |= bit(kFloorLeft);
  const double right = sc_.machine.seesaw_right_arm;
  if (d.grounded >= 0 && std::fabs(right * k.sin_s - c_.h_floor) <= kContact) s |= bit(kFloorRight);
  if (!d.on_seesaw && !d.bag_on_floor && std::fabs(k.h - c_.h_floor) <= kContact) s |= bit(kBagFloor);
  return s;
}

contact::Choice Model::choice(const Discrete& d, const contact::System& sys, const Kinematics& k, int trigger,
                              Trend trend) const {
  contact::Choice c;
  // Where the physics leaves a choice (only a massless seesaw does: contacts with zero force
  // either way), each contact stays as it was, the one that triggered the event goes the way it
  // tends, and a sandbag on a massless seesaw stays on it (docs/model.md §4: once landed, it stays; with
  // the rope slack that seesaw simply turns with the falling sandbag).
  const Set s0 = active_set(d);
  for (int i = 0; i < c_.contacts; ++i) {
    c.want[i] = contact::has(s0, i) ? 1 : -1;
    c.weight[i] = 1;
  }
  if (trigger >= 0 && trend != Trend::forced_off) {
    c.want[trigger] = trend == Trend::closing ? 1 : -1;
    c.weight[trigger] = 8;
  }
  if (!c_.heavy) {
    c.want[kBag] = 1;
    c.weight[kBag] = 16;
  }
  c.needs[kStop] = bit(kBag);     // the stop is an edge of the arm
  c.needs[kBagSlip] = bit(kBag);  // friction acts only while the arm pushes
  // "Zero" on the scale of this machine and motion.
  const double len = c_.length_scale;
  double v = std::sqrt(c_.g * len);
  v = std::fmax(v, std::fmax(std::fabs(k.vx), std::fabs(k.vh)));
  v = std::fmax(v, len * std::fmax(std::fabs(k.dphi_s), std::fabs(k.dphi_l)));
  const double mass = c_.m_s + c_.m_l + sc_.machine.seesaw_mass;
  const double acc = c_.g + v * v / len;
  c.force_tol = 1e-9 * mass * acc * (1.0 + len);
  c.impulse_tol = 1e-9 * mass * v * (1.0 + len);
  // A contact that would separate slower than a millionth of the machine's speed is held: the
  // end of an inelastic cascade (rope jerks the lid a hair off the box, the lid drops back, the
  // seesaw lets the rope go, ...) whose gaps never open beyond rounding. Without it such a Zeno
  // cascade never reaches its limit, where both contacts hold (docs/model.md §7: impacts are inelastic).
  c.rate_tol = 1e-6 * v;
  c.closing_tol = 1e-12 * v;
  c.accel_tol = 1e-9 * acc;
  // Below every friction guard's band: the sandbag's (N) and the torques' (N m).
  c.friction_tol = 1e-11 * mass * c_.g * std::fmin(1.0, len);
  (void)sys;
  return c;
}

Kinematics Model::touch_exactly(const Discrete& d, contact::Set touch, Kinematics k) const {
  using contact::has;
  const bool resting = has(touch, kLid);
  if (resting && k.phi_l < c_.phi_l0) k.phi_l = c_.phi_l0;
  k.cos_l = std::cos(k.phi_l), k.sin_l = std::sin(k.phi_l);
  if (has(touch, kRope) && std::fabs(rope_.span(k.phi_s, k.phi_l) - rope_.rope_length()) > 0.0) {
    double phi = 0.0;
    if (!resting) {  // the lid moves onto the straight rope
      if (rope_.lid_angle_for(k.phi_s, phi) && rope_.lid_below_rope(k.phi_s, phi) &&
          std::fabs(phi - k.phi_l) < 1e-3) {
        k.phi_l = phi;
        k.cos_l = std::cos(phi), k.sin_l = std::sin(phi);
      }
    } else if (rope_.seesaw_angle_for(
                   k.phi_l, RopeGeometry::side_of(rope_.lid_edge(k.phi_l), rope_.seesaw_end(k.phi_s)), phi) &&
               std::fabs(phi - k.phi_s) < 1e-3) {
      // The lid rests: the seesaw turns onto the straight rope, a massless one with the sandbag
      // it carries (turned about the pivot with it).
      if (!d.heavy && d.on_seesaw) {
        const double c = std::cos(phi - k.phi_s), s = std::sin(phi - k.phi_s);
        const double x = k.x * c - k.h * s, h = k.x * s + k.h * c;
        const double vx = k.vx * c - k.vh * s, vh = k.vx * s + k.vh * c;
        k.x = x, k.h = h, k.vx = vx, k.vh = vh;
      }
      k.phi_s = phi;
    }
  }
  k.cos_s = std::cos(k.phi_s), k.sin_s = std::sin(k.phi_s);
  const bool carries = has(touch, kBag) || d.on_seesaw;
  if (has(touch, kFloorLeft)) ground(k, 1, carries);
  if (has(touch, kFloorRight)) ground(k, -1, carries);
  if (has(touch, kBag)) {
    // The sandbag onto the arm's line, along its normal.
    const double above = height_above_arm(k);
    if (std::fabs(above) < 1e-3) k.x += above * k.sin_s, k.h -= above * k.cos_s;
  }
  if (has(touch, kStop)) k.x = -c_.arm * k.cos_s, k.h = -c_.arm * k.sin_s;  // at the arm's end
  if (has(touch, kBagFloor)) k.h = c_.h_floor;
  k.r = along_arm(k);
  return k;
}

void Model::ground(Kinematics& k, int side, bool carries) const {
  // The seesaw turned onto the floor (a rounding's worth), with the sandbag it carries.
  const double phi = grounded_angle(side);
  if (carries) {
    const double c = std::cos(phi - k.phi_s), s = std::sin(phi - k.phi_s);
    const double x = k.x * c - k.h * s, h = k.x * s + k.h * c;
    const double vx = k.vx * c - k.vh * s, vh = k.vx * s + k.vh * c;
    k.x = x, k.h = h, k.vx = vx, k.vh = vh;
  }
  k.phi_s = phi;
  k.cos_s = std::cos(phi), k.sin_s = std::sin(phi);
}

Discrete Model::with_contacts(Discrete d, Set s) {
  d.on_seesaw = contact::has(s, kBag);
  d.taut = contact::has(s, kRope);
  d.lid_resting = contact::has(s, kLid);
  d.at_stop = contact::has(s, kStop) && d.on_seesaw;  // the stop is an edge of the arm
  d.grounded = contact::has(s, kFloorLeft) ? 1 : (contact::has(s, kFloorRight) ? -1 : 0);
  d.bag_on_floor = contact::has(s, kBagFloor);
  d.bag_stuck = contact::has(s, kBagSlip) && d.on_seesaw;
  if (!d.on_seesaw || d.bag_stuck) d.bag_slip = 0;
  d.seesaw_stuck = contact::has(s, kPivotSlip) && d.grounded == 0;
  if (d.seesaw_held()) d.seesaw_slip = 0;
  d.lid_stuck = contact::has(s, kHingeSlip) && !d.lid_resting;
  if (d.lid_held()) d.lid_slip = 0;
  return d;
}

void Model::take_slips(Discrete& d, const std::array<int, contact::kMaxContacts>& slip) const {
  d.bag_slip = c_.mu > 0.0 && d.on_seesaw && !d.bag_stuck ? slip[kBagSlip] : 0;
  d.seesaw_slip = c_.t_p > 0.0 && !d.seesaw_held() ? slip[kPivotSlip] : 0;
  d.lid_slip = c_.t_h > 0.0 && !d.lid_held() && !d.latched ? slip[kHingeSlip] : 0;
}

void Model::set_contacts(Discrete& d, Set s, const Kinematics& k) const {
  d = with_contacts(d, s);
  // The unloaded massless seesaw is parked where it is, or follows the lid; on the closure the
  // chart is the seesaw's angle while the lid moves no faster than it (|k| <= 1).
  if (!d.on_seesaw && !d.heavy) d.parked_seesaw = k.phi_s;
  d.side = RopeGeometry::side_of(rope_.lid_edge(k.phi_l), rope_.seesaw_end(k.phi_s));
  d.lid_chart = on_closure(d) && std::fabs(rope_.transfer(k.phi_s, k.phi_l).k) > 1.0;
}

namespace {
[[noreturn]] void no_consistent(const char* what, double t, Mode mode) {
  char msg[200];
  std::snprintf(msg, sizeof msg, "no consistent %s at t = %.9g s in mode M%d (degenerate contact)", what, t,
                static_cast<int>(mode));
  throw SimulationError(msg);
}
}  // namespace

// The contact decision in its phases (Pfeiffer & Glocker's event-driven method, docs/model.md
// "Contacts"): which contacts touch, the impact on velocities, the impact law, which contacts
// hold after it, the motion on accelerations, then the new state with its released contacts
// armed, and the report of every change.
void Model::resolve(HybridState& hs, const Kinematics& k_event, int trigger, Trend trend,
                    std::vector<Event>& out) const {
  Decision x = decide_touching(hs.d, k_event, trigger, trend);
  impact_on_velocities(hs.d, x, hs.t);
  apply_impact_law(x);
  hold_after_impact(x);
  motion_on_accelerations(hs.d, x, hs.t);
  const Mode before = hs.d.mode();
  enter_contacts(hs, x);
  report_changes(hs, x, before, out);
}

Model::Decision Model::decide_touching(const Discrete& d, const Kinematics& k_event, int trigger,
                                       Trend trend) const {
  Decision x;
  x.trigger = trigger;
  x.trend = trend;
  x.s0 = active_set(d);
  x.touch = x.s0 | touching(d, k_event);
  if (trend == Trend::closing) x.touch |= bit(trigger);
  // A rope that stretches is a spring, not a contact, once the sandbag rides the seesaw: a landing
  // takes no impulse through it (docs/impact.md).
  if (c_.stretchy && trigger == kBag && trend == Trend::closing) x.touch &= ~bit(kRope);
  if (trend == Trend::forced_off) {
    x.touch &= ~bit(trigger);
    // Off the end of an arm that stands on the floor: the sandbag is on the floor at once.
    if (c_.floor && std::fabs(k_event.h - c_.h_floor) <= kContact) x.touch |= bit(kBagFloor);
  }
  // Wherever the arm may push the sandbag, friction takes part: it sticks or slips; so do the
  // pivot's and the hinge's Coulomb torques.
  if (c_.mu > 0.0 && contact::has(x.touch, kBag)) x.touch |= bit(kBagSlip);
  if (c_.t_p > 0.0) x.touch |= bit(kPivotSlip);
  if (c_.t_h > 0.0 && !d.latched) x.touch |= bit(kHingeSlip);
  // The touching contacts are at zero gap by definition: take back the event's overshoot (the
  // event-time tolerance times the closing speed, or a fixed step's interpolation error) before
  // anything is decided, so that the impact happens where the contacts touch and a contact that
  // lets go again starts from exactly zero.
  x.k0 = touch_exactly(d, x.touch, k_event);
  return x;
}

void Model::impact_on_velocities(const Discrete& d, Decision& x, double t) const {
  // An impact wherever a touching contact is closing: perfectly inelastic (the rope law, eq. 7).
  using contact::has;
  x.sys = contact_system(d, x.k0);
  x.ch = choice(d, x.sys, x.k0, x.trigger, x.trend);
  x.imp = contact::solve_impact(x.sys, x.touch, x.ch);
  if (!x.imp.ok) no_consistent("impact", t, d.mode());
  x.u = x.imp.velocity;
  x.rate = x.imp.rate;
  if (c_.restitution) rebound(x);
  x.impacted = false;
  for (int i = 0; i < c_.contacts; ++i) x.impacted = x.impacted || x.impulsive(i);
}

void Model::rebound(Decision& x) const {
  // Newton's restitution, as event-driven methods have it: a contact that takes an impulse leaves
  // with -e times the gap rate it came with (e per contact: docs/extensions.md), the others do not
  // close; the same complementarity problem as the inelastic impact, with those rates as targets.
  contact::PerContact after{};
  bool any = false;
  for (int i = 0; i < c_.contacts; ++i) {
    if (!x.impulsive(i) || !(c_.e[i] > 0.0)) continue;
    const double came = x.sys.rate(i, x.sys.velocity);
    if (came < 0.0) after[i] = -c_.e[i] * came, any = true;
  }
  if (!any) return;
  const contact::Impact bounce = contact::solve_impact(x.sys, x.touch, x.ch, &after);
  if (!bounce.ok) return;  // then the inelastic impact stands
  // Restitution at several contacts at once can come out with more kinetic energy than the
  // machine brought in: then the inelastic impact stands (an impact never gains energy).
  auto kinetic = [&](const contact::Coords& v) {
    double e = 0.0;
    for (int j = 0; j < x.sys.coords; ++j) e += 0.5 * x.sys.mass[j] * v[j] * v[j];
    return e;
  };
  // (Beyond rounding: a perfectly elastic rebound, e = 1, keeps the energy to the last bits.)
  const double before = kinetic(x.sys.velocity);
  if (kinetic(bounce.velocity) > before + 1e-12 * before) return;
  // A contact that bounced took an impulse but is not held (unless its rebound is rounding).
  for (int i = 0; i < c_.contacts; ++i) {
    const double speed = i == kLid ? 2.0 * c_.r_l * after[i] : after[i];
    if (contact::has(bounce.impulsive, i) && speed > x.ch.rate_tol) x.bounced |= bit(i);
  }
  x.imp = bounce;
  x.u = bounce.velocity;
  x.rate = bounce.rate;
}

void Model::apply_impact_law(Decision& x) const {
  // The rope's jerk by the chosen law (the inelastic solution is the rope law, eq. 7), provided
  // nothing else it touches is then left closing. Where the law cannot be applied, the rope law
  // stands and the event says why (docs/model.md §7).
  using contact::has;
  const ImpactLaw chosen = sc_.run.impact_law;
  if (!x.impulsive(kRope) || chosen == ImpactLaw::rope) return;
  if (x.bounced != 0) {
    x.law_note = "the jerk comes with a bounce on the floor, which no single law covers: the rope law";
    return;
  }
  if (x.impulsive(kLid)) {
    x.law_note =
        "the jerk also presses the lid onto the box, which no single law covers: perfectly inelastic (rope "
        "law)";
    return;
  }
  contact::Coords ul = x.u;
  std::string_view note;
  if (!law_velocity(x.k0, has(x.imp.impulsive, kBag), ul, &note)) {
    x.law_note = "the law has no finite solution at this state: perfectly inelastic (rope law)";
    return;
  }
  bool ok = true;
  contact::PerContact rl = x.rate;
  for (int i = 0; i < c_.contacts; ++i) {
    if (!has(x.touch, i) || is_friction(i)) continue;  // a slip either way is no gap closing
    rl[i] = has(x.imp.impulsive, i) ? 0.0 : x.sys.rate(i, ul);
    ok = ok && rl[i] >= -x.ch.closing_tol;
  }
  if (!ok) {
    x.law_note =
        "the law would drive a touching contact (the lid into the box, or the sandbag into the arm): "
        "perfectly inelastic (rope law)";
    return;
  }
  x.u = ul, x.rate = rl;
  x.law = note.empty() ? chosen : ImpactLaw::rope;
  x.law_note = note;
}

bool Model::slip_is_rounding(const Decision& x, int i) const {
  // A slip is zero where stopping it, with the contacts that hold, changes the machine's motion
  // by rounding only: its own rate alone cannot tell, since a contact that holds may gear it up
  // (a pivot that turns a millionth as fast as the lid it drives through a taut rope tied next to
  // the hinge). Measured as the speed sqrt(2 dE / m) of the kinetic energy dE that stopping it takes.
  contact::System after = x.sys;  // projected from the velocities after the impact
  after.velocity = x.u;
  contact::Coords with{}, without{};
  if (!contact::constrained_velocity(after, x.held | bit(i), with) ||
      !contact::constrained_velocity(after, x.held, without))
    return true;  // the rate's own test stands
  double twice_energy = 0.0;
  for (int j = 0; j < x.sys.coords; ++j)
    twice_energy += after.mass[j] * (with[j] - without[j]) * (with[j] - without[j]);
  const double mass = c_.m_s + c_.m_l + sc_.machine.seesaw_mass;
  return twice_energy <= mass * x.ch.rate_tol * x.ch.rate_tol;
}

void Model::hold_after_impact(Decision& x) const {
  // Touching contacts with zero gap rate after the impact.
  using contact::has;
  x.held = 0;
  for (int i = 0; i < c_.contacts; ++i) {
    if (is_friction(i)) {  // friction: a candidate to stick where it acts and the slip is zero
      const bool acts = i != kBagSlip || has(x.held, kBag);
      if (has(x.touch, i) && acts && std::fabs(x.sys.rate(i, x.u)) <= x.ch.rate_tol && slip_is_rounding(x, i))
        x.held |= bit(i);
      continue;
    }
    // The lid's gap is an angle: its rate compared as the speed of the lid's far edge.
    const double speed = i == kLid ? 2.0 * c_.r_l * x.rate[i] : x.rate[i];
    const bool stopped = has(x.imp.impulsive, i) && !has(x.bounced, i);
    if (has(x.touch, i) && (stopped || speed <= x.ch.rate_tol)) x.held |= bit(i);
  }
}

void Model::motion_on_accelerations(const Discrete& d, Decision& x, double t) const {
  // Which of the held contacts carry the motion on: forces >= 0, released ones separating.
  using contact::has;
  x.k1 = with_velocity(x.k0, x.u);
  Discrete held = with_contacts(d, x.held);
  // A stretched rope is a force of one sign, T = k s + c s' >= 0, decided with the contacts: where
  // the impact's velocities would make it push (its damper, s' changed by a jump elsewhere), it lets
  // go now, and the contacts' forces are found without it; where they make a slack rope that is
  // still longer than l_R pull, it pulls from now on, and the forces are found with it.
  if (x.impacted && c_.stretchy && spring_rope(held)) {
    Discrete pulling = held;
    pulling.stretched = true;
    const RopePull p = rope_pull(pulling, x.k1);
    if (held.stretched && !(p.tension > 0.0)) {
      held.stretched = false;
      x.rope_let_go = true;
    } else if (!held.stretched && p.stretch > 0.0 && p.tension > 0.0) {
      held.stretched = true;
      x.rope_pulls = true;
    }
  }
  const contact::System sys1 = contact_system(held, x.k1);
  x.mot = contact::solve_motion(sys1, x.held, x.ch);
  if (!x.mot.ok) no_consistent("set of contacts", t, d.mode());
  x.s2 = x.mot.active;

  // Released contacts: their gaps start at zero and open, by their rate or their acceleration.
  for (int i = 0; i < c_.contacts; ++i) {
    if (is_friction(i)) {
      // Friction's guard is minus the slip's speed: it starts at zero where the slip starts from
      // rest, and falls as fast as the slip picks up.
      const double a = std::fabs(x.mot.gap_acceleration[i]);
      x.released[i] = !has(x.held, i)
                          ? GuardStart{}
                          : (a > x.ch.accel_tol ? GuardStart{1, -a} : GuardStart{2, kUnknownLead});
      continue;
    }
    if (!has(x.held, i)) {
      x.released[i] = {1, -x.rate[i]};
    } else if (x.mot.gap_acceleration[i] > x.ch.accel_tol) {
      x.released[i] = {2, -0.5 * x.mot.gap_acceleration[i]};
    } else {
      x.released[i] = {3, kUnknownLead};
    }
  }

  // The contacts that hold are left with exactly zero gap rate (they may have had a rate within
  // the rounding band): the same projection as an impact, booked like one.
  // So is a friction found at rest whose rounding speed points against the slip the accelerations
  // gave it: it starts from exactly zero (its guard, minus the slip's speed, starts at zero and
  // falls), not from a speed the other way that its guard would find at once, again and again.
  Set at_rest = x.s2;
  for (int i = kBagSlip; i < c_.contacts; ++i)
    if (has(x.held, i) && !has(x.s2, i) && x.mot.slip[i] * sys1.rate(i, sys1.velocity) < 0.0)
      at_rest |= bit(i);
  x.k2 = x.k1;
  contact::Coords u2;
  if (at_rest != 0 && contact::constrained_velocity(sys1, at_rest, u2)) x.k2 = with_velocity(x.k1, u2);

  // A touch that changes nothing (no impulse, the same contacts, no slip brought to rest) leaves
  // the state as it was.
  if (x.s2 == x.s0 && !x.impacted && at_rest == x.s2) x.k2 = x.k0;
}

void Model::enter_contacts(HybridState& hs, const Decision& x) const {
  // The new contact set and state; the released contacts' guards armed for the piece that starts.
  using contact::has;
  Discrete& d = hs.d;
  d.armed = {};
  set_contacts(d, x.s2, x.k2);
  take_slips(d, x.mot.slip);
  for (int i = 0; i < c_.contacts; ++i) {
    const Guard gi = guard_of(i);
    if (has(x.touch, i) && !has(x.s2, i)) {
      if (i == kBagSlip && !has(x.s2, kBag)) continue;  // no friction off the arm
      d.armed[gi] = x.released[i];
    } else if (is_friction(i)) {
      // Sticking with the friction force at its bound already: it can only slip.
      const double bound = i == kBagSlip ? c_.mu * x.mot.force[kBag] : coulomb_hold(d, x.k2, i);
      if (!has(x.s2, i) || has(x.s0, i) || std::fabs(x.mot.force[i]) < bound - x.ch.force_tol) continue;
      d.armed[gi] = {1, kUnknownLead};
    } else if (has(x.s2, i) && !has(x.s0, i) && x.mot.force[i] <= x.ch.force_tol) {
      d.armed[gi] = {1, kUnknownLead};  // closed with a force still zero: it can only load up
    } else {
      continue;
    }
    d.armed[gi].floor = guard_floor(gi, d);
  }
  if (x.trend == Trend::forced_off) d.fallen_off = true;
  if (x.rope_let_go) d.stretched = false;
  if (x.rope_pulls) d.stretched = true;
  place(hs, x.k2);
}

std::array<double, 6> Model::impulses(const Decision& x) const {
  // The impulses that make the velocity jump, M (u+ - u-) = sum_i W_i p_i: the inelastic impact's
  // own under the rope law, else the contacts' share of the chosen law's jump (least squares where
  // the law moves the machine in a way no contact impulse could: linear momentum).
  contact::PerContact p = x.imp.impulse;
  if (x.law != ImpactLaw::rope) {
    contact::System jump = x.sys;
    jump.force = {};
    contact::Coords dv{};
    for (int j = 0; j < jump.coords; ++j) dv[j] = x.u[j] - x.sys.velocity[j];
    if (!contact::multipliers_for(jump, x.imp.impulsive, dv, p)) p = x.imp.impulse;
  }
  // Per contact, in the order of the event's impulses (its row's impulse column). An impulse that
  // is rounding (within the decision's tolerance) is none: not reported.
  std::array<double, 6> out{};
  for (int i = 0; i < c_.contacts; ++i) {
    const int column = kContacts[i].impulse;
    if (column >= 0 && contact::has(x.imp.impulsive, i) && std::fabs(p[i]) > x.ch.impulse_tol)
      out[column] += p[i];
  }
  return out;
}

void Model::report_changes(HybridState& hs, const Decision& x, Mode before, std::vector<Event>& out) const {
  // The changes as they happen: the one that triggered the event, those decided on the
  // velocities, then those decided on the accelerations. A lid knocked off the box by an impact
  // is part of that impact (M3 > M4 says it), not an event of its own.
  using contact::has;
  const int trigger = x.trigger;
  const bool trigger_changed =
      trigger >= 0 &&
      (x.trend == Trend::closing ? x.impulsive(trigger) || has(x.s2, trigger) : !has(x.s2, trigger));
  const bool lid_knocked = x.impacted && has(x.s0, kLid) && !has(x.held, kLid);
  Set cur = x.s0;
  Mode from = before;
  bool first = true;
  auto emit = [&](EventType type) {
    if (first && lid_knocked) cur &= ~bit(kLid);
    const Mode to = mode_of(cur);
    Event e = make_event(type, hs, from, to);
    if (first && x.impacted) {
      e.impact = true;
      e.energy_before = energy(x.k0);
      e.impulse = impulses(x);
      e.law = x.law;
      e.law_note = x.law_note;
    }
    out.push_back(e);
    from = to;
    first = false;
  };
  if (trigger_changed) {
    if (x.trend == Trend::closing) {
      cur |= bit(trigger);
      emit(change_event(trigger, true));
    } else {
      cur &= ~bit(trigger);
      emit(x.trend == Trend::forced_off ? EventType::sandbag_falls_off : change_event(trigger, false));
    }
  }
  // A bounce on the floor touches and lets go in the same instant: reported as both, even where
  // it is not the contact that triggered the event.
  for (int i = 0; i < c_.contacts; ++i) {
    if (!has(x.bounced, i) || has(cur, i)) continue;
    cur |= bit(i);
    emit(change_event(i, true));
  }
  // The trigger's own change was reported first; a contact it closed may still let go below.
  auto step_to = [&](Set target, bool trigger_may_change) {
    for (int i = 0; i < c_.contacts; ++i) {
      if (i == trigger && !trigger_may_change) continue;
      if (has(cur, i) == has(target, i)) continue;
      if (i == kBagSlip && !has(target, kBag)) {  // off the arm: no friction, nothing to report
        cur &= ~bit(i);
        continue;
      }
      if (has(target, i)) {
        cur |= bit(i);
      } else {
        cur &= ~bit(i);
      }
      emit(change_event(i, has(target, i)));
    }
  };
  // Friction's stick or slip is reported as the motion goes on (a slip stopped by the stop's
  // impact is no sticking).
  const Set frictions = bit(kBagSlip) | bit(kPivotSlip) | bit(kHingeSlip);
  step_to((x.held & ~frictions) | (x.s0 & frictions), false);
  step_to(x.s2, trigger_changed && x.trend == Trend::closing);
  if (x.rope_let_go) emit(EventType::rope_slack);
  if (x.rope_pulls) emit(EventType::rope_taut);
}

}  // namespace whatnext
