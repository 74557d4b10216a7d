// The contact decision at an event: which contacts touch, the impact on velocities, the motion on accelerations, and the report of what changed.
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
  if (d.latched) return s;
  if (!d.on_seesaw && !d.fallen_off) {
    const double along = along_arm(k);
    if (std::fabs(height_above_arm(k)) <= kContact && along >= 0.0 && along <= arm_) s |= bit(kBag);
  }
  if (!d.taut && std::fabs(rope_.span(k.phi_s, k.phi_l) - rope_.rope_length()) <= kContact &&
      rope_.lid_below_rope(k.phi_s, k.phi_l)) {
    s |= bit(kRope);
  }
  if (!d.lid_resting && k.phi_l - phi_l0_ <= kContact) s |= bit(kLid);
  return s;
}

contact::Choice Model::choice(const Discrete& d, const contact::System& sys, const Kinematics& k,
                              int trigger, Trend trend) const {
  contact::Choice c;
  // Where the physics leaves a choice (only a massless seesaw does: contacts with zero force
  // either way), each contact stays as it was, the one that triggered the event goes the way it
  // tends, and a sandbag on a massless seesaw stays on it (MODEL.md: once landed, it stays; with
  // the rope slack that seesaw simply turns with the falling sandbag).
  const Set s0 = active_set(d);
  for (int i = 0; i < 3; ++i) {
    c.want[i] = contact::has(s0, i) ? 1 : -1;
    c.weight[i] = 1;
  }
  if (trigger >= 0 && trend != Trend::forced_off) {
    c.want[trigger] = trend == Trend::closing ? 1 : -1;
    c.weight[trigger] = 8;
  }
  if (!heavy_) {
    c.want[kBag] = 1;
    c.weight[kBag] = 16;
  }
  // "Zero" on the scale of this machine and motion.
  const double len = length_scale_;
  double v = std::sqrt(g_ * len);
  v = std::fmax(v, std::fmax(std::fabs(k.vx), std::fabs(k.vh)));
  v = std::fmax(v, len * std::fmax(std::fabs(k.dphi_s), std::fabs(k.dphi_l)));
  const double mass = m_s_ + m_l_ + sc_.machine.seesaw_mass;
  const double acc = g_ + v * v / len;
  c.force_tol = 1e-9 * mass * acc * (1.0 + len);
  c.impulse_tol = 1e-9 * mass * v * (1.0 + len);
  // A contact that would separate slower than a millionth of the machine's speed is held: the
  // end of an inelastic cascade (rope jerks the lid a hair off the box, the lid drops back, the
  // seesaw lets the rope go, ...) whose gaps never open beyond rounding. Without it such a Zeno
  // cascade never reaches its limit, where both contacts hold (MODEL.md: impacts are inelastic).
  c.rate_tol = 1e-6 * v;
  c.closing_tol = 1e-12 * v;
  c.accel_tol = 1e-9 * acc;
  (void)sys;
  return c;
}


Kinematics Model::touch_exactly(const Discrete& d, contact::Set touch, Kinematics k) const {
  using contact::has;
  const bool resting = has(touch, kLid);
  if (resting && k.phi_l < phi_l0_) k.phi_l = phi_l0_;
  k.cos_l = std::cos(k.phi_l), k.sin_l = std::sin(k.phi_l);
  if (has(touch, kRope) && std::fabs(rope_.span(k.phi_s, k.phi_l) - rope_.rope_length()) > 0.0) {
    double phi = 0.0;
    if (!resting) {  // the lid moves onto the straight rope
      if (rope_.lid_angle_for(k.phi_s, phi) && rope_.lid_below_rope(k.phi_s, phi) &&
          std::fabs(phi - k.phi_l) < 1e-3) {
        k.phi_l = phi;
        k.cos_l = std::cos(phi), k.sin_l = std::sin(phi);
      }
    } else if (rope_.seesaw_angle_for(k.phi_l, RopeGeometry::side_of(rope_.lid_edge(k.phi_l),
                                                                       rope_.seesaw_end(k.phi_s)), phi) &&
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
  if (has(touch, kBag)) {
    // The sandbag onto the arm's line, along its normal.
    const double above = height_above_arm(k);
    if (std::fabs(above) < 1e-3) k.x += above * k.sin_s, k.h -= above * k.cos_s;
  }
  k.r = along_arm(k);
  return k;
}

void Model::set_contacts(Discrete& d, Set s, const Kinematics& k) const {
  d.on_seesaw = contact::has(s, kBag);
  d.taut = contact::has(s, kRope);
  d.lid_resting = contact::has(s, kLid);
  // The unloaded massless seesaw is parked where it is, or follows the lid; on the closure the
  // chart is the seesaw's angle while the lid moves no faster than it (|k| <= 1).
  if (!d.on_seesaw && !d.heavy) d.parked_seesaw = k.phi_s;
  d.side = RopeGeometry::side_of(rope_.lid_edge(k.phi_l), rope_.seesaw_end(k.phi_s));
  d.lid_chart = on_closure(d) && std::fabs(rope_.transfer(k.phi_s, k.phi_l).k) > 1.0;
}

void Model::resolve(HybridState& hs, const Kinematics& k_event, int trigger, Trend trend,
                    std::vector<Event>& out) const {
  using contact::has;
  Discrete& d = hs.d;
  const Set s0 = active_set(d);
  Set touch = s0 | touching(d, k_event);
  if (trend == Trend::closing) touch |= bit(trigger);
  if (trend == Trend::forced_off) touch &= ~bit(trigger);

  // The touching contacts are at zero gap by definition: take back the event's overshoot (the
  // event-time tolerance times the closing speed, or a fixed step's interpolation error) before
  // anything is decided, so that the impact happens where the contacts touch and a contact that
  // lets go again starts from exactly zero.
  const Kinematics k0 = touch_exactly(d, touch, k_event);

  auto fail = [&](const char* what) {
    char msg[200];
    std::snprintf(msg, sizeof msg, "no consistent %s at t = %.9g s in mode M%d (degenerate contact)",
                  what, hs.t, static_cast<int>(d.mode()));
    throw SimulationError(msg);
  };

  // Velocities: an impact wherever a touching contact is closing.
  const contact::System sys = contact_system(d, k0);
  const contact::Choice ch = choice(d, sys, k0, trigger, trend);
  const contact::Impact imp = contact::solve_impact(sys, touch, ch);
  if (!imp.ok) fail("impact");
  contact::Coords u = imp.velocity;
  contact::PerContact rate = imp.rate;
  bool impacted = false;
  for (int i = 0; i < 3; ++i) impacted = impacted || (has(imp.impulsive, i) && imp.impulse[i] > ch.impulse_tol);
  const bool rope_jerk = has(imp.impulsive, kRope) && imp.impulse[kRope] > ch.impulse_tol;
  if (rope_jerk && sc_.run.impact_law != ImpactLaw::rope &&
      !(has(imp.impulsive, kLid) && imp.impulse[kLid] > ch.impulse_tol)) {
    // The rope's jerk by the chosen law (the inelastic solution above is the rope law, eq. 7),
    // provided nothing else it touches is then left closing.
    contact::Coords ul = u;
    if (law_velocity(k0, has(imp.impulsive, kBag), ul)) {
      bool ok = true;
      contact::PerContact rl = rate;
      for (int i = 0; i < 3; ++i) {
        if (!has(touch, i)) continue;
        rl[i] = has(imp.impulsive, i) ? 0.0 : sys.rate(i, ul);
        ok = ok && rl[i] >= -ch.closing_tol;
      }
      if (ok) u = ul, rate = rl;
    }
  }
  Set held = 0;  // touching contacts with zero gap rate after the impact
  for (int i = 0; i < 3; ++i) {
    // The lid's gap is an angle: its rate compared as the speed of the lid's far edge.
    const double speed = i == kLid ? 2.0 * r_l_ * rate[i] : rate[i];
    if (has(touch, i) && (has(imp.impulsive, i) || speed <= ch.rate_tol)) held |= bit(i);
  }

  // Accelerations: which of them carry the motion on.
  const Kinematics k1 = with_velocity(k0, u);
  Discrete dh = d;
  dh.on_seesaw = has(held, kBag), dh.taut = has(held, kRope), dh.lid_resting = has(held, kLid);
  const contact::System sys1 = contact_system(dh, k1);
  const contact::Motion mot = contact::solve_motion(sys1, held, ch);
  if (!mot.ok) fail("set of contacts");
  const Set s2 = mot.active;

  // Released contacts: their gaps start at zero and open, by their rate or their acceleration.
  d.armed = {};
  GuardStart released[3];
  for (int i = 0; i < 3; ++i) {
    if (!has(held, i)) {
      released[i] = {1, -rate[i]};
    } else if (mot.gap_acceleration[i] > ch.accel_tol) {
      released[i] = {2, -0.5 * mot.gap_acceleration[i]};
    } else {
      released[i] = {3, kUnknownLead};
    }
  }

  // The contacts that hold are left with exactly zero gap rate (they may have had a rate within
  // the rounding band): the same projection as an impact, booked like one.
  Kinematics k2 = k1;
  contact::Coords u2;
  if (s2 != 0 && contact::constrained_velocity(sys1, s2, u2)) k2 = with_velocity(k1, u2);

  // A touch that changes nothing (no impulse, the same contacts) leaves the state as it was.
  if (s2 == s0 && !impacted) k2 = k0;

  const Mode before = d.mode();
  set_contacts(d, s2, k2);
  for (int i = 0; i < 3; ++i) {
    const Guard gi = guard_of(i);
    if (has(touch, i) && !has(s2, i)) {
      d.armed[gi] = released[i];
    } else if (has(s2, i) && !has(s0, i) && mot.force[i] <= ch.force_tol) {
      d.armed[gi] = {1, kUnknownLead};  // closed with a force still zero: it can only load up
    } else {
      continue;
    }
    d.armed[gi].floor = guard_floor(gi, d);
  }
  if (trend == Trend::forced_off) d.fallen_off = true;
  place(hs, k2);

  // Report the changes as they happen: the one that triggered the event, those decided on the
  // velocities, then those decided on the accelerations. A lid knocked off the box by an impact
  // is part of that impact (M3 > M4 says it), not an event of its own.
  const bool trigger_changed =
      trend == Trend::closing ? (has(imp.impulsive, trigger) && imp.impulse[trigger] > ch.impulse_tol) || has(s2, trigger)
                              : !has(s2, trigger);
  const bool lid_knocked = impacted && has(s0, kLid) && !has(held, kLid);
  Set cur = s0;
  Mode from = before;
  bool first = true;
  auto emit = [&](EventType type) {
    if (first && lid_knocked) cur &= ~bit(kLid);
    const Mode to = mode_of(cur);
    Event e = make_event(type, hs, from, to);
    if (first && impacted) {
      e.impact = true;
      e.energy_before = energy(k0);
    }
    out.push_back(e);
    from = to;
    first = false;
  };
  if (trigger_changed) {
    if (trend == Trend::closing) {
      cur |= bit(trigger);
      emit(change_event(trigger, true));
    } else {
      cur &= ~bit(trigger);
      emit(trend == Trend::forced_off ? EventType::sandbag_falls_off : change_event(trigger, false));
    }
  }
  // The trigger's own change was reported first; a contact it closed may still let go below.
  auto step_to = [&](Set target, bool trigger_may_change) {
    for (int i = 0; i < 3; ++i) {
      if (i == trigger && !trigger_may_change) continue;
      if (has(cur, i) == has(target, i)) continue;
      if (has(target, i)) {
        cur |= bit(i);
      } else {
        cur &= ~bit(i);
      }
      emit(change_event(i, has(target, i)));
    }
  };
  step_to(held, false);
  step_to(s2, trigger_changed && trend == Trend::closing);
}

}  // namespace whatnext
