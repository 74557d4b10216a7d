#include "whatnext/model.hpp"

#include <cmath>
#include <cstdio>
#include <string>

#include "whatnext/simulate.hpp"

namespace whatnext {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kContact = 1e-9;  // MODEL.md: touching (on the arm, rope straight) within 1e-9 m
constexpr double kNoEnd = std::numeric_limits<double>::infinity();  // MODEL.md's endless arm
// Lead of an armed guard whose first non-zero derivative is not known (a force that just reached
// zero): only its sign matters to the integrators.
constexpr double kUnknownLead = -1e-300;

using contact::Set;
constexpr Set bit(int i) { return 1u << i; }

Guard guard_of(int contact) {
  return contact == kBag ? kGuardBag : (contact == kRope ? kGuardRope : kGuardLid);
}

EventType change_event(int contact, bool closes) {
  switch (contact) {
    case kBag: return closes ? EventType::sandbag_lands : EventType::sandbag_leaves;
    case kRope: return closes ? EventType::rope_taut : EventType::rope_slack;
    default: return closes ? EventType::lid_rests : EventType::lid_lifts;
  }
}

Mode mode_of(Set s) { return Discrete::mode_of(contact::has(s, kBag), contact::has(s, kRope), contact::has(s, kLid)); }
}  // namespace

bool fires_at_once(Guard g) {
  // A contact guard at zero is a contact that touches (decided where the piece starts); the balloon
  // is decided by the model (Model::jump) since it is both kinds.
  return !(g == kGuardBag || g == kGuardRope || g == kGuardLid || g == kGuardBalloon);
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
      balloon_x_(scenario.machine.hinge.x + scenario.machine.lid_half_length),
      length_scale_(scenario.machine.seesaw_right_arm + 2.0 * scenario.machine.lid_half_length +
                    scenario.machine.rope_length) {}

// --- flows -------------------------------------------------------------------------------------

double Model::lid_free_acceleration(double phi_l, double dphi_l) const {
  return (-m_l_ * g_ * r_l_ * std::cos(phi_l) - c_l_ * dphi_l) / i_l_;
}

namespace {
template <class Memo>
bool recall(const Memo& m, int flags, double a, double b, double c, double d) {
  return m.valid && m.flags == flags && m.args[0] == a && m.args[1] == b && m.args[2] == c && m.args[3] == d;
}
template <class Memo, class Value>
const Value& remember(Memo& m, int flags, double a, double b, double c, double d, const Value& v) {
  m.valid = true, m.flags = flags;
  m.args[0] = a, m.args[1] = b, m.args[2] = c, m.args[3] = d;
  m.value = v;
  return m.value;
}
}  // namespace

Model::Swing Model::swing(bool on, bool taut, double r, double phi_s, double dr, double dphi_s) const {
  const int flags = (on ? 1 : 0) | (taut ? 2 : 0);
  if (recall(swing_memo_, flags, r, phi_s, dr, dphi_s)) return swing_memo_.value;
  return remember(swing_memo_, flags, r, phi_s, dr, dphi_s, compute_swing(on, taut, r, phi_s, dr, dphi_s));
}

Model::LidSwing Model::swing_by_lid(bool on, double r, double phi_l, double dr, double dphi_l, int side) const {
  const int flags = (on ? 1 : 0) | (side > 0 ? 2 : 0);
  if (recall(lid_swing_memo_, flags, r, phi_l, dr, dphi_l)) return lid_swing_memo_.value;
  return remember(lid_swing_memo_, flags, r, phi_l, dr, dphi_l, compute_swing_by_lid(on, r, phi_l, dr, dphi_l, side));
}

Model::Swing Model::compute_swing(bool on, bool taut, double r, double phi_s, double dr,
                                  double dphi_s) const {
  // J phiS'' = Q with J = I_S + [on] m_S r^2 + [taut] I_L k^2. With I_S = 0, no seesaw weight and no
  // damping (MODEL.md) the extra terms are exact zeros and this is eqs. (3) and (4) of the paper.
  // This is the flow's hot path: one sincos of phiS serves the weights and the whole linkage.
  Swing p{};
  const double cs = std::cos(phi_s), ss = std::sin(phi_s);
  if (taut) {  // the lid on the rope's closure phiL(phiS), with analytic k, k'
    p.lk = rope_.from_seesaw(cs, ss);
  } else {
    p.lk.cos_s = cs, p.lk.sin_s = ss;
  }
  double num = -w_s_ * g_ * cs - c_p_ * dphi_s;
  double den = i_s_;
  if (on) {
    p.ddr = along_arm_acceleration(r, ss, dphi_s);
    num += m_s_ * g_ * r * cs - 2.0 * m_s_ * r * dr * dphi_s;
    den += m_s_ * r * r;
  }
  if (taut) {
    const double k = p.lk.transfer.k;
    num -= (m_l_ * g_ * r_l_ * p.lk.cos_l + i_l_ * p.lk.transfer.dk * dphi_s * dphi_s) * k +
           c_l_ * k * k * dphi_s;
    den += i_l_ * k * k;
  }
  p.ddphi_s = num / den;
  return p;
}

Model::LidSwing Model::compute_swing_by_lid(bool on, double r, double phi_l, double dr, double dphi_l,
                                            int side) const {
  // Along the closure phiS = S(phiL): multiply the seesaw's equation by S' and add the lid's, and
  // the rope's force drops out (its gradient is normal to the closure). With phiS' = S' phiL' and
  // phiS'' = S' phiL'' + S'' phiL'^2:
  //   [(I_S + m r^2) S'^2 + I_L] phiL'' = S' Q_S + Q_L - (I_S + m r^2) S' S'' phiL'^2 - 2 m r r' S'^2 phiL'
  // with Q_S, Q_L the weights' and dampers' torques. Finite where k = 1/S' is not.
  LidSwing p{};
  p.lk = rope_.from_lid(std::cos(phi_l), std::sin(phi_l), side);
  const double ds = p.lk.ds, dphi_s = ds * dphi_l;
  const double cs = p.lk.cos_s;
  const double carried = i_s_ + (on ? m_s_ * r * r : 0.0);
  double q_s = -w_s_ * g_ * cs - c_p_ * dphi_s;
  if (on) {
    q_s += m_s_ * g_ * r * cs;
    p.ddr = along_arm_acceleration(r, p.lk.sin_s, dphi_s);
  }
  const double q_l = -m_l_ * g_ * r_l_ * p.lk.cos_l - c_l_ * dphi_l;
  const double num = ds * q_s + q_l - carried * ds * p.lk.dds * dphi_l * dphi_l -
                     (on ? 2.0 * m_s_ * r * dr * ds * ds * dphi_l : 0.0);
  p.ddphi_l = num / (carried * ds * ds + i_l_);
  return p;
}

void Model::flow(const Discrete& d, const State& y, State& dy) const {
  dy.fill(0.0);
  if (d.polar()) {
    dy[slot::r] = y[slot::dr];
    dy[slot::phi_s] = y[slot::dphi_s];
    if (d.taut && d.lid_resting) {  // M5: seesaw held by the rope, sandbag slides on the fixed arm
      dy[slot::dr] = along_arm_acceleration(y[slot::r], std::sin(y[slot::phi_s]), 0.0);
    } else if (d.lid_chart && d.taut) {  // M4 near the lid's dead centre: the lid's angle integrated
      const LidSwing p = swing_by_lid(true, y[slot::r], y[slot::phi_s], y[slot::dr], y[slot::dphi_s], d.side);
      dy[slot::dr] = p.ddr;
      dy[slot::dphi_s] = p.ddphi_l;
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
      dy[slot::seesaw_phi] = y[slot::seesaw_dphi];
      dy[slot::seesaw_dphi] =
          d.lid_chart && d.taut ? swing_by_lid(false, 0.0, y[slot::seesaw_phi], 0.0, y[slot::seesaw_dphi], d.side).ddphi_l
                      : swing(false, d.taut, 0.0, y[slot::seesaw_phi], 0.0, y[slot::seesaw_dphi]).ddphi_s;
    }
  }
  if (!d.balloon_stuck) {
    dy[slot::balloon_h] = y[slot::balloon_v];
    dy[slot::balloon_v] = balloon_acceleration(y[slot::balloon_v]);
  }
  if (c_p_ > 0.0 || c_l_ > 0.0 || drag_ > 0.0) dissipation(d, kinematics(d, y), dy);
}

void Model::dissipation(const Discrete& /*d*/, const Kinematics& k, State& dy) const {
  // Power turned into heat (the pivot's damper comes with a seesaw that has inertia).
  dy[slot::lost_pivot] = c_p_ * k.dphi_s * k.dphi_s;
  dy[slot::lost_hinge] = c_l_ * k.dphi_l * k.dphi_l;
  const double v = std::fabs(k.balloon_v);
  dy[slot::lost_drag] = m_b_ * drag_ * v * v * v;
}

// --- kinematics --------------------------------------------------------------------------------

Kinematics Model::kinematics(const Discrete& d, const State& y, bool rates, bool memo) const {
  Kinematics k;
  // The memos serve one thread's integration; samples made on other threads compute afresh.
  auto swing_of = [&](bool on, bool taut, double r, double phi_s, double dr, double dphi_s) {
    return memo ? swing(on, taut, r, phi_s, dr, dphi_s) : compute_swing(on, taut, r, phi_s, dr, dphi_s);
  };
  auto lid_swing_of = [&](bool on, double r, double phi_l, double dr, double dphi_l, int side) {
    return memo ? swing_by_lid(on, r, phi_l, dr, dphi_l, side) : compute_swing_by_lid(on, r, phi_l, dr, dphi_l, side);
  };
  bool trig_s = false, trig_l = false;  // cos and sin of phiS / phiL already known
  auto free_lid = [&] {
    if (d.lid_resting) {
      k.phi_l = phi_l0_;
    } else if (d.latched || !rates) {
      k.phi_l = y[slot::phi_l];
    } else {
      k.phi_l = y[slot::phi_l];
      k.dphi_l = y[slot::dphi_l];
      k.ddphi_l = lid_free_acceleration(k.phi_l, k.dphi_l);
    }
  };
  // The lid on the rope's closure, from the seesaw's swing (chart S) or the lid's (chart L).
  auto on_rope = [&](const Swing& p) {
    k.phi_l = p.lk.phi_l();
    k.transfer = p.lk.transfer;
    k.ddphi_s = p.ddphi_s;
    k.dphi_l = p.lk.transfer.k * k.dphi_s;
    k.ddphi_l = p.lk.transfer.k * p.ddphi_s + p.lk.transfer.dk * k.dphi_s * k.dphi_s;
    k.cos_l = p.lk.cos_l, k.sin_l = p.lk.sin_l;
    trig_l = true;
  };
  auto by_lid = [&](const LidSwing& p, double phi_l, double dphi_l) {
    lid_chart(k, p, phi_l, dphi_l);
    trig_s = trig_l = true;
  };
  // Positions only: the same linkage the swings start from, without their accelerations, from the
  // lid's angle (its chart) or the seesaw's.
  auto placed = [&](bool by_lid_angle, double phi) {
    const double c = std::cos(phi), sn = std::sin(phi);
    const RopeGeometry::Linkage lk =
        by_lid_angle ? rope_.from_lid(c, sn, d.side, false) : rope_.from_seesaw(c, sn, false);
    if (by_lid_angle) {
      k.phi_l = phi;
      k.phi_s = lk.phi_s();
    } else {
      k.phi_l = lk.phi_l();
    }
    k.cos_s = lk.cos_s, k.sin_s = lk.sin_s, k.cos_l = lk.cos_l, k.sin_l = lk.sin_l;
    trig_s = trig_l = true;
  };
  if (d.polar()) {
    k.r = y[slot::r];
    k.phi_s = y[slot::phi_s];
    if (rates) k.dr = y[slot::dr], k.dphi_s = y[slot::dphi_s];
    if (!d.taut) {  // a heavy seesaw carrying the sandbag, the lid on its own
      if (rates) {
        const Swing p = swing_of(true, false, k.r, k.phi_s, k.dr, k.dphi_s);
        k.ddr = p.ddr;
        k.ddphi_s = p.ddphi_s;
        k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
        trig_s = true;
      }
      free_lid();
    } else if (d.lid_resting) {
      k.phi_l = phi_l0_;
      if (rates) k.transfer = rope_.transfer(k.phi_s, k.phi_l);
    } else if (d.lid_chart) {
      const double phi_l = y[slot::phi_s];
      if (rates) {
        const LidSwing p = lid_swing_of(true, k.r, phi_l, k.dr, y[slot::dphi_s], d.side);
        k.ddr = p.ddr;
        by_lid(p, phi_l, y[slot::dphi_s]);
      } else {
        placed(true, phi_l);
      }
    } else if (rates) {
      const Swing p = swing_of(true, true, k.r, k.phi_s, k.dr, k.dphi_s);
      k.ddr = p.ddr;
      k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
      trig_s = true;
      on_rope(p);
    } else {
      placed(false, k.phi_s);
    }
    if (!trig_s) k.cos_s = std::cos(k.phi_s), k.sin_s = std::sin(k.phi_s), trig_s = true;
    const double c = k.cos_s, s = k.sin_s;
    k.x = -k.r * c;
    k.h = -k.r * s;
    if (rates && d.taut && d.lid_resting) k.ddr = along_arm_acceleration(k.r, s, 0.0);  // M5: the arm is fixed
    if (rates) {
      k.vx = -k.dr * c + k.r * s * k.dphi_s;
      k.vh = -k.dr * s - k.r * c * k.dphi_s;
    }
  } else {
    k.x = y[slot::x];
    k.h = y[slot::h];
    if (rates) k.vx = y[slot::vx], k.vh = y[slot::vh];
    k.r = std::sqrt(k.x * k.x + k.h * k.h);
    if (rates) k.dr = k.r > 0.0 ? (k.x * k.vx + k.h * k.vh) / k.r : 0.0;
    if (!(d.heavy && d.taut)) free_lid();
    if (d.on_seesaw) {  // M3: the massless seesaw turns with the sandbag
      k.phi_s = std::atan2(-k.h, -k.x);
      const double c = -k.x / k.r, s = -k.h / k.r;
      k.cos_s = c, k.sin_s = s;
      trig_s = k.r > 0.0;
      if (rates) {
        k.dphi_s = (k.vx * s - k.vh * c) / k.r;
        k.ddphi_s = (g_ * c - 2.0 * k.dr * k.dphi_s) / k.r;
      }
    } else if (d.heavy) {  // the unloaded heavy seesaw, on its own or with the lid on the rope
      k.phi_s = y[slot::seesaw_phi];
      if (rates) k.dphi_s = y[slot::seesaw_dphi];
      if (d.taut && d.lid_resting) {
        k.phi_l = phi_l0_;
        if (rates) k.transfer = rope_.transfer(k.phi_s, k.phi_l);
      } else if (d.lid_chart && d.taut) {
        const double phi_l = y[slot::seesaw_phi];
        if (rates) {
          by_lid(lid_swing_of(false, 0.0, phi_l, 0.0, y[slot::seesaw_dphi], d.side), phi_l, y[slot::seesaw_dphi]);
        } else {
          placed(true, phi_l);
        }
      } else if (rates) {
        const Swing p = swing_of(false, d.taut, 0.0, k.phi_s, 0.0, k.dphi_s);
        k.ddphi_s = p.ddphi_s;
        k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
        trig_s = true;
        if (d.taut) on_rope(p);
      } else if (d.taut) {
        placed(false, k.phi_s);
      }
    } else if (d.taut) {  // M2: the unloaded massless seesaw follows the lid, on its side of P-E
      k.phi_s = d.parked_seesaw;  // exact while the lid rests
      if (!d.lid_resting) rope_.seesaw_angle_for(k.phi_l, d.side, k.phi_s);
      if (rates) {
        k.transfer = rope_.transfer(k.phi_s, k.phi_l);
        k.dphi_s = d.lid_resting ? 0.0 : k.dphi_l / k.transfer.k;
      }
    } else {  // M1: nothing moves the unloaded seesaw
      k.phi_s = d.parked_seesaw;
    }
  }
  if (!trig_s) k.cos_s = std::cos(k.phi_s), k.sin_s = std::sin(k.phi_s);
  if (!trig_l) k.cos_l = std::cos(k.phi_l), k.sin_l = std::sin(k.phi_l);
  if (d.balloon_stuck) {
    k.balloon_h = limit_.height_at(k.cos_l, k.sin_l);
    if (rates) k.balloon_v = limit_.rate_at(k.sin_l, k.dphi_l);
  } else {
    k.balloon_h = y[slot::balloon_h];
    if (rates) k.balloon_v = y[slot::balloon_v];
  }
  return k;
}

void Model::lid_chart(Kinematics& k, const LidSwing& p, double phi_l, double dphi_l) {
  // The lid's angle and rate are the state; the seesaw follows on the closure.
  k.phi_l = phi_l;
  k.phi_s = p.lk.phi_s();
  k.dphi_l = dphi_l;
  k.dphi_s = p.lk.ds * dphi_l;
  k.ddphi_l = p.ddphi_l;
  k.ddphi_s = p.lk.ds * p.ddphi_l + p.lk.dds * dphi_l * dphi_l;
  k.transfer = p.lk.transfer;
  k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s, k.cos_l = p.lk.cos_l, k.sin_l = p.lk.sin_l;
}

double Model::height_above_arm(const Kinematics& k) { return -k.x * k.sin_s + k.h * k.cos_s; }

double Model::along_arm(const Kinematics& k) { return -k.x * k.cos_s - k.h * k.sin_s; }

Kinematics Model::with_velocity(Kinematics k, const contact::Coords& u) {
  k.vx = u[0];
  k.vh = u[1];
  k.dphi_s = u[2];
  k.dphi_l = u[3];
  // On the arm's line r is the distance along it and r' the sandbag's speed along it (eq. 5).
  k.r = along_arm(k);
  k.dr = -k.vx * std::cos(k.phi_s) - k.vh * std::sin(k.phi_s);
  return k;
}

// --- the contact problem -------------------------------------------------------------------------

contact::System Model::contact_system(const Discrete& d, const Kinematics& k) const {
  // Coordinates (x, h, phiS, phiL), diagonal masses (m_S, m_S, I_S, I_L): I_S = 0 is MODEL.md's
  // massless seesaw, held by whatever contact acts on it. The gaps, each >= 0 when open:
  //   sandbag: its height above the arm's line, -x sin phiS + h cos phiS (multiplier: the arm's push, N)
  //   rope:    l_R - |R - E|                                  (multiplier: the tension, N)
  //   lid:     phiL - phiL0                                   (multiplier: the box's push, N m)
  contact::System s;
  s.coords = 4;
  s.contacts = 3;
  s.mass = {m_s_, m_s_, i_s_, i_l_};
  s.velocity = {k.vx, k.vh, k.dphi_s, k.dphi_l};
  const double cs = k.cos_s, sn = k.sin_s, cl = k.cos_l, sl = k.sin_l;
  // The pivot's damper needs a seesaw with inertia (validation rejects it on a massless one).
  s.force = {0.0, -m_s_ * g_, -w_s_ * g_ * cs - c_p_ * k.dphi_s, -m_l_ * g_ * r_l_ * cl - c_l_ * k.dphi_l};
  (void)d;

  const double height = -k.x * sn + k.h * cs;
  s.normal[kBag] = {-sn, cs, -k.x * cs - k.h * sn, 0.0};
  s.curvature[kBag] = -2.0 * k.dphi_s * (k.vx * cs + k.vh * sn) - k.dphi_s * k.dphi_s * height;

  const Vec2 r{sc_.machine.seesaw_right_arm * cs, sc_.machine.seesaw_right_arm * sn};
  const Vec2 el{2.0 * r_l_ * cl, 2.0 * r_l_ * sl};
  const Vec2 dv = r - (rope_.hinge() + el);  // D = R - E
  const double dn = norm(dv);
  const Vec2 r_s{-r.h, r.x}, e_l{-el.h, el.x};  // dR/dphiS, dE/dphiL
  s.normal[kRope] = {0.0, 0.0, -dot(dv, r_s) / dn, dot(dv, e_l) / dn};
  const Vec2 d_rate = k.dphi_s * r_s - k.dphi_l * e_l;
  const Vec2 d_acc = (k.dphi_l * k.dphi_l) * el - (k.dphi_s * k.dphi_s) * r;  // D'' without phiS'', phiL''
  const double along = dot(dv, d_rate) / dn;
  s.curvature[kRope] = -(dot(dv, d_acc) + dot(d_rate, d_rate) - along * along) / dn;

  s.normal[kLid] = {0.0, 0.0, 0.0, 1.0};
  s.curvature[kLid] = 0.0;
  return s;
}

contact::Set Model::active_set(const Discrete& d) {
  return (d.on_seesaw ? bit(kBag) : 0u) | (d.taut ? bit(kRope) : 0u) | (d.lid_resting ? bit(kLid) : 0u);
}

contact::Coords Model::accelerations(const Discrete& d, const Kinematics& k) const {
  if (!d.polar()) return {0.0, -g_, k.ddphi_s, k.ddphi_l};  // the sandbag falls freely
  // x = -r cos phiS, h = -r sin phiS: along the arm r'' - r phiS'^2, across it 2 r' phiS' + r phiS''.
  const double along = k.ddr - k.r * k.dphi_s * k.dphi_s, across = 2.0 * k.dr * k.dphi_s + k.r * k.ddphi_s;
  return {-along * k.cos_s + across * k.sin_s, -along * k.sin_s - across * k.cos_s, k.ddphi_s, k.ddphi_l};
}

bool Model::contact_forces(const Discrete& d, const Kinematics& k, contact::PerContact& force) const {
  if (contact::multipliers_for(contact_system(d, k), active_set(d), accelerations(d, k), force)) return true;
  force.fill(0.0);
  return false;
}

// --- energies and the snapshot -------------------------------------------------------------------

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

Snapshot Model::snapshot(double t, const Discrete& d, const State& y, bool full, bool memo) const {
  const Kinematics k = kinematics(d, y, full, memo);
  Snapshot s;
  s.t = t;
  s.mode = d.mode();
  s.on_seesaw = d.on_seesaw;
  s.rope_taut = d.taut;
  s.lid_resting = d.lid_resting;
  s.balloon_stuck = d.balloon_stuck;
  s.x = k.x, s.h = k.h, s.vx = k.vx, s.vh = k.vh, s.r = k.r, s.dr = k.dr;
  s.phi_s = k.phi_s, s.dphi_s = k.dphi_s;
  s.phi_l = k.phi_l, s.dphi_l = k.dphi_l, s.ddphi_l = k.ddphi_l;
  s.balloon_limit = limit_.height_at(k.cos_l, k.sin_l);
  s.balloon_h = k.balloon_h;
  if (!full) return s;
  s.balloon_limit_rate = limit_.rate_at(k.sin_l, k.dphi_l);
  s.balloon_v = k.balloon_v;
  if (!d.latched) {
    contact::PerContact f;
    contact_forces(d, k, f);
    s.tension = f[kRope];
    s.normal_force = f[kBag];
    s.box_reaction = f[kLid];
  }
  s.sandbag_kinetic = 0.5 * m_s_ * (k.vx * k.vx + k.vh * k.vh);
  s.sandbag_potential = m_s_ * g_ * k.h;
  s.lid_kinetic = 0.5 * i_l_ * k.dphi_l * k.dphi_l;
  s.lid_potential = m_l_ * g_ * r_l_ * std::sin(k.phi_l);
  s.seesaw_kinetic = 0.5 * i_s_ * k.dphi_s * k.dphi_s;
  s.seesaw_potential = w_s_ * g_ * std::sin(k.phi_s);
  s.balloon_kinetic = 0.5 * m_b_ * k.balloon_v * k.balloon_v;
  s.balloon_potential = -m_b_ * a_b_ * k.balloon_h;
  const Books& b = d.books;
  s.lost_impacts = b.impacts;
  s.lost_balloon_catch = b.balloon_catch;
  s.dissipated_pivot = y[slot::lost_pivot];
  s.dissipated_hinge = y[slot::lost_hinge];
  s.dissipated_drag = y[slot::lost_drag];
  s.lid_push_work = lid_push_now(d, k, y);
  s.initial_total = b.initial_total;
  return s;
}

// --- guards ------------------------------------------------------------------------------------

void Model::guards(const Discrete& d, const State& y, GuardValues& g, GuardValues* rates, int only) const {
  g.fill(kInactive);
  if (rates) rates->fill(std::numeric_limits<double>::quiet_NaN());
  const Kinematics k = kinematics(d, y);
  if (radio_) g[kGuardRadioOn] = radio_gap(k.balloon_h);
  if (d.balloon_stuck) {
    g[kGuardBalloon] =
        limit_.acceleration_at(k.cos_l, k.sin_l, k.dphi_l, k.ddphi_l) - balloon_acceleration(k.balloon_v);
  } else if (!d.latched) {
    g[kGuardBalloon] = y[slot::balloon_h] - limit_.height_at(k.cos_l, k.sin_l);
  }
  if (rates && !d.balloon_stuck && !d.latched) {
    (*rates)[kGuardBalloon] = y[slot::balloon_v] - limit_.rate_at(k.sin_l, k.dphi_l);
  }
  if (d.latched) return;  // the radio's wait: only the balloon matters now

  // Open contacts: their gaps, negative while open.
  if (!d.on_seesaw && !d.fallen_off) g[kGuardBag] = -height_above_arm(k);
  const Vec2 u_s{k.cos_s, k.sin_s}, u_l{k.cos_l, k.sin_l};
  if (!d.taut) g[kGuardRope] = rope_.span(u_s, u_l) - rope_.rope_length();
  if (!d.lid_resting) g[kGuardLid] = phi_l0_ - k.phi_l;
  // Closed contacts: minus their forces. A massless seesaw held by one contact alone carries no
  // force through it at all (identically zero: no guard); held by sandbag and rope together, the
  // arm's push is the tension times the coupling k (torque balance), so the sandbag's guard is
  // the sign of k and the rope's the tension.
  const bool loaded = heavy_ || (d.on_seesaw && d.taut);
  const bool forces = loaded && (d.on_seesaw || d.taut) &&
                      (only < 0 || only == kGuardBag || only == kGuardRope || only == kGuardLid);
  const bool open = !(d.on_seesaw && d.taut && d.lid_resting);
  contact::System sys;
  if (forces || (rates && open)) sys = contact_system(d, k);
  if (rates && open) {
    // An open contact's guard is minus its gap, so its rate is minus the gap's rate W_i . v.
    if (!d.on_seesaw && !d.fallen_off) (*rates)[kGuardBag] = -sys.rate(kBag, sys.velocity);
    if (!d.taut) (*rates)[kGuardRope] = -sys.rate(kRope, sys.velocity);
    if (!d.lid_resting) (*rates)[kGuardLid] = -k.dphi_l;
  }
  if (forces) {
    // The forces that make the flow's own accelerations (k has them).
    contact::PerContact f;
    if (contact::multipliers_for(sys, active_set(d), accelerations(d, k), f)) {
      // The sign of k is that of -W_RS (the rope's gap gradient along phiS), which stays finite
      // where k passes through infinity at the lid's dead centre.
      if (d.on_seesaw) g[kGuardBag] = heavy_ ? -f[kBag] : sys.normal[kRope][2];
      if (d.taut) g[kGuardRope] = -f[kRope];
      if (d.lid_resting && d.taut) g[kGuardLid] = -f[kLid];
    }
  }

  g[kGuardLidOpen] = k.phi_l - vertical_;  // a lid resting at or past it is open from the start
  if (on_closure(d)) {
    // The lid's dead centre: it reaches the rope's line (the rope would touch the hinge and then
    // run through the box). Crossed at a finite rate in the lid chart, so found exactly.
    if (only < 0 || only == kGuardRopeLocked) g[kGuardRopeLocked] = rope_.lid_side_of_rope(u_s, u_l);
    // Integrate the angle that moves slower: switch charts at |k| = 2 (seesaw) or 1/2 (lid).
    g[kGuardChart] = d.lid_chart ? std::fabs(1.0 / k.transfer.k) - 2.0 : std::fabs(k.transfer.k) - 2.0;
  } else if (d.taut && !d.lid_resting && !d.latched) {
    // The massless seesaw following the lid: R on the line from the pivot to E, where the seesaw
    // would have to turn infinitely fast.
    g[kGuardRopeLocked] = std::fabs(rope_.cos_rho(k.phi_l)) - (1.0 - 1e-9);
  }
  if (d.polar()) {
    g[kGuardAtPivot] = -k.r;
  } else if (d.on_seesaw) {
    // A free-falling sandbag can only leave the left arm through the pivot's vertical line.
    g[kGuardAtPivot] = k.x;
  }
  // With the sandbag on it, the seesaw turning vertical ends the model (MODEL.md); an unloaded
  // seesaw with inertia may swing on past it.
  if (d.on_seesaw) {
    g[kGuardSeesawVertical] = k.phi_s - vertical_;
    if (arm_ < kNoEnd) g[kGuardArmEnd] = k.r - arm_;
  }
}

double Model::guard_floor(Guard g, const Discrete& d) const {
  // A thousand times what rounding leaves in each kind of value, on this machine's scale.
  const double len = length_scale_, weight = (m_s_ + m_l_ + sc_.machine.seesaw_mass) * g_;
  switch (g) {
    case kGuardBag:
      if (!d.on_seesaw) return 1e-12 * len;
      return heavy_ ? 1e-10 * weight : 1e-12;  // the arm's push, or the sign of k
    case kGuardRope: return d.taut ? 1e-10 * weight : 1e-12 * len;
    case kGuardLid: return d.lid_resting ? 1e-10 * weight * len : 1e-12;
    case kGuardBalloon: return d.balloon_stuck ? 1e-10 * g_ : 1e-12 * len;
    default: return 0.0;
  }
}

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

bool Model::law_velocity(const Kinematics& k, bool bag, contact::Coords& u) const {
  // MODEL.md's impact laws fix the seesaw's rate after the rope's jerk; r' keeps the sandbag's
  // speed along the arm (eq. 5) except under linear-momentum; afterwards phiL' = k phiS'. A heavy
  // seesaw brings its own angular momentum I_S phiS'- (zero for the massless seesaw).
  const double c = std::cos(k.phi_s), s = std::sin(k.phi_s);
  const double r = along_arm(k);
  const double v_par = -k.vx * c - k.vh * s;
  const double v_perp = k.vx * s - k.vh * c;
  const double kk = rope_.transfer(k.phi_s, k.phi_l).k;
  const double m = bag ? m_s_ : 0.0;
  const double w0 = k.dphi_l, ws = k.dphi_s;
  double dr = v_par, dphi_s = 0.0;
  const double rope_num = m * r * v_perp + kk * i_l_ * w0 + i_s_ * ws;
  const double rope_den = m * r * r + i_l_ * kk * kk + i_s_;
  switch (sc_.run.impact_law) {
    case ImpactLaw::rope:  // eq. (7): inelastic impulse along the rope
      dphi_s = rope_num / rope_den;
      break;
    case ImpactLaw::angular_momentum_sum:
      dphi_s = (m * r * v_perp + i_l_ * w0 + i_s_ * ws) / (m * r * r + i_l_ * kk + i_s_);
      break;
    case ImpactLaw::kinetic_energy: {
      const double mag = std::sqrt((m * v_perp * v_perp + i_l_ * w0 * w0 + i_s_ * ws * ws) / rope_den);
      dphi_s = rope_num < 0.0 ? -mag : mag;
      break;
    }
    case ImpactLaw::linear_momentum: {
      if (!bag) {  // no sandbag in the impact: nothing for this law to say; inelastic instead
        dphi_s = rope_num / rope_den;
        break;
      }
      // Linear momentum of sandbag and lid centre of mass before = after (2x2 in r', phiS').
      const double sl = std::sin(k.phi_l), cl = std::cos(k.phi_l);
      const double px = m_s_ * k.vx - m_l_ * r_l_ * sl * w0;
      const double ph = m_s_ * k.vh + m_l_ * r_l_ * cl * w0;
      const double a11 = -m_s_ * c, a12 = m_s_ * r * s - m_l_ * r_l_ * sl * kk;
      const double a21 = -m_s_ * s, a22 = -m_s_ * r * c + m_l_ * r_l_ * cl * kk;
      const double det = a11 * a22 - a12 * a21;
      dr = (px * a22 - a12 * ph) / det;
      dphi_s = (a11 * ph - a21 * px) / det;
      break;
    }
  }
  contact::Coords out = u;
  if (bag) {
    out[0] = -dr * c + r * s * dphi_s;
    out[1] = -dr * s - r * c * dphi_s;
  }
  out[2] = dphi_s;
  out[3] = kk * dphi_s;
  for (double x : out)
    if (!std::isfinite(x)) return false;
  u = out;
  return true;
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

// --- jumps -------------------------------------------------------------------------------------

HybridState Model::initial(std::vector<Event>& out) const {
  const Start& st = sc_.start;
  HybridState hs;
  hs.t = 0.0;
  Discrete& d = hs.d;
  d.parked_seesaw = st.seesaw_angle;
  d.balloon_stuck = true;
  d.heavy = heavy_;
  d.on_seesaw = false;
  d.taut = false;
  d.lid_resting = true;
  Kinematics k;
  k.x = st.sandbag_x;
  k.h = st.sandbag_h;
  k.phi_s = st.seesaw_angle;
  k.phi_l = phi_l0_;
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
  if (rope_.span(st.seesaw_angle, phi_l0_) >= rope_.rope_length() - kContact) touch |= bit(kRope);
  k = with_velocity(k, contact::Coords{});
  // Everything starts at rest, so only forces decide; what touches is kept where they allow it.
  Discrete dt = d;
  dt.on_seesaw = contact::has(touch, kBag), dt.taut = contact::has(touch, kRope);
  const contact::System sys = contact_system(dt, k);
  contact::Choice ch = choice(dt, sys, k, -1, Trend::closing);
  const contact::Motion mot = contact::solve_motion(sys, touch, ch);
  if (!mot.ok) throw SimulationError("no consistent set of contacts at the start (degenerate contact)");
  set_contacts(d, mot.active, k);
  hs.y.fill(0.0);
  place(hs, k);
  hs.y[slot::balloon_h] = limit_.height(phi_l0_);
  for (int i = 0; i < 3; ++i) {
    if (!contact::has(touch, i) || contact::has(mot.active, i)) continue;
    const Guard gi = guard_of(i);
    d.armed[gi] = mot.gap_acceleration[i] > ch.accel_tol ? GuardStart{2, -0.5 * mot.gap_acceleration[i]}
                                                         : GuardStart{3, kUnknownLead};
    d.armed[gi].floor = guard_floor(gi, d);
  }

  const Kinematics k1 = kinematics(d, hs.y);
  Books& b = d.books;
  b.initial_total = energy(k1) + balloon_energy(k1.balloon_h, k1.balloon_v);
  b.balloon_e_mark = balloon_energy(k1.balloon_h, k1.balloon_v);  // nothing pushed yet
  open_books(hs, k1);
  // A rope or a sandbag that touches at the start but lets go at once is an event at t = 0 (a lid
  // that lifts at once just starts in M4).
  Set cur = touch;
  for (int i : {kBag, kRope}) {
    if (!contact::has(touch, i) || contact::has(mot.active, i)) continue;
    const Mode from = mode_of(cur);
    cur &= ~bit(i);
    out.push_back(make_event(change_event(i, false), hs, from, mode_of(cur)));
  }
  return hs;
}

void Model::place(HybridState& hs, const Kinematics& k) const {
  // In the lid chart the angle slots hold the lid's angle and rate instead of the seesaw's.
  const bool by_lid = hs.d.lid_chart && on_closure(hs.d);
  const double angle = by_lid ? k.phi_l : k.phi_s, rate = by_lid ? k.dphi_l : k.dphi_s;
  if (hs.d.polar()) {
    hs.y[slot::r] = k.r;
    hs.y[slot::phi_s] = angle;
    hs.y[slot::dr] = k.dr;
    hs.y[slot::dphi_s] = rate;
  } else {
    hs.y[slot::x] = k.x;
    hs.y[slot::h] = k.h;
    hs.y[slot::vx] = k.vx;
    hs.y[slot::vh] = k.vh;
  }
  hs.y[slot::phi_l] = k.phi_l;
  hs.y[slot::dphi_l] = k.dphi_l;
  hs.y[slot::seesaw_phi] = angle;
  hs.y[slot::seesaw_dphi] = rate;
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

void Model::release_balloon_if_lid_jumped(HybridState& hs, double limit_rate_before,
                                          const Books& opened, std::vector<Event>& out) const {
  if (!hs.d.balloon_stuck) return;
  const Kinematics k = kinematics(hs.d, hs.y);
  const double rate = limit_.rate(k.phi_l, k.dphi_l);
  // A jump, not rounding: beyond what the contact decision calls a zero rate.
  if (rate > limit_rate_before + 1e-7 * std::sqrt(g_ * length_scale_) + 1e-9 * std::fabs(limit_rate_before)) {
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

bool Model::jump(Guard fired, HybridState& hs, std::vector<Event>& out) const {
  hs.d.armed = {};
  const Mode before = hs.d.mode();
  const Kinematics k0 = kinematics(hs.d, hs.y);
  const double limit_rate0 = limit_.rate(k0.phi_l, k0.dphi_l);
  open_books(hs, k0);
  const Books opened = hs.d.books;
  auto stop = [&](EventType type) {
    out.push_back(make_event(type, hs, before, before));
    return true;
  };
  // MODEL.md: the model ends when the sandbag reaches the pivot. As r -> 0 the rope's pull on the
  // lid vanishes too, so contact changes and sandbag_at_pivot arrive together; the pivot wins.
  if (hs.d.on_seesaw && k0.r <= kContact && !fires_at_once(fired)) return stop(EventType::sandbag_at_pivot);
  switch (fired) {
    case kGuardBag:
      if (hs.d.on_seesaw) {
        resolve(hs, k0, kBag, Trend::releasing, out);
        break;
      }
      {
        // The falling sandbag reaches the arm's line: it lands where the arm is. Beyond a finite
        // arm's end it has missed it for good; on the pivot's other side the model ends.
        const double along = along_arm(k0);
        if (along > arm_) {
          hs.d.fallen_off = true;
          out.push_back(make_event(EventType::sandbag_falls_off, hs, before, before));
          return false;
        }
        if (along < 0.0) return stop(EventType::sandbag_at_pivot);
        resolve(hs, k0, kBag, Trend::closing, out);
      }
      break;
    case kGuardRope:
      // MODEL.md's linkage: the rope straightens on the lid-below-rope side only; on the other
      // it would run under the hinge, through the box, and the model cannot go on.
      if (!hs.d.taut && !rope_.lid_below_rope(k0.phi_s, k0.phi_l)) return stop(EventType::rope_locked);
      resolve(hs, k0, kRope, hs.d.taut ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardLid:
      resolve(hs, k0, kLid, hs.d.lid_resting ? Trend::releasing : Trend::closing, out);
      break;
    case kGuardArmEnd:  // off the end of a finite arm, velocity kept; it never lands again
      resolve(hs, k0, kBag, Trend::forced_off, out);
      break;
    case kGuardBalloon:
      if (hs.d.balloon_stuck) {  // the lid pulls away faster than the balloon can follow
        free_balloon(hs, k0, limit_rate0);
        hs.d.armed[kGuardBalloon] = {3, kUnknownLead, guard_floor(kGuardBalloon, hs.d)};
        out.push_back(make_event(EventType::balloon_free, hs, before, before));
        return false;
      }
      hs.d.balloon_stuck = true;
      out.push_back(make_event(EventType::balloon_caught, hs, before, before));
      {
        // Caught by a lid that accelerates away faster than the balloon can: it touches and parts.
        const double ahead = limit_.acceleration(k0.phi_l, k0.dphi_l, k0.ddphi_l) - balloon_acceleration(limit_rate0);
        if (ahead > 0.0) {
          free_balloon(hs, k0, limit_rate0);
          hs.d.armed[kGuardBalloon] = {2, -0.5 * ahead, guard_floor(kGuardBalloon, hs.d)};
          out.push_back(make_event(EventType::balloon_free, hs, before, before));
        }
      }
      return false;
    case kGuardLidOpen:
      if (!radio_) return stop(EventType::lid_open);
      {
        // The radio's question goes on: the lid latches open where it is (its kinetic energy is
        // lost to the latch), the rope is let go for good, the sandbag falls freely off the
        // story and the balloon rises without a limit.
        hs.d.latched = true;
        hs.d.lid_resting = false;
        hs.d.taut = false;
        hs.d.on_seesaw = false;
        hs.d.lid_chart = false;
        hs.d.parked_seesaw = k0.phi_s;
        Kinematics k = k0;
        k.dphi_l = 0.0;
        place(hs, k);
        out.push_back(make_event(EventType::lid_open, hs, before, hs.d.mode()));
        if (hs.d.balloon_stuck) {
          const Mode m = hs.d.mode();
          free_balloon(hs, k0, limit_rate0);
          out.push_back(make_event(EventType::balloon_free, hs, m, m));
        }
      }
      return false;
    case kGuardSeesawVertical: return stop(EventType::seesaw_vertical);
    case kGuardAtPivot: return stop(EventType::sandbag_at_pivot);
    case kGuardRopeLocked: return stop(EventType::rope_locked);
    case kGuardRadioOn: return stop(EventType::radio_on);
    case kGuardChart:  // the same state in the other angle: no event
      hs.d.lid_chart = !hs.d.lid_chart;
      hs.d.side = RopeGeometry::side_of(rope_.lid_edge(k0.phi_l), rope_.seesaw_end(k0.phi_s));
      place(hs, k0);
      return false;
    case kGuardCount: break;
  }
  release_balloon_if_lid_jumped(hs, limit_rate0, opened, out);
  book(hs);  // a jump may end with a change that no event reports
  return false;
}

void Model::timeout(HybridState& hs, std::vector<Event>& out) const {
  open_books(hs, kinematics(hs.d, hs.y));
  out.push_back(make_event(EventType::timeout, hs, hs.d.mode(), hs.d.mode()));
}

}  // namespace whatnext
