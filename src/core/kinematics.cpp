// Kinematics: where everything is and how fast, from the discrete state and the continuous one.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

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

}  // namespace whatnext
