// Geometry of the rope between the seesaw's right end R and its knot E on the lid (the lid's free
// edge unless geometry.rope_on_lid ties it nearer the hinge, docs/model.md §3), and of the
// balloon's height limit under the lid. Every geometric formula of the model lives here, once.
#pragma once

#include <cmath>

#include "whatnext/params.hpp"
#include "whatnext/vec2.hpp"

namespace whatnext {

// dphiL/dphiS and d2phiL/dphiS2 along the straight-rope constraint.
struct Transfer {
  double k = 0.0;
  double dk = 0.0;
};

class RopeGeometry {
 public:
  explicit RopeGeometry(const Machine& m)
      : r_h_(m.seesaw_right_arm),
        r_l_(0.5 * m.rope_knot()),
        l_r_(m.rope_length),
        inv_rh_(1.0 / r_h_),
        inv_lid_(0.5 / r_l_),
        hinge_(m.hinge) {}

  Vec2 hinge() const { return hinge_; }
  double rope_length() const { return l_r_; }
  // From the angles, or from their directions u = (cos, sin) where the caller has those already
  // (the guards: no trigonometric function computed twice); the same bits either way.
  Vec2 seesaw_end(Vec2 u_s) const { return r_h_ * u_s; }
  Vec2 seesaw_end(double phi_s) const { return seesaw_end(polar(1.0, phi_s)); }
  Vec2 lid_edge(Vec2 u_l) const { return hinge_ + (2.0 * r_l_) * u_l; }
  Vec2 lid_edge(double phi_l) const { return lid_edge(polar(1.0, phi_l)); }
  // Distance |R - E|.
  double span(Vec2 u_s, Vec2 u_l) const { return norm(seesaw_end(u_s) - lid_edge(u_l)); }
  double span(double phi_s, double phi_l) const { return span(polar(1.0, phi_s), polar(1.0, phi_l)); }
  // C = |R - E|^2 - l_R^2: negative while the rope is slack, zero when it is straight.
  double gap(double phi_s, double phi_l) const;

  // cos sigma of the closure at phiS; |cos sigma| > 1 where the rope cannot be straight.
  double cos_sigma(double phi_s) const;
  // Closure phiL(phiS) on the branch with the lid below the rope, in (-pi, pi]; false where the
  // rope cannot be straight (|cos sigma| > 1), and out is left untouched.
  bool lid_angle_for(double phi_s, double& phi_l) const;
  // The lid lies below the straight rope (E turned clockwise from the direction H->R): the only
  // physical side, since on the other the rope would run under the hinge, through the box.
  bool lid_below_rope(double phi_s, double phi_l) const;
  // Inverse closure phiS(phiL). The rope fixes R on one of two mirror positions about the line
  // from the pivot to E; side +1 is R turned counterclockwise from E (docs/model.md §3, "+rho"), -1 the
  // other. A seesaw cannot jump between them, so the caller keeps the side it is on.
  bool seesaw_angle_for(double phi_l, int side, double& phi_s) const;
  static int side_of(Vec2 e, Vec2 r) { return cross(e, r) >= 0.0 ? 1 : -1; }
  // cos rho of the inverse closure at phiL; |cos rho| -> 1 is its fold (R on the line P-E).
  double cos_rho(double phi_l) const;

  // Analytic k = -C_S/C_L and k' by implicit differentiation of C(phiS, phiL) = 0.
  Transfer transfer(Vec2 u_s, Vec2 u_l) const { return transfer_at(seesaw_end(u_s), (2.0 * r_l_) * u_l); }
  Transfer transfer(double phi_s, double phi_l) const {
    return transfer(polar(1.0, phi_s), polar(1.0, phi_l));
  }

  // The straight rope's linkage at one instant, for the flow's hot path: both angles' cosines and
  // sines and each angle's derivatives along the closure, from the sine and cosine of one angle
  // (the other follows from the triangle, not from trigonometric functions).
  struct Linkage {
    double cos_s = 1.0, sin_s = 0.0, cos_l = 1.0, sin_l = 0.0;
    Transfer transfer;  // k = dphiL/dphiS, k'
    double ds = 0.0;    // 1/k = dphiS/dphiL
    double dds = 0.0;   // d2phiS/dphiL2
    double phi_s() const { return std::atan2(sin_s, cos_s); }
    double phi_l() const { return std::atan2(sin_l, cos_l); }  // in (-pi, pi]: continuous
  };
  // From the seesaw's angle: the lid below the rope. |cos sigma| is clamped to 1; callers stop
  // the run at rope_locked before it gets there.
  // derivatives = false: the angles' cos and sin only (transfer, ds, dds zero), for positions.
  Linkage from_seesaw(double cos_s, double sin_s, bool derivatives = true) const;
  // From the lid's angle: the seesaw on a side of the line P-E (the chart in which a lid near
  // its dead centre, k -> infinity, moves smoothly). |cos rho| is clamped likewise.
  Linkage from_lid(double cos_l, double sin_l, int side, bool derivatives = true) const;
  // Where the lid stands against the straight rope: < 0 below it (the physical branch, docs/model.md §3), 0
  // along it (the dead centre: the rope would touch the hinge), > 0 on the mirror side. Dimensionless.
  double lid_side_of_rope(Vec2 u_s, Vec2 u_l) const;
  double lid_side_of_rope(double phi_s, double phi_l) const {
    return lid_side_of_rope(polar(1.0, phi_s), polar(1.0, phi_l));
  }
  // The paper's transfer coefficient r_H sin(alpha + phiS - phiL) / (2 r_L sin alpha).
  double paper_transfer(double phi_s, double phi_l) const;

  // Lever arms of a unit rope tension about the lid hinge and about the pivot.
  // Tension T gives the lid the torque T * lid_arm (opening) and the seesaw T * seesaw_arm
  // (against phiS growing).
  double lid_arm(double phi_s, double phi_l) const;
  double seesaw_arm(double phi_s, double phi_l) const;

  // The largest |R - E| over phiS in [-90 deg, 90 deg] and phiL in [phi_l_min, 90 deg].
  double max_span(double phi_l_min) const;

 private:
  // Partial derivatives of C = |R - E|^2 - l^2 given the seesaw end R and the lid vector E - H.
  struct Partials {
    double c_s, c_l, c_ss, c_sl, c_ll;
  };
  Partials partials_at(Vec2 r, Vec2 el) const;
  Linkage linkage_at(Vec2 r, Vec2 el, bool derivatives) const;
  // transfer() given the seesaw end R and the lid vector E - H.
  Transfer transfer_at(Vec2 r, Vec2 el) const;
  // r_l_ is half the knot's distance from the hinge: the lid's half length r_L for a rope tied at
  // its free edge, as in the paper's formulas (where the knot's distance a is 2 r_L).
  double r_h_, r_l_, l_r_;
  // 1 / r_H and 1 / (2 r_L), divided once: every flow evaluation and every row of positions on
  // the closure turns lengths back into directions with them, and a division costs as much as
  // the closure's square roots.
  double inv_rh_, inv_lid_;
  Vec2 hinge_;
};

// Height limit of the balloon's centre under a lid at angle phiL (heights from the hinge level):
// h_lim = -r_B (1 - sin phiL) / cos phiL, written as -r_B cos phiL / (1 + sin phiL), which stays
// finite and smooth up to 90 deg.
struct BalloonLimit {
  double radius;
  double height(double phi_l) const { return height_at(std::cos(phi_l), std::sin(phi_l)); }
  double rate(double phi_l, double dphi_l) const { return rate_at(std::sin(phi_l), dphi_l); }
  double acceleration(double phi_l, double dphi_l, double ddphi_l) const {
    return acceleration_at(std::cos(phi_l), std::sin(phi_l), dphi_l, ddphi_l);
  }
  // The same from the lid angle's cosine and sine, where the caller has them.
  double height_at(double cos_l, double sin_l) const;
  double rate_at(double sin_l, double dphi_l) const;
  double acceleration_at(double cos_l, double sin_l, double dphi_l, double ddphi_l) const;
};

// A balloon smaller than the box (r_B < r_L, docs/extensions.md "A balloon smaller than the box"),
// in coordinates from the hinge. Touching the lid's underside its centre is p = q u + r_B n with
// u = (cos phiL, sin phiL) along the lid, n = (sin phiL, -cos phiL) away from it into the box, and
// q the distance along the lid of the point it touches. The far wall (x = 2 r_L, its top corner W
// at the hinge's level) holds it at q <= q_max(phiL): against the wall's face while that point is
// below W, against W itself (|p - W| = r_B) above it, and not at all once the gap from W to the
// lid, 2 r_L sin phiL, is 2 r_B or more.
struct SmallBalloon {
  double radius;                                // r_B
  double lid;                                   // 2 r_L
  double wall() const { return lid - radius; }  // the centre's x against the far wall's face
  // q_max and its first two derivatives with respect to phiL; false once the corner lets it by.
  struct Limit {
    double q, dq, ddq;
  };
  bool limit(double cos_l, double sin_l, Limit& out) const;
  // The same against the hinge's wall (x = r_B), which holds it at q >= q_min(phiL).
  void hinge(double cos_l, double sin_l, Limit& out) const { face(radius, cos_l, sin_l, out); }
  // Against a wall's face at the centre's x = x: q = (x - r_B sin phiL) / cos phiL.
  void face(double x, double cos_l, double sin_l, Limit& out) const;
  // The centre p (relative to the hinge) touching the lid at q.
  Vec2 centre(double q, double cos_l, double sin_l) const {
    return {q * cos_l + radius * sin_l, q * sin_l - radius * cos_l};
  }
  // Its velocity: p' = (q' + r_B phiL') u + q phiL' u_perp, u_perp = (-sin phiL, cos phiL).
  Vec2 velocity(double q, double dq, double cos_l, double sin_l, double dphi_l) const {
    const double a = dq + radius * dphi_l, b = q * dphi_l;
    return {a * cos_l - b * sin_l, a * sin_l + b * cos_l};
  }
};

}  // namespace whatnext
