#include "whatnext/model.hpp"

#include <cmath>

namespace whatnext {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kContact = 1e-9;  // MODEL.md: "on" and "taut" at the start within 1e-9 m
constexpr double kNoEnd = std::numeric_limits<double>::infinity();  // MODEL.md's endless arm
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
    case kGuardFallsOff: return EventType::sandbag_falls_off;
    case kGuardLeaves: return EventType::sandbag_leaves;
    case kGuardRadioOn: return EventType::radio_on;
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
      vertical_(kHalfPi - scenario.run.vertical_margin),
      drag_(scenario.machine.balloon_drag_rate()),
      m_b_(scenario.machine.balloon_inertia()),
      i_s_(scenario.machine.seesaw_inertia),
      w_s_(scenario.machine.seesaw_mass * scenario.machine.seesaw_com_offset),
      c_p_(scenario.machine.pivot_damping),
      c_l_(scenario.machine.lid_hinge_damping),
      arm_(scenario.machine.seesaw_left_arm),
      heavy_(scenario.machine.heavy_seesaw()),
      radio_(scenario.machine.radio),
      switch_(scenario.machine.radio_switch),
      string_(scenario.machine.string_length),
      balloon_x_(scenario.machine.hinge.x + scenario.machine.lid_half_length) {}

// --- flows -------------------------------------------------------------------------------------

double Model::lid_free_acceleration(double phi_l, double dphi_l) const {
  return (-m_l_ * g_ * r_l_ * std::cos(phi_l) - c_l_ * dphi_l) / i_l_;
}

double Model::seesaw_load(bool on, double r, double phi_s) const {
  return (on ? m_s_ * r * std::cos(phi_s) : 0.0) - w_s_ * std::cos(phi_s);
}

Model::Swing Model::swing(bool on, bool taut, double r, double phi_s, double dr,
                          double dphi_s) const {
  // J phiS'' = Q with J = I_S + [on] m_S r^2 + [taut] I_L k^2. With I_S = 0, no seesaw weight and no
  // damping (MODEL.md) the extra terms are exact zeros and this is eqs. (3) and (4) of the paper.
  Swing p{};
  double num = -w_s_ * g_ * std::cos(phi_s) - c_p_ * dphi_s;
  double den = i_s_;
  if (on) {
    p.ddr = g_ * std::sin(phi_s) + r * dphi_s * dphi_s;
    num += m_s_ * g_ * r * std::cos(phi_s) - 2.0 * m_s_ * r * dr * dphi_s;
    den += m_s_ * r * r;
  }
  if (taut) {  // the lid on the rope's closure phiL(phiS), with analytic k, k'
    // One call for phiL, cos phiL, k and k': this is the flow's hot path (see docs/performance.md).
    const RopeGeometry::Closure c = rope_.closure(phi_s);
    p.phi_l = c.phi_l;
    p.tr = c.transfer;
    const double k = p.tr.k;
    num -= (m_l_ * g_ * r_l_ * c.cos_phi_l + i_l_ * p.tr.dk * dphi_s * dphi_s) * k +
           c_l_ * k * k * dphi_s;
    den += i_l_ * k * k;
  }
  p.ddphi_s = num / den;
  return p;
}

void Model::flow(const Discrete& d, const State& y, State& dy) const {
  dy.fill(0.0);
  if (d.polar()) {
    dy[slot::r] = y[slot::dr];
    dy[slot::phi_s] = y[slot::dphi_s];
    if (d.taut && d.lid_resting) {  // M5: seesaw held by the rope, sandbag slides on the fixed arm
      dy[slot::dr] = g_ * std::sin(y[slot::phi_s]);
    } else {  // M4, or a heavy seesaw carrying the sandbag
      const Swing p = swing(true, d.taut, y[slot::r], y[slot::phi_s], y[slot::dr], y[slot::dphi_s]);
      dy[slot::dr] = p.ddr;
      dy[slot::dphi_s] = p.ddphi_s;
    }
    if (!d.taut && !d.lid_resting) {
      dy[slot::phi_l] = y[slot::dphi_l];
      dy[slot::dphi_l] = lid_free_acceleration(y[slot::phi_l], y[slot::dphi_l]);
    }
  } else {
    // Sandbag in free fall. On the seesaw with the rope slack (M3) this is the paper's polar free
    // fall written in Cartesian form: the same motion, regular at r = 0, and exact for any RK method.
    dy[slot::x] = y[slot::vx];
    dy[slot::h] = y[slot::vh];
    dy[slot::vh] = -g_;
    const bool lid_on_rope = d.heavy && d.taut;  // then the lid follows the heavy seesaw
    if (!d.lid_resting && !d.latched && !lid_on_rope) {
      dy[slot::phi_l] = y[slot::dphi_l];
      dy[slot::dphi_l] = lid_free_acceleration(y[slot::phi_l], y[slot::dphi_l]);
    }
    if (d.heavy && !(d.taut && d.lid_resting)) {  // the unloaded heavy seesaw swings
      const Swing p = swing(false, d.taut, 0.0, y[slot::seesaw_phi], 0.0, y[slot::seesaw_dphi]);
      dy[slot::seesaw_phi] = y[slot::seesaw_dphi];
      dy[slot::seesaw_dphi] = p.ddphi_s;
    }
  }
  if (!d.balloon_stuck) {
    dy[slot::balloon_h] = y[slot::balloon_v];
    dy[slot::balloon_v] = balloon_acceleration(y[slot::balloon_v]);
  }
  if (c_p_ > 0.0 || c_l_ > 0.0 || drag_ > 0.0) dissipation(d, kinematics(d, y), dy);
}

void Model::dissipation(const Discrete& d, const Kinematics& k, State& dy) const {
  // Power turned into heat. The pivot's damper acts where the seesaw has inertia or is coupled
  // to the lid (M4); a massless seesaw elsewhere carries no load that could resist it.
  if (d.heavy || (d.on_seesaw && d.taut)) dy[slot::lost_pivot] = c_p_ * k.dphi_s * k.dphi_s;
  dy[slot::lost_hinge] = c_l_ * k.dphi_l * k.dphi_l;
  const double v = std::fabs(k.balloon_v);
  dy[slot::lost_drag] = m_b_ * drag_ * v * v * v;
}

// --- kinematics --------------------------------------------------------------------------------

Kinematics Model::kinematics(const Discrete& d, const State& y) const {
  Kinematics k;
  auto free_lid = [&] {
    if (d.lid_resting) {
      k.phi_l = phi_l0_;
    } else if (d.latched) {
      k.phi_l = y[slot::phi_l];
    } else {
      k.phi_l = y[slot::phi_l];
      k.dphi_l = y[slot::dphi_l];
      k.ddphi_l = lid_free_acceleration(k.phi_l, k.dphi_l);
    }
  };
  if (d.polar()) {
    k.r = y[slot::r];
    k.phi_s = y[slot::phi_s];
    k.dr = y[slot::dr];
    k.dphi_s = y[slot::dphi_s];
    if (!d.taut) {  // a heavy seesaw carrying the sandbag, the lid on its own
      k.ddphi_s = swing(true, false, k.r, k.phi_s, k.dr, k.dphi_s).ddphi_s;
      free_lid();
    } else if (d.lid_resting) {
      k.phi_l = phi_l0_;
      k.transfer = rope_.transfer(k.phi_s, k.phi_l);
    } else {
      const Swing p = swing(true, true, k.r, k.phi_s, k.dr, k.dphi_s);
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
  } else {
    k.x = y[slot::x];
    k.h = y[slot::h];
    k.vx = y[slot::vx];
    k.vh = y[slot::vh];
    k.r = std::hypot(k.x, k.h);
    k.dr = k.r > 0.0 ? (k.x * k.vx + k.h * k.vh) / k.r : 0.0;
    if (!(d.heavy && d.taut)) free_lid();
    if (d.on_seesaw) {  // M3: the massless seesaw turns with the sandbag
      k.phi_s = std::atan2(-k.h, -k.x);
      const double c = std::cos(k.phi_s), s = std::sin(k.phi_s);
      k.dphi_s = (k.vx * s - k.vh * c) / k.r;
      k.ddphi_s = (g_ * c - 2.0 * k.dr * k.dphi_s) / k.r;
    } else if (d.heavy) {  // the unloaded heavy seesaw, on its own or with the lid on the rope
      k.phi_s = y[slot::seesaw_phi];
      k.dphi_s = y[slot::seesaw_dphi];
      if (d.taut && d.lid_resting) {
        k.phi_l = phi_l0_;
        k.transfer = rope_.transfer(k.phi_s, k.phi_l);
      } else {
        const Swing p = swing(false, d.taut, 0.0, k.phi_s, 0.0, k.dphi_s);
        k.ddphi_s = p.ddphi_s;
        if (d.taut) {
          k.phi_l = p.phi_l;
          k.transfer = p.tr;
          k.dphi_l = p.tr.k * k.dphi_s;
          k.ddphi_l = p.tr.k * p.ddphi_s + p.tr.dk * k.dphi_s * k.dphi_s;
        }
      }
    } else if (d.taut) {  // M2: the unloaded seesaw follows the lid
      k.phi_s = d.parked_seesaw;  // exact while the lid rests, the branch hint otherwise
      if (!d.lid_resting) rope_.seesaw_angle_for(k.phi_l, d.parked_seesaw, k.phi_s);
      k.transfer = rope_.transfer(k.phi_s, k.phi_l);
      k.dphi_s = d.lid_resting ? 0.0 : k.dphi_l / k.transfer.k;
    } else {  // M1: nothing moves the unloaded seesaw
      k.phi_s = d.parked_seesaw;
    }
  }
  if (d.balloon_stuck) {
    k.balloon_h = limit_.height(k.phi_l);
    k.balloon_v = limit_.rate(k.phi_l, k.dphi_l);
  } else {
    k.balloon_h = y[slot::balloon_h];
    k.balloon_v = y[slot::balloon_v];
  }
  return k;
}

double Model::lid_rope_torque(const Kinematics& k) const {
  // Torque the rope must supply to the lid: I phiL'' + m_L g r_L cos phiL (+ the hinge damper's
  // c phiL') — the paper's connecting-rod check: the rope can only pull, so it goes slack when
  // this is negative.
  return i_l_ * k.ddphi_l + m_l_ * g_ * r_l_ * std::cos(k.phi_l) + c_l_ * k.dphi_l;
}

bool Model::lid_lifts_now(bool on, double r, double phi_s) const {
  const double k = rope_.transfer(phi_s, phi_l0_).k;
  // >= so that it agrees exactly with the lid_lifts guard at the instant that guard fires.
  return seesaw_load(on, r, phi_s) >= k * m_l_ * r_l_ * std::cos(phi_l0_);
}

double Model::normal_force(const Kinematics& k) const {
  // Newton across the arm: N = m_S (g cos phiS - 2 r' phiS' - r phiS'').
  return m_s_ * (g_ * std::cos(k.phi_s) - 2.0 * k.dr * k.dphi_s - k.r * k.ddphi_s);
}

double Model::radio_gap(double balloon_h) const {
  // Distance from the switch to the balloon's centre, minus the string: >= 0 when it is straight.
  const Vec2 b{balloon_x_ - switch_.x, rope_.hinge().h + balloon_h - switch_.h};
  return std::hypot(b.x, b.h) - string_;
}

double Model::energy(const Kinematics& k) const {
  return 0.5 * m_s_ * (k.vx * k.vx + k.vh * k.vh) + m_s_ * g_ * k.h +
         0.5 * i_l_ * k.dphi_l * k.dphi_l + m_l_ * g_ * r_l_ * std::sin(k.phi_l) +
         0.5 * i_s_ * k.dphi_s * k.dphi_s + w_s_ * g_ * std::sin(k.phi_s);
}

double Model::balloon_energy(double h, double v) const {
  return 0.5 * m_b_ * v * v - m_b_ * a_b_ * h;
}

double Model::lid_push_now(const Discrete& d, const Kinematics& k, const State& y) const {
  // While stuck the balloon's energy changes only by the lid's push and the air drag.
  const Books& b = d.books;
  if (!d.balloon_stuck) return b.lid_push;
  return b.lid_push + (balloon_energy(k.balloon_h, k.balloon_v) - b.balloon_e_mark) +
         (y[slot::lost_drag] - b.drag_mark);
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
  s.balloon_h = k.balloon_h;
  s.balloon_v = k.balloon_v;
  if (s.mode == Mode::M4) {
    s.tension = lid_rope_torque(k) / rope_.lid_arm(k.phi_s, k.phi_l);
  } else if (s.mode == Mode::M5) {
    // The fixed arm carries the sandbag's normal force m g cos phiS at distance r; the rope balances it.
    s.tension = (m_s_ * g_ * std::cos(k.phi_s) * k.r - w_s_ * g_ * std::cos(k.phi_s)) /
                rope_.seesaw_arm(k.phi_s, k.phi_l);
  }
  if (hs.d.on_seesaw) s.normal_force = normal_force(k);
  s.sandbag_kinetic = 0.5 * m_s_ * (k.vx * k.vx + k.vh * k.vh);
  s.sandbag_potential = m_s_ * g_ * k.h;
  s.lid_kinetic = 0.5 * i_l_ * k.dphi_l * k.dphi_l;
  s.lid_potential = m_l_ * g_ * r_l_ * std::sin(k.phi_l);
  s.seesaw_kinetic = 0.5 * i_s_ * k.dphi_s * k.dphi_s;
  s.seesaw_potential = w_s_ * g_ * std::sin(k.phi_s);
  s.balloon_kinetic = 0.5 * m_b_ * k.balloon_v * k.balloon_v;
  s.balloon_potential = -m_b_ * a_b_ * k.balloon_h;
  const Books& b = hs.d.books;
  s.lost_impacts = b.impacts;
  s.lost_balloon_catch = b.balloon_catch;
  s.dissipated_pivot = hs.y[slot::lost_pivot];
  s.dissipated_hinge = hs.y[slot::lost_hinge];
  s.dissipated_drag = hs.y[slot::lost_drag];
  s.lid_push_work = lid_push_now(hs.d, k, hs.y);
  s.initial_total = b.initial_total;
  return s;
}

// --- guards ------------------------------------------------------------------------------------

void Model::guards(const Discrete& d, const State& y, GuardValues& g) const {
  g.fill(kInactive);
  const Kinematics k = kinematics(d, y);
  if (radio_) g[kGuardRadioOn] = radio_gap(k.balloon_h);
  if (d.balloon_stuck) {
    g[kGuardBalloonFree] =
        limit_.acceleration(k.phi_l, k.dphi_l, k.ddphi_l) - balloon_acceleration(k.balloon_v);
  } else if (!d.latched) {
    g[kGuardBalloonCaught] = y[slot::balloon_h] - limit_.height(k.phi_l);
  }
  if (d.latched) return;  // the radio's wait: only the balloon matters now
  if (!d.on_seesaw && !d.fallen_off) {
    // Height of the sandbag above the left arm's line, measured across the arm; it can only land
    // where the arm is (a finite arm ends at seesaw_left_arm).
    const double along = -k.x * std::cos(k.phi_s) - k.h * std::sin(k.phi_s);
    const double below = -(-k.x * std::sin(k.phi_s) + k.h * std::cos(k.phi_s));
    // Passing the arm's line beyond its end is missing the arm for good (sandbag_falls_off).
    g[along <= arm_ ? kGuardLands : kGuardFallsOff] = below;
  }
  if (!d.taut) g[kGuardRopeTaut] = rope_.gap(k.phi_s, k.phi_l);
  g[kGuardLidOpen] = k.phi_l - vertical_;  // a lid resting at or past it is open from the start
  if (!d.lid_resting) g[kGuardLidRests] = phi_l0_ - k.phi_l;
  if (d.taut && (d.on_seesaw || d.heavy)) {  // something with inertia hangs on the rope
    if (d.lid_resting) {
      const double load = seesaw_load(d.on_seesaw, k.r, k.phi_s);
      g[kGuardLidLifts] = load - k.transfer.k * m_l_ * r_l_ * std::cos(phi_l0_);
      if (d.heavy) g[kGuardRopeSlack] = -load;  // the seesaw tips back: nothing pulls the rope
    } else {
      g[kGuardRopeSlack] = -lid_rope_torque(k);
      g[kGuardRopeLocked] = std::fabs(rope_.cos_sigma(k.phi_s)) - (1.0 - 1e-9);
    }
  }
  if (d.polar()) {
    g[kGuardAtPivot] = -k.r;
  } else if (d.on_seesaw) {
    // A free-falling sandbag can only leave the left arm through the pivot's vertical line.
    g[kGuardAtPivot] = k.x;
  }
  if (d.on_seesaw) {
    g[kGuardSeesawVertical] = k.phi_s - vertical_;
    if (arm_ < kNoEnd) g[kGuardFallsOff] = k.r - arm_;
    if (d.heavy && !(d.taut && d.lid_resting)) g[kGuardLeaves] = -normal_force(k);
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
  hs.d.heavy = heavy_;
  const double c = std::cos(st.seesaw_angle), s = std::sin(st.seesaw_angle);
  const double above = -st.sandbag_x * s + st.sandbag_h * c;
  hs.d.on_seesaw = std::fabs(above) <= kContact;
  hs.d.taut = rope_.span(st.seesaw_angle, phi_l0_) >= rope_.rope_length() - kContact;
  if (hs.d.polar()) {
    const double r = -st.sandbag_x * c - st.sandbag_h * s;
    hs.y = {r, st.seesaw_angle, 0.0, 0.0, phi_l0_, 0.0, 0.0, 0.0};
  } else {
    hs.y = {st.sandbag_x, st.sandbag_h, 0.0, 0.0, phi_l0_, 0.0, 0.0, 0.0};
    if (hs.d.on_seesaw) {
      // Placed on the arm: the polar and the Cartesian pictures agree exactly on the arm's line.
      hs.y[slot::x] = -std::hypot(st.sandbag_x, st.sandbag_h) * c;
      hs.y[slot::h] = -std::hypot(st.sandbag_x, st.sandbag_h) * s;
    }
  }
  hs.y[slot::seesaw_phi] = st.seesaw_angle;
  if (hs.d.taut && (hs.d.on_seesaw || hs.d.heavy)) {
    const double r = hs.d.on_seesaw ? hs.y[slot::r] : 0.0;
    hs.d.lid_resting = !lid_lifts_now(hs.d.on_seesaw, r, st.seesaw_angle);
    // A heavy seesaw that tips the other way does not pull the straight rope.
    if (hs.d.heavy && hs.d.lid_resting && seesaw_load(hs.d.on_seesaw, r, st.seesaw_angle) < 0.0) {
      hs.d.taut = false;
    }
  }
  hs.y[slot::balloon_h] = limit_.height(phi_l0_);
  const Kinematics k = kinematics(hs.d, hs.y);
  Books& b = hs.d.books;
  b.initial_total = energy(k) + balloon_energy(k.balloon_h, k.balloon_v);
  b.balloon_e_mark = balloon_energy(k.balloon_h, k.balloon_v);  // nothing pushed yet
  open_books(hs, k);
  return hs;
}

void Model::impact(HybridState& hs, const Kinematics& b, bool bag, bool rope) const {
  // Sudden coupling of sandbag (bag), seesaw and lid (rope): r' keeps the sandbag's speed along
  // the arm (eq. 5), phiS' jumps by the chosen law, and afterwards phiL' = k phiS'. A heavy
  // seesaw brings its own angular momentum I_S phiS'- (zero for MODEL.md's massless seesaw).
  const double c = std::cos(b.phi_s), s = std::sin(b.phi_s);
  const double r = -b.x * c - b.h * s;
  const double v_par = -b.vx * c - b.vh * s;
  const double v_perp = b.vx * s - b.vh * c;
  const double k = rope ? rope_.transfer(b.phi_s, b.phi_l).k : 0.0;
  const double m = bag ? m_s_ : 0.0;
  const double w0 = b.dphi_l, ws = b.dphi_s;
  double dr = v_par, dphi_s = 0.0;
  const double rope_num = m * r * v_perp + k * i_l_ * w0 + i_s_ * ws;
  const double rope_den = m * r * r + i_l_ * k * k + i_s_;
  // Landing on a heavy seesaw with the rope slack: the lid is not involved, and every law reduces
  // to the perfectly inelastic one (angular momentum about the pivot).
  const ImpactLaw law = rope ? sc_.run.impact_law : ImpactLaw::rope;
  switch (law) {
    case ImpactLaw::rope:  // eq. (7): inelastic impulse along the rope
      dphi_s = rope_num / rope_den;
      break;
    case ImpactLaw::angular_momentum_sum:
      dphi_s = (m * r * v_perp + i_l_ * w0 + i_s_ * ws) / (m * r * r + i_l_ * k + i_s_);
      break;
    case ImpactLaw::kinetic_energy: {
      const double mag =
          std::sqrt((m * v_perp * v_perp + i_l_ * w0 * w0 + i_s_ * ws * ws) / rope_den);
      dphi_s = rope_num < 0.0 ? -mag : mag;
      break;
    }
    case ImpactLaw::linear_momentum: {
      if (!bag) {  // no sandbag in the impact: nothing for this law to say; inelastic instead
        dphi_s = rope_num / rope_den;
        break;
      }
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
  if (rope) {
    hs.d.taut = true;
    hs.d.lid_resting = false;
  }
  if (bag) {
    hs.d.on_seesaw = true;
    hs.y[slot::r] = r;
    hs.y[slot::phi_s] = b.phi_s;
    hs.y[slot::dr] = dr;
    hs.y[slot::dphi_s] = dphi_s;
  } else {
    hs.y[slot::seesaw_phi] = b.phi_s;
    hs.y[slot::seesaw_dphi] = dphi_s;
  }
}

void Model::place(HybridState& hs, const Kinematics& k) const {
  if (hs.d.polar()) {
    hs.y[slot::r] = k.r;
    hs.y[slot::phi_s] = k.phi_s;
    hs.y[slot::dr] = k.dr;
    hs.y[slot::dphi_s] = k.dphi_s;
  } else {
    hs.y[slot::x] = k.x;
    hs.y[slot::h] = k.h;
    hs.y[slot::vx] = k.vx;
    hs.y[slot::vh] = k.vh;
  }
  hs.y[slot::phi_l] = k.phi_l;
  hs.y[slot::dphi_l] = k.dphi_l;
  hs.y[slot::seesaw_phi] = k.phi_s;
  hs.y[slot::seesaw_dphi] = k.dphi_s;
}

void Model::set_seesaw_rate(HybridState& hs, double rate) const {
  hs.y[hs.d.polar() ? slot::dphi_s : slot::seesaw_dphi] = rate;
}

void Model::open_books(HybridState& hs, const Kinematics& k) const {
  Books& b = hs.d.books;
  b.lid_push = lid_push_now(hs.d, k, hs.y);
  b.machine_mark = energy(k);
  b.balloon_v_mark = k.balloon_v;
  b.balloon_e_mark = balloon_energy(k.balloon_h, k.balloon_v);
  b.drag_mark = hs.y[slot::lost_drag];
}

void Model::book(HybridState& hs) const {
  // What the jump changed: the machine's energy drop is an impact loss; a forced change of the
  // balloon's velocity from v to V (the lid's) loses (1/2) m (V - v)^2 and the lid's impulse
  // m (V - v) does the work m (V - v) V.
  const Kinematics k = kinematics(hs.d, hs.y);
  Books& b = hs.d.books;
  const double e = energy(k);
  b.impacts += b.machine_mark - e;
  b.machine_mark = e;
  const double v = k.balloon_v, dv = v - b.balloon_v_mark;
  b.balloon_catch += 0.5 * m_b_ * dv * dv;
  b.lid_push += m_b_ * v * dv;
  b.balloon_v_mark = v;
  b.balloon_e_mark = balloon_energy(k.balloon_h, v);
  b.drag_mark = hs.y[slot::lost_drag];
}

Event Model::make_event(EventType type, HybridState& hs, Mode before) const {
  book(hs);
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
  // Right after a jump that leaves something with inertia on a taut rope, decide between M4 and
  // M5 and apply MODEL.md's immediate checks (lid lifting, rope going slack at once); on a heavy
  // seesaw also whether the sandbag leaves the arm at once.

  // Lets go of the rope (or of the sandbag) where it is, with no impulse, and reports it.
  auto part = [&](const Kinematics& k, EventType type) {
    const Mode m = hs.d.mode();
    if (type == EventType::sandbag_leaves) {
      hs.d.on_seesaw = false;
    } else {
      hs.d.taut = false;
    }
    place(hs, k);
    out.push_back(make_event(type, hs, m));
  };
  if (hs.d.taut && (hs.d.on_seesaw || hs.d.heavy)) {
    if (!hs.d.lid_resting) {
      const Kinematics k = kinematics(hs.d, hs.y);
      // The box stops a lid left moving down, or left at rest with too little pull to lift it
      // (a lid that has just lifted, at rest but pulled hard enough, goes on lifting).
      // A heavy seesaw of vanishing inertia jerks the resting lid up by less than the contact
      // tolerance before it falls back: too brief for any step to see, so the box stops it here.
      const double rise = k.ddphi_l < 0.0 ? r_l_ * k.dphi_l * k.dphi_l / -k.ddphi_l : kNoEnd;
      const bool twitch = hs.d.heavy && k.dphi_l > 0.0 && rise < kContact;
      if (k.phi_l <= phi_l0_ + 1e-12 &&
          (k.dphi_l < 0.0 || twitch ||
           (k.dphi_l == 0.0 && !lid_lifts_now(hs.d.on_seesaw, k.r, k.phi_s)))) {
        hs.d.lid_resting = true;
        set_seesaw_rate(hs, 0.0);
      }
    }
    bool pulling = true;
    if (hs.d.lid_resting) {
      const Kinematics k = kinematics(hs.d, hs.y);
      const Mode m = hs.d.mode();
      if (lid_lifts_now(hs.d.on_seesaw, k.r, k.phi_s)) {
        hs.d.lid_resting = false;
        set_seesaw_rate(hs, 0.0);
        out.push_back(make_event(EventType::lid_lifts, hs, m));
      } else {
        pulling = false;
        if (hs.d.heavy && seesaw_load(hs.d.on_seesaw, k.r, k.phi_s) < 0.0) part(k, EventType::rope_slack);
      }
    }
    if (pulling) {
      const Kinematics k = kinematics(hs.d, hs.y);
      if (lid_rope_torque(k) < 0.0) part(k, EventType::rope_slack);
    }
  }
  if (hs.d.heavy && hs.d.on_seesaw && !(hs.d.taut && hs.d.lid_resting)) {
    const Kinematics k = kinematics(hs.d, hs.y);
    if (normal_force(k) < 0.0) part(k, EventType::sandbag_leaves);
  }
}

void Model::free_balloon(HybridState& hs, const Kinematics& k, double v) const {
  hs.d.balloon_stuck = false;
  hs.y[slot::balloon_h] = limit_.height(k.phi_l);
  hs.y[slot::balloon_v] = v;
}

void Model::release_balloon_if_lid_jumped(HybridState& hs, double limit_rate_before,
                                          const Books& opened, std::vector<Event>& out) const {
  if (!hs.d.balloon_stuck) return;
  const Kinematics k = kinematics(hs.d, hs.y);
  const double rate = limit_.rate(k.phi_l, k.dphi_l);
  if (rate > limit_rate_before + 1e-12 * (1.0 + std::fabs(limit_rate_before))) {
    // The lid jumped away faster than the balloon moves: it keeps its own velocity, so the
    // balloon's side of the books is as it was before the jump.
    const Mode m = hs.d.mode();
    free_balloon(hs, k, limit_rate_before);
    Books& b = hs.d.books;
    b.balloon_catch = opened.balloon_catch;
    b.lid_push = opened.lid_push;
    b.balloon_v_mark = opened.balloon_v_mark;
    out.push_back(make_event(EventType::balloon_free, hs, m));
  }
}

bool Model::jump(Guard fired, HybridState& hs, std::vector<Event>& out) const {
  const Mode before = hs.d.mode();
  const Kinematics k0 = kinematics(hs.d, hs.y);
  const double limit_rate0 = limit_.rate(k0.phi_l, k0.dphi_l);
  open_books(hs, k0);
  const Books opened = hs.d.books;
  EventType type = event_of(fired);
  // MODEL.md: the model ends when the sandbag reaches the pivot. As r -> 0 the rope's pull on the
  // lid vanishes too, so rope_slack and sandbag_at_pivot arrive together; the pivot wins.
  if (hs.d.on_seesaw && k0.r <= kContact && !is_stop(type)) type = EventType::sandbag_at_pivot;
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
        impact(hs, k0, true, true);
        emit_impact();
        settle(hs, out);
      } else if (hs.d.heavy) {  // the heavy seesaw takes its share of the blow
        impact(hs, k0, type == EventType::sandbag_lands, type == EventType::rope_taut);
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
      hs.d.taut = false;
      place(hs, k0);
      out.push_back(make_event(type, hs, before));
      settle(hs, out);
      break;
    case EventType::lid_rests:
      hs.d.lid_resting = true;
      if (hs.d.taut && (hs.d.on_seesaw || hs.d.heavy)) {
        // M4 -> M5: lid, seesaw and the sandbag's motion across the arm stop together
        set_seesaw_rate(hs, 0.0);
        emit_impact();
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
      set_seesaw_rate(hs, 0.0);
      out.push_back(make_event(type, hs, before));
      settle(hs, out);
      break;
    case EventType::sandbag_falls_off:
    case EventType::sandbag_leaves:
      // Off the arm into free fall, velocity kept; past the end of the arm for good.
      hs.d.on_seesaw = false;
      hs.d.fallen_off = hs.d.fallen_off || type == EventType::sandbag_falls_off;
      hs.d.parked_seesaw = k0.phi_s;
      place(hs, k0);
      out.push_back(make_event(type, hs, before));
      settle(hs, out);
      break;
    case EventType::balloon_caught: {
      hs.d.balloon_stuck = true;
      out.push_back(make_event(type, hs, before));
      // Caught by a lid that accelerates away faster than the balloon can: it touches and parts.
      if (limit_.acceleration(k0.phi_l, k0.dphi_l, k0.ddphi_l) > balloon_acceleration(limit_rate0)) {
        free_balloon(hs, k0, limit_rate0);
        out.push_back(make_event(EventType::balloon_free, hs, before));
      }
      return false;
    }
    case EventType::balloon_free:
      free_balloon(hs, k0, limit_rate0);
      out.push_back(make_event(type, hs, before));
      return false;
    case EventType::lid_open:
      if (!radio_) {
        out.push_back(make_event(type, hs, before));
        return true;
      }
      {
        // The radio's question goes on: the lid latches open where it is (its kinetic energy is
        // lost to the latch), the rope is let go for good, the sandbag falls freely off the
        // story and the balloon rises without a limit.
        hs.d.latched = true;
        hs.d.lid_resting = false;
        hs.d.taut = false;
        hs.d.on_seesaw = false;
        hs.d.parked_seesaw = k0.phi_s;
        Kinematics k = k0;
        k.dphi_l = 0.0;
        place(hs, k);
        out.push_back(make_event(type, hs, before));
        if (hs.d.balloon_stuck) {
          const Mode m = hs.d.mode();
          free_balloon(hs, k0, limit_rate0);
          out.push_back(make_event(EventType::balloon_free, hs, m));
        }
      }
      return false;
    default:  // stops
      out.push_back(make_event(type, hs, before));
      return true;
  }
  release_balloon_if_lid_jumped(hs, limit_rate0, opened, out);
  book(hs);  // a jump may end with a settling that no event reports
  return false;
}

void Model::timeout(HybridState& hs, std::vector<Event>& out) const {
  open_books(hs, kinematics(hs.d, hs.y));
  out.push_back(make_event(EventType::timeout, hs, hs.d.mode()));
}

}  // namespace whatnext
