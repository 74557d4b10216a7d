// Jumps: the start, every event's change of the discrete state, and the end of a run.
#include "model.hpp"

#include <cmath>
#include <cstdio>

#include "model_internal.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext {

using namespace model_detail;

// --- jumps -------------------------------------------------------------------------------------

HybridState Model::initial(std::vector<Event>& out) const {
  const Start& st = sc_.start;
  HybridState hs;
  hs.t = 0.0;
  Discrete& d = hs.d;
  d.parked_seesaw = st.seesaw_angle;
  d.balloon_stuck = true;
  d.balloon_held = true;  // a balloon smaller than the box: in the corner at the far wall
  d.heavy = c_.heavy;
  d.on_seesaw = false;
  d.taut = false;
  d.lid_resting = true;
  Kinematics k;
  const Set touch = start_touching(d, k);
  // Everything starts at rest, so only forces decide; what touches is kept where they allow it.
  const Discrete dt = with_contacts(d, touch);
  const contact::System sys = contact_system(dt, k);
  contact::Choice ch = choice(dt, sys, k, -1, Trend::closing);
  const contact::Motion mot = contact::solve_motion(sys, touch, ch);
  if (!mot.ok) throw SimulationError("no consistent set of contacts at the start (degenerate contact)");
  set_contacts(d, mot.active, k);
  take_slips(d, mot.slip);
  hs.y.fill(0.0);
  place(hs, k);
  hs.y[slot::balloon_h] = limit_.height(c_.phi_l0);
  SmallBalloon::Limit corner{0.0, 0.0, 0.0};
  if (c_.small && !sb_.limit(k.cos_l, k.sin_l, corner)) {
    // A lid resting so steep that the wall's top lets a smaller balloon by: it starts under the
    // lid above the far wall's face (docs/extensions.md), free to slide along the lid; at most at
    // the line where it is out (beyond it the face's point may lie past the lid's free edge).
    d.balloon_held = false;
    hs.y[slot::balloon_h] = std::fmin((sb_.wall() - sb_.radius * k.sin_l) / k.cos_l, sb_.lid * k.cos_l);
    hs.y[slot::balloon_v] = 0.0;
  }
  arm_start_releases(d, touch, mot, ch.accel_tol);

  const Kinematics k1 = kinematics(d, hs.y);
  Books& b = d.books;
  b.initial_total = energy(k1) + balloon_energy(k1);
  b.balloon_e_mark = balloon_energy(k1);  // nothing pushed yet
  open_books(hs, k1);
  report_start_releases(hs, touch, mot.active, out);
  return hs;
}

Set Model::start_touching(const Discrete& d, Kinematics& k) const {
  const Start& st = sc_.start;
  k.x = st.sandbag_x;
  k.h = st.sandbag_h;
  k.phi_s = st.seesaw_angle;
  k.phi_l = c_.phi_l0;
  k.cos_s = std::cos(k.phi_s), k.sin_s = std::sin(k.phi_s);
  k.cos_l = std::cos(k.phi_l), k.sin_l = std::sin(k.phi_l);
  // What touches at t = 0: the sandbag placed on the arm, the rope straight, the lid on the box.
  Set touch = bit(kLid);
  const double c = std::cos(st.seesaw_angle), s = std::sin(st.seesaw_angle);
  if (std::fabs(height_above_arm(k)) <= kContact) {
    touch |= bit(kBag);
    // Placed on the arm: the polar and the Cartesian pictures agree exactly on the arm's line.
    const double r = std::hypot(st.sandbag_x, st.sandbag_h);
    k.x = -r * c;
    k.h = -r * s;
  }
  if (rope_.span(st.seesaw_angle, c_.phi_l0) >= rope_.rope_length() - kContact) touch |= bit(kRope);
  // A rope that stretches is no contact while the sandbag rides the seesaw (docs/impact.md).
  if (c_.stretchy && (c_.heavy || contact::has(touch, kBag))) touch &= ~bit(kRope);
  k = with_velocity(k, contact::Coords{});
  if (c_.contacts > 3) {  // a seesaw that starts standing on the floor (a sandbag on it at the stop)
    Discrete dt = d;
    dt.on_seesaw = contact::has(touch, kBag);
    touch |= touching_built(dt, k);
    k = touch_exactly(dt, touch, k);
  }
  if (c_.mu > 0.0 && contact::has(touch, kBag)) touch |= bit(kBagSlip);  // it sticks, or slips
  if (c_.t_p > 0.0) touch |= bit(kPivotSlip);  // a seesaw at rest on its pivot, unless its torque wins
  return touch;
}

void Model::arm_start_releases(Discrete& d, Set touch, const contact::Motion& mot, double accel_tol) const {
  // A contact that touches but is not kept opens from rest: its guard starts at zero and turns
  // negative as its acceleration, or a higher derivative, makes it (GuardStart).
  for (int i = 0; i < c_.contacts; ++i) {
    if (!contact::has(touch, i) || contact::has(mot.active, i)) continue;
    const Guard gi = guard_of(i);
    if (is_friction(i)) {  // slipping from rest: minus the slip's speed falls as it picks up
      if (i == kBagSlip && !d.on_seesaw) continue;
      const double a = std::fabs(mot.gap_acceleration[i]);
      d.armed[gi] = a > accel_tol ? GuardStart{1, -a} : GuardStart{2, kUnknownLead};
    } else {
      d.armed[gi] = mot.gap_acceleration[i] > accel_tol ? GuardStart{2, -0.5 * mot.gap_acceleration[i]}
                                                        : GuardStart{3, kUnknownLead};
    }
    d.armed[gi].floor = guard_floor(gi, d);
  }
}

void Model::report_start_releases(HybridState& hs, Set touch, Set active, std::vector<Event>& out) const {
  // A rope or a sandbag that touches at the start but lets go at once is an event at t = 0 (a lid
  // that lifts at once just starts in M4).
  Set cur = touch;
  for (int i : {kBag, kRope, kFloorLeft, kFloorRight}) {
    if (!contact::has(touch, i) || contact::has(active, i)) continue;
    const Mode from = mode_of(cur);
    cur &= ~bit(i);
    out.push_back(make_event(change_event(i, false), hs, from, mode_of(cur)));
  }
}

void Model::place(HybridState& hs, const Kinematics& k) const {
  // In the lid chart the angle slots hold the lid's angle and rate instead of the seesaw's.
  const bool by_lid = hs.d.lid_chart && on_closure(hs.d);
  const double angle = by_lid ? k.phi_l : k.phi_s, rate = by_lid ? k.dphi_l : k.dphi_s;
  // A closed stop or floor holds its coordinate exactly (its rate is zero within rounding).
  const double held_rate = hs.d.seesaw_held() ? 0.0 : rate;
  if (hs.d.polar()) {
    hs.y[slot::r] = hs.d.at_stop ? c_.arm : k.r;
    hs.y[slot::phi_s] = angle;
    hs.y[slot::dr] = hs.d.at_stop || hs.d.bag_stuck ? 0.0 : k.dr;
    hs.y[slot::dphi_s] = held_rate;
  } else {
    hs.y[slot::x] = k.x;
    hs.y[slot::h] = k.h;
    hs.y[slot::vx] = k.vx;
    hs.y[slot::vh] = k.vh;
  }
  hs.y[slot::phi_l] = k.phi_l;
  hs.y[slot::dphi_l] = (hs.d.seesaw_held() && hs.d.taut) || hs.d.lid_stuck ? 0.0 : k.dphi_l;
  hs.y[slot::seesaw_phi] = angle;
  hs.y[slot::seesaw_dphi] = held_rate;
  if (hs.d.bag_on_floor) hs.y[slot::vh] = 0.0;
}

Event Model::make_event(EventType type, HybridState& hs, Mode before, Mode after) const {
  book(hs);
  Event e;
  e.type = type;
  e.t = hs.t;
  e.mode_before = before;
  e.mode_after = after;
  return e;  // after and the energies: see jump()
}

void Model::free_balloon(HybridState& hs, const Kinematics& k, double v) const {
  hs.d.balloon_stuck = false;
  hs.y[slot::balloon_h] = limit_.height(k.phi_l);
  hs.y[slot::balloon_v] = v;
}

void Model::release_balloon_if_lid_jumped(HybridState& hs, const Kinematics& k0, double limit_rate_before,
                                          const Books& opened, std::vector<Event>& out) const {
  if (!hs.d.balloon_stuck) return;
  if (c_.small) {
    // Booked once, at the jump's end, for the whole change of the balloon's velocity.
    Books& b = hs.d.books;
    b.balloon_catch = opened.balloon_catch;
    b.lid_push = opened.lid_push;
    b.balloon_v_mark = opened.balloon_v_mark;
    b.balloon_vx_mark = opened.balloon_vx_mark;
    small_balloon_after_lid_jump(hs, k0, out);
    return;
  }
  const Kinematics k = kinematics(hs.d, hs.y);
  const double rate = limit_.rate(k.phi_l, k.dphi_l);
  // A jump, not rounding: beyond what the contact decision calls a zero rate.
  if (rate >
      limit_rate_before + 1e-7 * std::sqrt(c_.g * c_.length_scale) + 1e-9 * std::fabs(limit_rate_before)) {
    // The lid jumped away faster than the balloon moves: it keeps its own velocity, so the
    // balloon's side of the books is as it was before the jump.
    const Mode m = hs.d.mode();
    free_balloon(hs, k, limit_rate_before);
    hs.d.armed[kGuardBalloon] = {1, limit_rate_before - rate, guard_floor(kGuardBalloon, hs.d)};
    Books& b = hs.d.books;
    b.balloon_catch = opened.balloon_catch;
    b.lid_push = opened.lid_push;
    b.balloon_v_mark = opened.balloon_v_mark;
    out.push_back(make_event(EventType::balloon_free, hs, m, m));
  }
}

void Model::balloon_meets_lid(HybridState& hs, const Kinematics& k0, double limit_rate0, Mode before,
                              std::vector<Event>& out) const {
  if (hs.d.balloon_stuck) {  // the lid pulls away faster than the balloon can follow
    free_balloon(hs, k0, limit_rate0);
    hs.d.armed[kGuardBalloon] = {3, kUnknownLead, guard_floor(kGuardBalloon, hs.d)};
    out.push_back(make_event(EventType::balloon_free, hs, before, before));
    return;
  }
  hs.d.balloon_stuck = true;
  out.push_back(make_event(EventType::balloon_caught, hs, before, before));
  // Caught by a lid that accelerates away faster than the balloon can: it touches and parts.
  const double ahead =
      limit_.acceleration(k0.phi_l, k0.dphi_l, k0.ddphi_l) - balloon_acceleration(limit_rate0);
  if (ahead > 0.0) {
    free_balloon(hs, k0, limit_rate0);
    hs.d.armed[kGuardBalloon] = {2, -0.5 * ahead, guard_floor(kGuardBalloon, hs.d)};
    out.push_back(make_event(EventType::balloon_free, hs, before, before));
  }
}

void Model::latch_open(HybridState& hs, const Kinematics& k0, double limit_rate0, Mode before,
                       std::vector<Event>& out) const {
  // The radio's question goes on: the lid latches open where it is (its kinetic energy is lost to
  // the latch), the rope is let go for good, the sandbag falls freely off the story and the
  // balloon rises without a limit.
  const bool pulled = hs.d.taut || hs.d.stretched;
  hs.d.latched = true;
  hs.d.lid_resting = false;
  hs.d.taut = false;
  hs.d.stretched = false;
  // The built machine's sandbag stays where it is (on the arm, at the stop): it has a floor to
  // land on and the drawing shows it.
  if (!c_.built) hs.d.on_seesaw = false;
  hs.d.lid_chart = false;
  hs.d.parked_seesaw = k0.phi_s;
  Kinematics k = k0;
  k.dphi_l = 0.0;
  place(hs, k);
  // The latch is an impact: it stops the lid (the box's angular impulse through it, I_L phiL', along
  // the latch's normal) and takes the lid's kinetic energy and a stretched rope's.
  // The rope is let go for good: an event of its own, after the latch's (M4 > M4, then M4 > M3).
  const Mode latched = Discrete::mode_of(hs.d.on_seesaw, pulled, false);
  Event latch = make_event(EventType::lid_open, hs, before, latched);
  latch.impact = true;
  latch.energy_before = energy(k0);
  latch.impulse[2] = c_.i_l * k0.dphi_l;
  out.push_back(latch);
  if (pulled) out.push_back(make_event(EventType::rope_slack, hs, latched, hs.d.mode()));
  // What the rope held is decided again by the contacts that are left, like at any event: a
  // sandbag stuck on the arm against the rope's pull slips at this instant, a seesaw held on the
  // floor may lift off.
  resolve(hs, kinematics(hs.d, hs.y, true), -1, Trend::releasing, out);
  if (hs.d.balloon_stuck) {
    const Mode m = hs.d.mode();
    if (c_.small) {
      small_balloon_free(hs, k0);
    } else {
      free_balloon(hs, k0, limit_rate0);
    }
    out.push_back(make_event(EventType::balloon_free, hs, m, m));
  }
}

bool Model::jump(Guard fired, HybridState& hs, std::vector<Event>& out, Workspace* ws) const {
  if (c_.stretchy) {  // the contact decision names modes by its contacts: add the stretched rope
    const std::size_t first = out.size();
    const bool was_stretched = hs.d.stretched;
    const bool end = jump_contacts(fired, hs, out, ws);
    if (!end) stretched_rope_left(hs, out);
    stretchy_modes(was_stretched, hs.d, out, first);
    if (!end) hs.d.rope_relaxing = relaxing(hs);
    return end;
  }
  return jump_contacts(fired, hs, out, ws);
}

bool Model::jump_contacts(Guard fired, HybridState& hs, std::vector<Event>& out, Workspace* ws) const {
  hs.d.armed = {};
  const Mode before = hs.d.mode();
  const Kinematics k0 = kinematics(hs.d, hs.y, true, ws);
  const double limit_rate0 = limit_.rate(k0.phi_l, k0.dphi_l);
  open_books(hs, k0);
  const Books opened = hs.d.books;
  auto stop = [&](EventType type) {
    out.push_back(make_event(type, hs, before, before));
    return true;
  };
  // docs/model.md §6: the model ends when the sandbag reaches the pivot. As r -> 0 the rope's pull on the
  // lid vanishes too, so contact changes and sandbag_at_pivot arrive together; the pivot wins.
  if (hs.d.on_seesaw && k0.r <= kContact && !fires_at_once(fired)) return stop(EventType::sandbag_at_pivot);
  switch (fired) {
    case kGuardBag:
      if (!c_.heavy && spring_rope(hs.d) && hs.d.stretched) return stretchy_jump(fired, hs, k0, before, out);
      if (hs.d.on_seesaw) {
        resolve(hs, k0, kBag, Trend::releasing, out);
        break;
      }
      {
        // The falling sandbag reaches the arm's line: it lands where the arm is. Beyond a finite
        // arm's end it has missed it for good; on the pivot's other side the model ends.
        const double along = along_arm(k0);
        if (along > c_.arm) {
          hs.d.fallen_off = true;
          out.push_back(make_event(EventType::sandbag_falls_off, hs, before, before));
          return false;
        }
        if (along < 0.0) return stop(EventType::sandbag_at_pivot);
        resolve(hs, k0, kBag, Trend::closing, out);
      }
      break;
    case kGuardRope:
      // The linkage (docs/model.md §3): the rope straightens on the lid-below-rope side only; on the other
      // it would run under the hinge, through the box, and the model cannot go on.
      if (!hs.d.taut && !rope_.lid_below_rope(k0.phi_s, k0.phi_l)) return stop(EventType::rope_locked);
      if (spring_rope(hs.d)) return stretchy_jump(fired, hs, k0, before, out);
      resolve(hs, k0, kRope, hs.d.taut ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardLid: resolve(hs, k0, kLid, hs.d.lid_resting ? Trend::releasing : Trend::closing, out); break;
    case kGuardStop: resolve(hs, k0, kStop, hs.d.at_stop ? Trend::releasing : Trend::closing, out); break;
    case kGuardFloor:
      if (hs.d.grounded != 0) {
        resolve(hs, k0, hs.d.grounded > 0 ? kFloorLeft : kFloorRight, Trend::releasing, out);
      } else {  // the end that reached the floor
        const double left = -c_.arm * k0.sin_s, right = sc_.machine.seesaw_right_arm * k0.sin_s;
        resolve(hs, k0, left <= right ? kFloorLeft : kFloorRight, Trend::closing, out);
      }
      break;
    case kGuardBagFloor: resolve(hs, k0, kBagFloor, Trend::closing, out); break;
    case kGuardBagSlip:
      resolve(hs, k0, kBagSlip, hs.d.bag_stuck ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardPivotSlip:
      resolve(hs, k0, kPivotSlip, hs.d.seesaw_stuck ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardHingeSlip:
      resolve(hs, k0, kHingeSlip, hs.d.lid_stuck ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardArmEnd:  // off the end of a finite arm, velocity kept; it never lands again
      resolve(hs, k0, kBag, Trend::forced_off, out);
      break;
    case kGuardBalloon:
    case kGuardBalloonCorner:
    case kGuardBalloonEscape:
    case kGuardLidOpen:
    case kGuardSeesawVertical:
    case kGuardAtPivot:
    case kGuardRopeLocked:
    case kGuardRadioOn:
    case kGuardRopeRelaxed:
    case kGuardChart: return jump_without_contacts(fired, hs, k0, limit_rate0, before, out);
    case kGuardCount: break;
  }
  release_balloon_if_lid_jumped(hs, k0, limit_rate0, opened, out);
  book(hs, ws);  // a jump may end with a change that no event reports
  return false;
}

bool Model::jump_without_contacts(Guard fired, HybridState& hs, const Kinematics& k0, double limit_rate0,
                                  Mode before, std::vector<Event>& out) const {
  auto stop = [&](EventType type) {
    out.push_back(make_event(type, hs, before, before));
    return true;
  };
  switch (fired) {
    case kGuardBalloon:
      if (c_.small) {
        small_balloon_jump(fired, hs, k0, before, out);
        return false;
      }
      balloon_meets_lid(hs, k0, limit_rate0, before, out);
      return false;
    case kGuardBalloonCorner:
    case kGuardBalloonEscape: small_balloon_jump(fired, hs, k0, before, out); return false;
    case kGuardLidOpen:
      if (!c_.radio) return stop(EventType::lid_open);
      latch_open(hs, k0, limit_rate0, before, out);
      return false;
    case kGuardSeesawVertical: return stop(EventType::seesaw_vertical);
    case kGuardAtPivot: return stop(EventType::sandbag_at_pivot);
    case kGuardRopeLocked: return stop(EventType::rope_locked);
    case kGuardRadioOn:
      // The string straightens and holds the balloon: it pulls with the balloon's net lift.
      return stop(sc_.machine.balloon_pull() >= sc_.machine.switch_force ? EventType::radio_on
                                                                         : EventType::switch_stays_off);
    case kGuardRopeRelaxed:  // the slack rope back at l_R: nothing moves differently, no event
      hs.d.rope_relaxing = false;
      return false;
    case kGuardChart:  // the same state in the other angle: no event
      hs.d.lid_chart = !hs.d.lid_chart;
      hs.d.side = RopeGeometry::side_of(rope_.lid_edge(k0.phi_l), rope_.seesaw_end(k0.phi_s));
      place(hs, k0);
      return false;
    default: break;  // the contacts' guards: jump_contacts
  }
  return false;
}

void Model::timeout(HybridState& hs, std::vector<Event>& out) const {
  open_books(hs, kinematics(hs.d, hs.y));
  out.push_back(make_event(EventType::timeout, hs, hs.d.mode(), hs.d.mode()));
}

}  // namespace whatnext
