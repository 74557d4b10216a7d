#include "whatnext/model.hpp"

#include <cmath>

namespace whatnext {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kContact = 1e-9;  // MODEL.md: "on" and "taut" at the start within 1e-9 m
}  // namespace

EventType event_of(Guard g) {
  switch (g) {
    case kGuardLands: return EventType::sandbag_lands;
    case kGuardRopeTaut: return EventType::rope_taut;
    case kGuardRopeSlack: return EventType::rope_slack;
    case kGuardLidRests: return EventType::lid_rests;
    case kGuardLidLifts: return EventType::lid_lifts;
    case kGuardBalloonCaught: return EventType::balloon_caught;
    case kGuardBalloonFree: return EventType::balloon_free;
    case kGuardLidOpen: return EventType::lid_open;
    case kGuardSeesawVertical: return EventType::seesaw_vertical;
    case kGuardAtPivot: return EventType::sandbag_at_pivot;
    case kGuardRopeLocked: return EventType::rope_locked;
    case kGuardCount: break;
  }
  return EventType::timeout;
}

Model::Model(const Scenario& scenario)
    : sc_(scenario),
      rope_(scenario.machine),
      limit_{scenario.machine.balloon_radius},
      g_(scenario.machine.gravity),
      m_s_(scenario.machine.sandbag_mass),
      m_l_(scenario.machine.lid_mass),
      i_l_(scenario.machine.lid_inertia()),
      r_l_(scenario.machine.lid_half_length),
      a_b_(scenario.machine.balloon_acceleration()),
      phi_l0_(scenario.start.lid_angle),
      vertical_(kHalfPi - scenario.run.vertical_margin) {}

// --- flows -------------------------------------------------------------------------------------

double Model::lid_free_acceleration(double phi_l) const {
  return -m_l_ * g_ * r_l_ * std::cos(phi_l) / i_l_;
}

Model::Polar Model::taut_accelerations(double r, double phi_s, double dr, double dphi_s) const {
  // Eqs. (3) and (4) of the paper with phiL = phiL(phiS) and analytic k, k'.
  Polar p{};
  double cs = rope_.cos_sigma(phi_s);
  cs = cs > 1.0 ? 1.0 : (cs < -1.0 ? -1.0 : cs);  // the rope_locked guard stops the run before
  const Vec2 hr = rope_.seesaw_end(phi_s) - rope_.hinge();
  p.phi_l = std::atan2(hr.h, hr.x) - std::acos(cs);
  p.tr = rope_.transfer(phi_s, p.phi_l);
  const double k = p.tr.k;
  p.ddr = g_ * std::sin(phi_s) + r * dphi_s * dphi_s;
  const double num = m_s_ * g_ * r * std::cos(phi_s) - 2.0 * m_s_ * r * dr * dphi_s -
                     (m_l_ * g_ * r_l_ * std::cos(p.phi_l) + i_l_ * p.tr.dk * dphi_s * dphi_s) * k;
  p.ddphi_s = num / (m_s_ * r * r + i_l_ * k * k);
  return p;
}

void Model::flow(const Discrete& d, const State& y, State& dy) const {
  dy.fill(0.0);
  if (d.polar()) {
    dy[slot::r] = y[slot::dr];
    dy[slot::phi_s] = y[slot::dphi_s];
    if (d.lid_resting) {  // M5: seesaw held by the rope, sandbag slides on the fixed arm
      dy[slot::dr] = g_ * std::sin(y[slot::phi_s]);
    } else {  // M4
      const Polar p = taut_accelerations(y[slot::r], y[slot::phi_s], y[slot::dr], y[slot::dphi_s]);
      dy[slot::dr] = p.ddr;
      dy[slot::dphi_s] = p.ddphi_s;
    }
  } else {
    // Sandbag in free fall. On the seesaw with the rope slack (M3) this is the paper's polar free
    // fall written in Cartesian form: the same motion, regular at r = 0, and exact for any RK method.
    dy[slot::x] = y[slot::vx];
    dy[slot::h] = y[slot::vh];
    dy[slot::vh] = -g_;
    if (!d.lid_resting) {
      dy[slot::phi_l] = y[slot::dphi_l];
      dy[slot::dphi_l] = lid_free_acceleration(y[slot::phi_l]);
    }
  }
  if (!d.balloon_stuck) {
    dy[slot::balloon_h] = y[slot::balloon_v];
    dy[slot::balloon_v] = a_b_;
  }
}

// --- kinematics --------------------------------------------------------------------------------

Kinematics Model::kinematics(const Discrete& d, const State& y) const {
  Kinematics k;
  if (d.polar()) {
    k.r = y[slot::r];
    k.phi_s = y[slot::phi_s];
    k.dr = y[slot::dr];
    k.dphi_s = y[slot::dphi_s];
    if (d.lid_resting) {
      k.phi_l = phi_l0_;
      k.transfer = rope_.transfer(k.phi_s, k.phi_l);
    } else {
      const Polar p = taut_accelerations(k.r, k.phi_s, k.dr, k.dphi_s);
      k.phi_l = p.phi_l;
      k.transfer = p.tr;
      k.ddphi_s = p.ddphi_s;
      k.dphi_l = p.tr.k * k.dphi_s;
      k.ddphi_l = p.tr.k * p.ddphi_s + p.tr.dk * k.dphi_s * k.dphi_s;
    }
    const double c = std::cos(k.phi_s), s = std::sin(k.phi_s);
    k.x = -k.r * c;
    k.h = -k.r * s;
    k.vx = -k.dr * c + k.r * s * k.dphi_s;
    k.vh = -k.dr * s - k.r * c * k.dphi_s;
    return k;
  }
  k.x = y[slot::x];
  k.h = y[slot::h];
  k.vx = y[slot::vx];
  k.vh = y[slot::vh];
  k.r = std::hypot(k.x, k.h);
  k.dr = k.r > 0.0 ? (k.x * k.vx + k.h * k.vh) / k.r : 0.0;
  if (d.lid_resting) {
    k.phi_l = phi_l0_;
  } else {
    k.phi_l = y[slot::phi_l];
    k.dphi_l = y[slot::dphi_l];
    k.ddphi_l = lid_free_acceleration(k.phi_l);
  }
  if (d.on_seesaw) {  // M3: the massless seesaw turns with the sandbag
    k.phi_s = std::atan2(-k.h, -k.x);
    const double c = std::cos(k.phi_s), s = std::sin(k.phi_s);
    k.dphi_s = (k.vx * s - k.vh * c) / k.r;
    k.ddphi_s = (g_ * c - 2.0 * k.dr * k.dphi_s) / k.r;
  } else if (d.taut) {  // M2: the unloaded seesaw follows the lid
    k.phi_s = d.parked_seesaw;  // exact while the lid rests, the branch hint otherwise
    if (!d.lid_resting) rope_.seesaw_angle_for(k.phi_l, d.parked_seesaw, k.phi_s);
    k.transfer = rope_.transfer(k.phi_s, k.phi_l);
    k.dphi_s = d.lid_resting ? 0.0 : k.dphi_l / k.transfer.k;
  } else {  // M1: nothing moves the unloaded seesaw
    k.phi_s = d.parked_seesaw;
  }
  return k;
}

double Model::lid_rope_torque(const Kinematics& k) const {
  // Torque the rope must supply to the lid: I phiL'' + m_L g r_L cos phiL (the paper's
  // connecting-rod check: the rope can only pull, so it goes slack when this is negative).
  return i_l_ * k.ddphi_l + m_l_ * g_ * r_l_ * std::cos(k.phi_l);
}

bool Model::lid_lifts_now(double r, double phi_s) const {
  const double k = rope_.transfer(phi_s, phi_l0_).k;
  // >= so that it agrees exactly with the lid_lifts guard at the instant that guard fires.
  return m_s_ * r * std::cos(phi_s) >= k * m_l_ * r_l_ * std::cos(phi_l0_);
}

double Model::energy(const Kinematics& k) const {
  return 0.5 * m_s_ * (k.vx * k.vx + k.vh * k.vh) + m_s_ * g_ * k.h +
         0.5 * i_l_ * k.dphi_l * k.dphi_l + m_l_ * g_ * r_l_ * std::sin(k.phi_l);
}

Snapshot Model::snapshot(const HybridState& hs) const {
  const Kinematics k = kinematics(hs.d, hs.y);
  Snapshot s;
  s.t = hs.t;
  s.mode = hs.d.mode();
  s.on_seesaw = hs.d.on_seesaw;
  s.rope_taut = hs.d.taut;
  s.lid_resting = hs.d.lid_resting;
  s.balloon_stuck = hs.d.balloon_stuck;
  s.x = k.x, s.h = k.h, s.vx = k.vx, s.vh = k.vh, s.r = k.r, s.dr = k.dr;
  s.phi_s = k.phi_s, s.dphi_s = k.dphi_s;
  s.phi_l = k.phi_l, s.dphi_l = k.dphi_l, s.ddphi_l = k.ddphi_l;
  s.balloon_limit = limit_.height(k.phi_l);
  s.balloon_limit_rate = limit_.rate(k.phi_l, k.dphi_l);
  if (hs.d.balloon_stuck) {
    s.balloon_h = s.balloon_limit;
    s.balloon_v = s.balloon_limit_rate;
  } else {
    s.balloon_h = hs.y[slot::balloon_h];
    s.balloon_v = hs.y[slot::balloon_v];
  }
  if (s.mode == Mode::M4) {
    s.tension = lid_rope_torque(k) / rope_.lid_arm(k.phi_s, k.phi_l);
  } else if (s.mode == Mode::M5) {
    // The fixed arm carries the sandbag's normal force m g cos phiS at distance r; the rope balances it.
    s.tension = m_s_ * g_ * std::cos(k.phi_s) * k.r / rope_.seesaw_arm(k.phi_s, k.phi_l);
  }
  s.sandbag_kinetic = 0.5 * m_s_ * (k.vx * k.vx + k.vh * k.vh);
  s.sandbag_potential = m_s_ * g_ * k.h;
  s.lid_kinetic = 0.5 * i_l_ * k.dphi_l * k.dphi_l;
  s.lid_potential = m_l_ * g_ * r_l_ * std::sin(k.phi_l);
  return s;
}

// --- guards ------------------------------------------------------------------------------------

void Model::guards(const Discrete& d, const State& y, GuardValues& g) const {
  g.fill(kInactive);
  const Kinematics k = kinematics(d, y);
  if (!d.on_seesaw) {
    // Height of the sandbag above the left arm's line, measured across the arm.
    g[kGuardLands] = -(-k.x * std::sin(k.phi_s) + k.h * std::cos(k.phi_s));
  }
  if (!d.taut) g[kGuardRopeTaut] = rope_.gap(k.phi_s, k.phi_l);
  if (!d.lid_resting) {
    g[kGuardLidRests] = phi_l0_ - k.phi_l;
    g[kGuardLidOpen] = k.phi_l - vertical_;
  }
  if (d.polar()) {
    g[kGuardAtPivot] = -k.r;
    if (d.lid_resting) {
      const double kk = k.transfer.k;
      g[kGuardLidLifts] =
          m_s_ * k.r * std::cos(k.phi_s) - kk * m_l_ * r_l_ * std::cos(phi_l0_);
    } else {
      g[kGuardRopeSlack] = -lid_rope_torque(k);
      g[kGuardRopeLocked] = std::fabs(rope_.cos_sigma(k.phi_s)) - (1.0 - 1e-9);
    }
  } else if (d.on_seesaw) {
    // A free-falling sandbag can only leave the left arm through the pivot's vertical line.
    g[kGuardAtPivot] = k.x;
  }
  if (d.on_seesaw) g[kGuardSeesawVertical] = k.phi_s - vertical_;
  if (d.balloon_stuck) {
    g[kGuardBalloonFree] = limit_.acceleration(k.phi_l, k.dphi_l, k.ddphi_l) - a_b_;
  } else {
    g[kGuardBalloonCaught] = y[slot::balloon_h] - limit_.height(k.phi_l);
  }
}

// --- jumps -------------------------------------------------------------------------------------

HybridState Model::initial(std::vector<Event>& out) const {
  (void)out;
  const Start& st = sc_.start;
  HybridState hs;
  hs.t = 0.0;
  hs.d.parked_seesaw = st.seesaw_angle;
  hs.d.lid_resting = true;
  hs.d.balloon_stuck = true;
  const double c = std::cos(st.seesaw_angle), s = std::sin(st.seesaw_angle);
  const double above = -st.sandbag_x * s + st.sandbag_h * c;
  hs.d.on_seesaw = std::fabs(above) <= kContact;
  hs.d.taut = rope_.span(st.seesaw_angle, phi_l0_) >= rope_.rope_length() - kContact;
  if (hs.d.polar()) {
    const double r = -st.sandbag_x * c - st.sandbag_h * s;
    hs.y = {r, st.seesaw_angle, 0.0, 0.0, phi_l0_, 0.0, 0.0, 0.0};
    hs.d.lid_resting = !lid_lifts_now(r, st.seesaw_angle);
  } else {
    hs.y = {st.sandbag_x, st.sandbag_h, 0.0, 0.0, phi_l0_, 0.0, 0.0, 0.0};
    if (hs.d.on_seesaw) {
      // Placed on the arm: the polar and the Cartesian pictures agree exactly on the arm's line.
      hs.y[slot::x] = -std::hypot(st.sandbag_x, st.sandbag_h) * c;
      hs.y[slot::h] = -std::hypot(st.sandbag_x, st.sandbag_h) * s;
    }
  }
  hs.y[slot::balloon_h] = limit_.height(phi_l0_);
  return hs;
}

void Model::impact(HybridState& hs, const Kinematics& b) const {
  // Sudden coupling of sandbag, seesaw and lid: r' keeps the sandbag's speed along the arm (eq. 5),
  // phiS' jumps by the chosen law, and afterwards phiL' = k phiS'.
  const double c = std::cos(b.phi_s), s = std::sin(b.phi_s);
  const double r = -b.x * c - b.h * s;
  const double v_par = -b.vx * c - b.vh * s;
  const double v_perp = b.vx * s - b.vh * c;
  const double k = rope_.transfer(b.phi_s, b.phi_l).k;
  const double w0 = b.dphi_l;
  double dr = v_par, dphi_s = 0.0;
  const double rope_num = m_s_ * r * v_perp + k * i_l_ * w0;
  switch (sc_.run.impact_law) {
    case ImpactLaw::rope:  // eq. (7): inelastic impulse along the rope
      dphi_s = rope_num / (m_s_ * r * r + i_l_ * k * k);
      break;
    case ImpactLaw::angular_momentum_sum:
      dphi_s = (m_s_ * r * v_perp + i_l_ * w0) / (m_s_ * r * r + i_l_ * k);
      break;
    case ImpactLaw::kinetic_energy: {
      const double mag =
          std::sqrt((m_s_ * v_perp * v_perp + i_l_ * w0 * w0) / (m_s_ * r * r + i_l_ * k * k));
      dphi_s = rope_num < 0.0 ? -mag : mag;
      break;
    }
    case ImpactLaw::linear_momentum: {
      // Linear momentum of sandbag and lid centre of mass before = after (2x2 in r', phiS').
      const double sl = std::sin(b.phi_l), cl = std::cos(b.phi_l);
      const double px = m_s_ * b.vx - m_l_ * r_l_ * sl * w0;
      const double ph = m_s_ * b.vh + m_l_ * r_l_ * cl * w0;
      const double a11 = -m_s_ * c, a12 = m_s_ * r * s - m_l_ * r_l_ * sl * k;
      const double a21 = -m_s_ * s, a22 = -m_s_ * r * c + m_l_ * r_l_ * cl * k;
      const double det = a11 * a22 - a12 * a21;
      dr = (px * a22 - a12 * ph) / det;
      dphi_s = (a11 * ph - a21 * px) / det;
      break;
    }
  }
  hs.d.on_seesaw = true;
  hs.d.taut = true;
  hs.d.lid_resting = false;
  hs.y[slot::r] = r;
  hs.y[slot::phi_s] = b.phi_s;
  hs.y[slot::dr] = dr;
  hs.y[slot::dphi_s] = dphi_s;
}

void Model::to_cartesian(HybridState& hs, const Kinematics& k) const {
  hs.y[slot::x] = k.x;
  hs.y[slot::h] = k.h;
  hs.y[slot::vx] = k.vx;
  hs.y[slot::vh] = k.vh;
  hs.y[slot::phi_l] = k.phi_l;
  hs.y[slot::dphi_l] = k.dphi_l;
}

Event Model::make_event(EventType type, const HybridState& hs, Mode before) const {
  Event e;
  e.type = type;
  e.t = hs.t;
  e.mode_before = before;
  e.mode_after = hs.d.mode();
  e.after = snapshot(hs);
  e.energy_before = e.energy_after = e.after.energy();
  return e;
}

void Model::settle(HybridState& hs, std::vector<Event>& out) const {
  // Right after a jump that leaves the sandbag on the seesaw with the rope taut, decide between
  // M4 and M5 and apply MODEL.md's immediate checks (lid lifting, rope going slack at once).
  if (!hs.d.polar()) return;
  if (!hs.d.lid_resting) {
    const Kinematics k = kinematics(hs.d, hs.y);
    // The box stops a lid left moving down, or left at rest with too little pull to lift it
    // (a lid that has just lifted, at rest but pulled hard enough, goes on lifting).
    if (k.phi_l <= phi_l0_ + 1e-12 &&
        (k.dphi_l < 0.0 || (k.dphi_l == 0.0 && !lid_lifts_now(hs.y[slot::r], hs.y[slot::phi_s])))) {
      hs.d.lid_resting = true;
      hs.y[slot::dphi_s] = 0.0;
    }
  }
  if (hs.d.lid_resting) {
    if (!lid_lifts_now(hs.y[slot::r], hs.y[slot::phi_s])) return;
    hs.d.lid_resting = false;
    hs.y[slot::dphi_s] = 0.0;
    out.push_back(make_event(EventType::lid_lifts, hs, Mode::M5));
  }
  const Kinematics k = kinematics(hs.d, hs.y);
  if (lid_rope_torque(k) < 0.0) {
    to_cartesian(hs, k);
    hs.d.taut = false;
    out.push_back(make_event(EventType::rope_slack, hs, Mode::M4));
  }
}

void Model::release_balloon_if_lid_jumped(HybridState& hs, double limit_rate_before,
                                          std::vector<Event>& out) const {
  if (!hs.d.balloon_stuck) return;
  const Kinematics k = kinematics(hs.d, hs.y);
  const double rate = limit_.rate(k.phi_l, k.dphi_l);
  if (rate > limit_rate_before + 1e-12 * (1.0 + std::fabs(limit_rate_before))) {
    // The lid jumped away faster than the balloon moves: it keeps its own velocity.
    const Mode m = hs.d.mode();
    hs.d.balloon_stuck = false;
    hs.y[slot::balloon_h] = limit_.height(k.phi_l);
    hs.y[slot::balloon_v] = limit_rate_before;
    out.push_back(make_event(EventType::balloon_free, hs, m));
  }
}

bool Model::jump(Guard fired, HybridState& hs, std::vector<Event>& out) const {
  const Mode before = hs.d.mode();
  const Kinematics k0 = kinematics(hs.d, hs.y);
  const double limit_rate0 = limit_.rate(k0.phi_l, k0.dphi_l);
  EventType type = event_of(fired);
  // MODEL.md: the model ends when the sandbag reaches the pivot. As r -> 0 the rope's pull on the
  // lid vanishes too, so rope_slack and sandbag_at_pivot arrive together; the pivot wins.
  if (hs.d.on_seesaw && k0.r <= 1e-9 && !is_stop(type)) type = EventType::sandbag_at_pivot;
  auto emit_impact = [&] {
    Event e = make_event(type, hs, before);
    e.impact = true;
    e.energy_before = energy(k0);
    out.push_back(e);
  };
  switch (type) {
    case EventType::sandbag_lands:
    case EventType::rope_taut:
      if (hs.d.on_seesaw || (type == EventType::sandbag_lands && hs.d.taut)) {
        impact(hs, k0);
        emit_impact();
        settle(hs, out);
      } else if (type == EventType::sandbag_lands) {  // M1 -> M3: velocity kept
        hs.d.on_seesaw = true;
        out.push_back(make_event(type, hs, before));
      } else {  // M1 -> M2: nothing loads the seesaw, no impulse
        hs.d.taut = true;
        out.push_back(make_event(type, hs, before));
      }
      break;
    case EventType::rope_slack:
      to_cartesian(hs, k0);
      hs.d.taut = false;
      hs.d.lid_resting = false;
      out.push_back(make_event(type, hs, before));
      break;
    case EventType::lid_rests:
      hs.d.lid_resting = true;
      if (hs.d.polar()) {  // M4 -> M5: lid, seesaw and the sandbag's motion across the arm stop
        hs.y[slot::dphi_s] = 0.0;
        Event e = make_event(type, hs, before);
        e.impact = true;
        e.energy_before = energy(k0);
        out.push_back(e);
        settle(hs, out);
      } else {
        hs.y[slot::phi_l] = phi_l0_;
        hs.y[slot::dphi_l] = 0.0;
        Event e = make_event(type, hs, before);
        e.energy_before = energy(k0);
        out.push_back(e);
      }
      break;
    case EventType::lid_lifts:
      hs.d.lid_resting = false;
      hs.y[slot::dphi_s] = 0.0;
      out.push_back(make_event(type, hs, before));
      settle(hs, out);
      break;
    case EventType::balloon_caught: {
      hs.d.balloon_stuck = true;
      out.push_back(make_event(type, hs, before));
      // Caught by a lid that accelerates away faster than the balloon can: it touches and parts.
      if (limit_.acceleration(k0.phi_l, k0.dphi_l, k0.ddphi_l) > a_b_) {
        hs.d.balloon_stuck = false;
        hs.y[slot::balloon_h] = limit_.height(k0.phi_l);
        hs.y[slot::balloon_v] = limit_rate0;
        out.push_back(make_event(EventType::balloon_free, hs, before));
      }
      return false;
    }
    case EventType::balloon_free:
      hs.d.balloon_stuck = false;
      hs.y[slot::balloon_h] = limit_.height(k0.phi_l);
      hs.y[slot::balloon_v] = limit_rate0;
      out.push_back(make_event(type, hs, before));
      return false;
    default:  // stops
      out.push_back(make_event(type, hs, before));
      return true;
  }
  release_balloon_if_lid_jumped(hs, limit_rate0, out);
  return false;
}

void Model::timeout(HybridState& hs, std::vector<Event>& out) const {
  out.push_back(make_event(EventType::timeout, hs, hs.d.mode()));
}

}  // namespace whatnext
