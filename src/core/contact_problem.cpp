// The contact problem of one instant, in the coordinates (x, h, phiS, phiL), and the forces of the closed
// contacts.
#include "model.hpp"

#include <cmath>

#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

// --- the contact problem -------------------------------------------------------------------------

contact::System Model::contact_system(const Discrete& d, const Kinematics& k) const {
  // Coordinates (x, h, phiS, phiL), diagonal masses (m_S, m_S, I_S, I_L): I_S = 0 is the paper's
  // massless seesaw, held by whatever contact acts on it. The gaps, each >= 0 when open:
  //   sandbag: its height above the arm's line, -x sin phiS + h cos phiS (multiplier: the arm's push, N)
  //   rope:    l_R - |R - E|                                  (multiplier: the tension, N)
  //   lid:     phiL - phiL0                                   (multiplier: the box's push, N m)
  contact::System s;
  s.coords = 4;
  s.contacts = 3;
  s.mass = {c_.m_s, c_.m_s, c_.i_s, c_.i_l};
  s.velocity = {k.vx, k.vh, k.dphi_s, k.dphi_l};
  const double cs = k.cos_s, sn = k.sin_s, cl = k.cos_l, sl = k.sin_l;
  // The pivot's damper needs a seesaw with inertia (validation rejects it on a massless one).
  s.force = {0.0, -c_.m_s * c_.g, -c_.w_s * c_.g * cs - c_.c_p * k.dphi_s,
             -c_.m_l * c_.g * c_.r_l * cl - c_.c_l * k.dphi_l};

  const double height = -k.x * sn + k.h * cs;
  s.normal[kBag] = {-sn, cs, -k.x * cs - k.h * sn, 0.0};
  s.curvature[kBag] = -2.0 * k.dphi_s * (k.vx * cs + k.vh * sn) - k.dphi_s * k.dphi_s * height;

  const Vec2 r{sc_.machine.seesaw_right_arm * cs, sc_.machine.seesaw_right_arm * sn};
  const double knot = sc_.machine.rope_knot();
  const Vec2 el{knot * cl, knot * sl};
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
  if (c_.contacts > 3) built_contacts(s, k);
  if (c_.stretchy && d.stretched) stretchy_force(d, k, s);
  if (c_.friction) friction_contacts(d, s, k);
  return s;
}

void Model::friction_contacts(const Discrete& d, contact::System& s, const Kinematics& k) const {
  // The sandbag's slip along the arm is r' (r = -x cos phiS - h sin phiS), bounded by mu times the
  // arm's push (docs/extensions.md "Friction"); the friction force along the arm passes through
  // the pivot, so it turns nothing but the sandbag.
  const double cs = k.cos_s, sn = k.sin_s;
  s.normal[kBagSlip] = {-cs, -sn, k.x * sn - k.h * cs, 0.0};
  s.curvature[kBagSlip] =
      2.0 * k.dphi_s * (k.vx * sn - k.vh * cs) + (k.x * cs + k.h * sn) * k.dphi_s * k.dphi_s;
  s.friction[kBagSlip] = kBag + 1;
  s.bound[kBagSlip] = c_.mu;
  s.slip[kBagSlip] = d.on_seesaw && !d.bag_stuck ? d.bag_slip : 0;
  // The seesaw's and the lid's turning, bounded by the pivot's and the hinge's Coulomb torques.
  s.normal[kPivotSlip] = {0.0, 0.0, 1.0, 0.0};
  s.curvature[kPivotSlip] = 0.0;
  s.friction[kPivotSlip] = contact::kFixedBound;
  s.bound[kPivotSlip] = c_.t_p;
  s.slip[kPivotSlip] = d.seesaw_stuck ? 0 : d.seesaw_slip;
  s.normal[kHingeSlip] = {0.0, 0.0, 0.0, 1.0};
  s.curvature[kHingeSlip] = 0.0;
  s.friction[kHingeSlip] = contact::kFixedBound;
  s.bound[kHingeSlip] = c_.t_h;
  s.slip[kHingeSlip] = d.lid_stuck ? 0 : d.lid_slip;
}

void Model::built_contacts(contact::System& s, const Kinematics& k) const {
  // The built machine's gaps (docs/extensions.md "The machine students build"), each >= 0 open:
  //   end stop:     L - r = L + x cos phiS + h sin phiS          (multiplier: the stop's push, N)
  //   floor, left:  -L sin phiS - h_floor   (the left end)       (multiplier: the floor's push, N)
  //   floor, right: r_H sin phiS - h_floor  (the right end)
  //   floor, bag:   h - h_floor
  s.contacts = kContactCount;
  const double cs = k.cos_s, sn = k.sin_s, w2 = k.dphi_s * k.dphi_s;
  const double left = std::isfinite(c_.arm) ? c_.arm : 0.0, right = sc_.machine.seesaw_right_arm;
  s.normal[kStop] = {cs, sn, -k.x * sn + k.h * cs, 0.0};
  s.curvature[kStop] = 2.0 * k.dphi_s * (-k.vx * sn + k.vh * cs) - (k.x * cs + k.h * sn) * w2;
  s.normal[kFloorLeft] = {0.0, 0.0, -left * cs, 0.0};
  s.curvature[kFloorLeft] = left * sn * w2;
  s.normal[kFloorRight] = {0.0, 0.0, right * cs, 0.0};
  s.curvature[kFloorRight] = -right * sn * w2;
  s.normal[kBagFloor] = {0.0, 1.0, 0.0, 0.0};
  s.curvature[kBagFloor] = 0.0;
}

double Model::coulomb_hold(const Discrete& d, const Kinematics& k, int i) const {
  const bool pivot = i == kPivotSlip;
  const double own = pivot ? c_.t_p : c_.t_h, other = pivot ? c_.t_h : c_.t_p;
  const bool coupled = d.taut && !d.latched && (pivot ? !d.lid_resting : d.grounded == 0);
  if (!(other > 0.0) || !coupled) return own;
  const double ratio = std::fabs(rope_.transfer(Vec2{k.cos_s, k.sin_s}, Vec2{k.cos_l, k.sin_l}).k);
  return own + (pivot ? ratio * other : other / ratio);
}

contact::Set Model::active_set(const Discrete& d) {
  return (d.on_seesaw ? bit(kBag) : 0u) | (d.taut ? bit(kRope) : 0u) | (d.lid_resting ? bit(kLid) : 0u) |
         (d.at_stop ? bit(kStop) : 0u) | (d.grounded > 0 ? bit(kFloorLeft) : 0u) |
         (d.grounded < 0 ? bit(kFloorRight) : 0u) | (d.bag_on_floor ? bit(kBagFloor) : 0u) |
         (d.bag_stuck ? bit(kBagSlip) : 0u) | (d.seesaw_stuck ? bit(kPivotSlip) : 0u) |
         (d.lid_stuck ? bit(kHingeSlip) : 0u);
}

contact::Coords Model::accelerations(const Discrete& d, const Kinematics& k) const {
  if (!d.polar()) {  // falls, or lies; on the massless seesaw pushed by the arm against a stretched rope
    contact::Coords a{0.0, d.bag_on_floor ? 0.0 : -c_.g, k.ddphi_s, k.ddphi_l};
    if (c_.stretchy && d.stretched) stretchy_accelerations(d, k, a);
    return a;
  }
  // x = -r cos phiS, h = -r sin phiS: along the arm r'' - r phiS'^2, across it 2 r' phiS' + r phiS''.
  const double along = k.ddr - k.r * k.dphi_s * k.dphi_s, across = 2.0 * k.dr * k.dphi_s + k.r * k.ddphi_s;
  return {-along * k.cos_s + across * k.sin_s, -along * k.sin_s - across * k.cos_s, k.ddphi_s, k.ddphi_l};
}

bool Model::contact_forces(const Discrete& d, const Kinematics& k, contact::PerContact& force) const {
  if (contact::multipliers_for(contact_system(d, k), active_set(d), accelerations(d, k), force)) return true;
  force.fill(0.0);
  return false;
}

}  // namespace whatnext
