// Kinematics: where everything is and how fast, from the discrete state and the continuous one.
#include "model.hpp"

#include <cmath>
#include <limits>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

namespace {
// phiS where guard_kinematics() does not ask for it: not a number, so that a reader shows.
constexpr double kUnasked = std::numeric_limits<double>::quiet_NaN();
}  // namespace

// The layout of the continuous state follows from the contacts alone: it is decided once here,
// and each layout has its own stage below that fills in positions, then (if asked) rates and
// accelerations. What every layout shares (the trig of both angles, the balloon) comes last.
WHATNEXT_STAGE Model::Layout Model::layout(const Discrete& d) {
  if (d.polar()) {
    if (d.seesaw_held()) return Layout::grounded_carrying;
    if (!d.taut) return Layout::carried_slack;
    if (d.lid_held()) return Layout::held_by_rope;
    return d.lid_chart ? Layout::on_rope_by_lid : Layout::on_rope;
  }
  if (d.on_seesaw) return Layout::falling_on_seesaw;
  if (d.heavy) return Layout::unloaded_heavy;
  return d.taut ? Layout::following_lid : Layout::parked;
}

// One evaluation of the kinematics: the state, what is asked for, and what is known so far.
struct Model::KinematicsPass {
  const Model& m;
  const Discrete& d;
  const State& y;
  bool rates;
  Workspace* ws;      // the integration's memos, or null
  bool seesaw_angle;  // phiS itself, where only its cos and sin follow (guard_kinematics: not asked)
  Kinematics& k;      // the caller's, returned without a copy
  bool trig_s = false, trig_l = false;  // cos and sin of phiS / phiL already known
  Torques q = {};  // what the swings add to the weights' torques (Model::extra_torques), with rates

  void torqued(double phi_s, double dphi_s) {
    q = m.extra_torques(d, phi_s, dphi_s, y[slot::phi_l], y[slot::dphi_l]);
  }
  Swing swing_of(bool on, bool taut, double r, double phi_s, double dr, double dphi_s) const {
    return ws ? m.swing(*ws, on, taut, r, phi_s, dr, dphi_s, q.seesaw, q.lid)
              : m.compute_swing(on, taut, r, phi_s, dr, dphi_s, q.seesaw, q.lid);
  }
  LidSwing lid_swing_of(bool on, double r, double phi_l, double dr, double dphi_l, int side) const {
    return ws ? m.swing_by_lid(*ws, on, r, phi_l, dr, dphi_l, side, q.seesaw, q.lid)
              : m.compute_swing_by_lid(on, r, phi_l, dr, dphi_l, side, q.seesaw, q.lid);
  }
  // The lid on its own: resting, latched open, held by its hinge's friction, or swinging freely.
  void free_lid() {
    if (d.lid_resting) {
      k.phi_l = m.c_.phi_l0;
    } else if (d.latched || d.lid_stuck || !rates) {
      k.phi_l = y[slot::phi_l];
    } else {
      k.phi_l = y[slot::phi_l];
      k.dphi_l = y[slot::dphi_l];
      // The directions now rather than in finish(): the lid's weight needs the cosine too.
      k.cos_l = std::cos(k.phi_l), k.sin_l = std::sin(k.phi_l);
      trig_l = true;
      k.ddphi_l = m.lid_free_acceleration_at(k.cos_l, k.dphi_l, q.lid);
    }
  }
  // The lid on the rope's closure, from the seesaw's swing (the seesaw's chart).
  void on_rope(const Swing& p) {
    k.phi_l = p.lk.phi_l();
    k.transfer = p.lk.transfer;
    k.ddphi_s = p.ddphi_s;
    k.dphi_l = p.lk.transfer.k * k.dphi_s;
    k.ddphi_l = p.lk.transfer.k * p.ddphi_s + p.lk.transfer.dk * k.dphi_s * k.dphi_s;
    k.cos_l = p.lk.cos_l, k.sin_l = p.lk.sin_l;
    trig_l = true;
  }
  // ... or from the lid's (the lid's chart).
  void by_lid(const LidSwing& p, double phi_l, double dphi_l) {
    lid_chart(k, p, phi_l, dphi_l, seesaw_angle);
    trig_s = trig_l = true;
  }
  // Positions only: the same linkage the swings start from, without their accelerations, from the
  // lid's angle (its chart) or the seesaw's.
  void placed(bool by_lid_angle, double phi) {
    const double c = std::cos(phi), sn = std::sin(phi);
    const RopeGeometry::Linkage lk =
        by_lid_angle ? m.rope_.from_lid(c, sn, d.side, false) : m.rope_.from_seesaw(c, sn, false);
    if (by_lid_angle) {
      k.phi_l = phi;
      k.phi_s = seesaw_angle ? lk.phi_s() : kUnasked;
    } else {
      k.phi_l = lk.phi_l();
    }
    k.cos_s = lk.cos_s, k.sin_s = lk.sin_s, k.cos_l = lk.cos_l, k.sin_l = lk.sin_l;
    trig_s = trig_l = true;
  }

  // --- the sandbag on the seesaw in polar form (r, phiS) ---
  void polar(Layout layout) {
    k.r = y[slot::r];
    k.phi_s = y[slot::phi_s];
    if (rates) k.dr = y[slot::dr], k.dphi_s = y[slot::dphi_s];
    if (rates) torqued(y[slot::phi_s], y[slot::dphi_s]);
    switch (layout) {
      case Layout::carried_slack: carried_slack(); break;
      case Layout::grounded_carrying: on_the_floor(); break;
      case Layout::held_by_rope:
        k.phi_l = d.lid_resting ? m.c_.phi_l0 : y[slot::phi_l];  // on the box, or held by the hinge
        if (rates) k.transfer = m.rope_.transfer(k.phi_s, k.phi_l);
        break;
      case Layout::on_rope_by_lid: on_rope_by_lid(); break;
      default: carried_on_rope(); break;
    }
    if (!trig_s) trig(ws ? &ws->seesaw : nullptr, k.phi_s, k.cos_s, k.sin_s), trig_s = true;
    const double c = k.cos_s, s = k.sin_s;
    k.x = -k.r * c;
    k.h = -k.r * s;
    if (rates && (layout == Layout::held_by_rope || layout == Layout::grounded_carrying))
      k.ddr = m.along_arm_acceleration(k.r, s, 0.0);  // M5 or on the floor: the arm is fixed
    if (d.at_stop || d.bag_stuck) {
      k.ddr = 0.0;  // the stop holds the sandbag at the arm's end, or friction holds it
    } else if (rates && d.bag_slip != 0) {
      k.ddr += m.bag_friction(d.bag_slip, k.r, k.dr, c, k.dphi_s, k.ddphi_s);
    }
    if (rates) {
      k.vx = -k.dr * c + k.r * s * k.dphi_s;
      k.vh = -k.dr * s - k.r * c * k.dphi_s;
    }
  }
  // A heavy seesaw carrying the sandbag, the lid on its own.
  void carried_slack() {
    if (rates) {
      const Swing p = swing_of(true, false, k.r, k.phi_s, k.dr, k.dphi_s);
      k.ddr = p.ddr;
      k.ddphi_s = p.ddphi_s;
      k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
      trig_s = true;
    }
    free_lid();
  }
  // The seesaw standing on the floor, at rest: the lid resting, hanging on the straight rope, or
  // on its own.
  void on_the_floor() {
    k.dphi_s = 0.0;
    if (!d.taut) return free_lid();
    if (d.lid_resting) {
      k.phi_l = m.c_.phi_l0;
    } else {
      placed(false, k.phi_s);
    }
    if (rates) k.transfer = m.rope_.transfer(k.phi_s, k.phi_l);
  }
  // M4 near the lid's dead centre: the angle slots hold the lid's angle and rate.
  void on_rope_by_lid() {
    const double phi_l = y[slot::phi_s];
    if (!rates) return placed(true, phi_l);
    const LidSwing p = lid_swing_of(true, k.r, phi_l, k.dr, y[slot::dphi_s], d.side);
    k.ddr = p.ddr;
    by_lid(p, phi_l, y[slot::dphi_s]);
  }
  // M4: the sandbag on the seesaw, the lid on the straight rope.
  void carried_on_rope() {
    if (!rates) return placed(false, k.phi_s);
    const Swing p = swing_of(true, true, k.r, k.phi_s, k.dr, k.dphi_s);
    k.ddr = p.ddr;
    k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
    trig_s = true;
    on_rope(p);
  }

  // --- the sandbag in free fall in Cartesian form (x, h) ---
  void cartesian(Layout layout) {
    if (rates) torqued(y[slot::seesaw_phi], y[slot::seesaw_dphi]);  // a massless seesaw is pulled by none
    k.x = y[slot::x];
    k.h = y[slot::h];
    if (rates) k.vx = y[slot::vx], k.vh = y[slot::vh];
    k.r = std::sqrt(k.x * k.x + k.h * k.h);
    if (rates) k.dr = k.r > 0.0 ? (k.x * k.vx + k.h * k.vh) / k.r : 0.0;
    if (!((d.heavy || d.seesaw_held()) && d.taut)) free_lid();
    switch (layout) {
      case Layout::falling_on_seesaw: falling_on_seesaw(); break;
      case Layout::unloaded_heavy: unloaded_heavy(); break;
      case Layout::following_lid: following_lid(); break;
      default: k.phi_s = d.parked_seesaw; break;  // M1: nothing moves the unloaded seesaw
    }
  }
  // M3: the massless seesaw turns with the falling sandbag.
  void falling_on_seesaw() {
    k.phi_s = seesaw_angle ? std::atan2(-k.h, -k.x) : kUnasked;
    const double c = -k.x / k.r, s = -k.h / k.r;
    k.cos_s = c, k.sin_s = s;
    trig_s = k.r > 0.0;
    if (rates) {
      k.dphi_s = (k.vx * s - k.vh * c) / k.r;
      k.ddphi_s = (m.c_.g * c - 2.0 * k.dr * k.dphi_s) / k.r;
    }
  }
  // The unloaded heavy seesaw, on its own or with the lid on the rope.
  void unloaded_heavy() {
    k.phi_s = y[slot::seesaw_phi];
    if (rates) k.dphi_s = y[slot::seesaw_dphi];
    if (d.seesaw_held()) {
      if (d.taut) on_the_floor();
    } else if (d.taut && d.lid_held()) {
      k.phi_l = d.lid_resting ? m.c_.phi_l0 : y[slot::phi_l];
      if (rates) k.transfer = m.rope_.transfer(k.phi_s, k.phi_l);
    } else if (d.lid_chart && d.taut) {
      const double phi_l = y[slot::seesaw_phi];
      if (!rates) return placed(true, phi_l);
      by_lid(lid_swing_of(false, 0.0, phi_l, 0.0, y[slot::seesaw_dphi], d.side), phi_l, y[slot::seesaw_dphi]);
    } else if (rates) {
      const Swing p = swing_of(false, d.taut, 0.0, k.phi_s, 0.0, k.dphi_s);
      k.ddphi_s = p.ddphi_s;
      k.cos_s = p.lk.cos_s, k.sin_s = p.lk.sin_s;
      trig_s = true;
      if (d.taut) on_rope(p);
    } else if (d.taut) {
      placed(false, k.phi_s);
    }
  }
  // M2: the unloaded massless seesaw follows the lid, on its side of the line P-E.
  void following_lid() {
    k.phi_s = d.parked_seesaw;  // exact while the lid rests
    if (d.grounded != 0) return on_the_floor();
    if (!d.lid_resting) m.rope_.seesaw_angle_for(k.phi_l, d.side, k.phi_s);
    if (rates) {
      k.transfer = m.rope_.transfer(k.phi_s, k.phi_l);
      k.dphi_s = d.lid_resting ? 0.0 : k.dphi_l / k.transfer.k;
    }
  }

  // What every layout shares: both angles' cos and sin, and the balloon.
  void finish() {
    if (!trig_s) trig(ws ? &ws->seesaw : nullptr, k.phi_s, k.cos_s, k.sin_s);
    if (!trig_l) trig(ws ? &ws->lid : nullptr, k.phi_l, k.cos_l, k.sin_l);
    if (m.c_.small) return small_balloon();
    k.balloon_x = m.c_.r_l;
    if (d.balloon_stuck) {
      k.balloon_h = m.limit_.height_at(k.cos_l, k.sin_l);
      if (rates) k.balloon_v = m.limit_.rate_at(k.sin_l, k.dphi_l);
    } else {
      k.balloon_h = y[slot::balloon_h];
      if (rates) k.balloon_v = y[slot::balloon_v];
    }
  }
  // A balloon smaller than the box (docs/extensions.md): on the lid at q, held in the corner
  // (q = q_max(phiL)) or sliding (q integrated); free in the plane.
  void small_balloon() {
    if (!d.balloon_stuck) {
      k.balloon_x = y[slot::balloon_x];
      k.balloon_h = y[slot::balloon_h];
      if (rates) k.balloon_vx = y[slot::balloon_vx], k.balloon_v = y[slot::balloon_v];
      return;
    }
    if (d.balloon_edge) {  // p = E + r_B e(psi), E = 2 r_L u
      const double psi = y[slot::balloon_h], ce = std::cos(psi), se = std::sin(psi), r = m.sb_.radius;
      k.balloon_q = psi;  // in place of q: the angle round the edge and its rate
      if (rates) k.balloon_dq = y[slot::balloon_v];
      k.balloon_x = m.sb_.lid * k.cos_l + r * ce;
      k.balloon_h = m.sb_.lid * k.sin_l + r * se;
      if (rates) {
        const double w = y[slot::balloon_v];
        k.balloon_vx = -m.sb_.lid * k.sin_l * k.dphi_l - r * se * w;
        k.balloon_v = m.sb_.lid * k.cos_l * k.dphi_l + r * ce * w;
      }
      return;
    }
    SmallBalloon::Limit lim{0.0, 0.0, 0.0};
    if (d.balloon_held && m.small_balloon_wall(d.balloon_side, k.cos_l, k.sin_l, lim)) {
      k.balloon_q = lim.q;
      k.balloon_dq = lim.dq * k.dphi_l;
    } else {
      k.balloon_q = y[slot::balloon_h];
      k.balloon_dq = y[slot::balloon_v];
    }
    const Vec2 p = m.sb_.centre(k.balloon_q, k.cos_l, k.sin_l);
    k.balloon_x = p.x;
    k.balloon_h = p.h;
    if (rates) {
      const Vec2 v = m.sb_.velocity(k.balloon_q, k.balloon_dq, k.cos_l, k.sin_l, k.dphi_l);
      k.balloon_vx = v.x;
      k.balloon_v = v.h;
    }
  }
};

Kinematics Model::kinematics(const Discrete& d, const State& y, bool rates, Workspace* ws) const {
  return kinematics_pass(d, y, rates, ws, true);
}

Kinematics Model::guard_kinematics(const Discrete& d, const State& y, Workspace* ws) const {
  return kinematics_pass(d, y, true, ws, false);
}

Kinematics Model::kinematics_pass(const Discrete& d, const State& y, bool rates, Workspace* ws,
                                  bool seesaw_angle) const {
  Kinematics k;
  k.rope_let_go = d.latched;
  KinematicsPass pass{*this, d, y, rates, ws, seesaw_angle, k};
  const Layout layout = Model::layout(d);
  if (d.polar()) {
    pass.polar(layout);
  } else {
    pass.cartesian(layout);
  }
  pass.finish();
  if (c_.stretchy && rates && d.stretched) stretchy_kinematics(d, k);
  return k;
}

void Model::lid_chart(Kinematics& k, const LidSwing& p, double phi_l, double dphi_l, bool seesaw_angle) {
  // The lid's angle and rate are the state; the seesaw follows on the closure.
  k.phi_l = phi_l;
  k.phi_s = seesaw_angle ? p.lk.phi_s() : kUnasked;
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

}  // namespace whatnext
