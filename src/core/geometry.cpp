#include "whatnext/geometry.hpp"

#include <algorithm>
#include <cmath>

namespace whatnext {

namespace {
constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kPi = 2.0 * kHalfPi;
// atan2(R - H) - sigma leaves (-pi, pi] only when R is left of the hinge and below it (steep
// starts); the lid's angle is continuous, so bring it back.
double wrap(double a) { return a <= -kPi ? a + 2.0 * kPi : (a > kPi ? a - 2.0 * kPi : a); }
}  // namespace

double RopeGeometry::gap(double phi_s, double phi_l) const {
  const Vec2 d = seesaw_end(phi_s) - lid_edge(phi_l);
  return dot(d, d) - l_r_ * l_r_;
}

double RopeGeometry::cos_sigma(double phi_s) const {
  const double d = norm(seesaw_end(phi_s) - hinge_);
  return (4.0 * r_l_ * r_l_ + d * d - l_r_ * l_r_) / (4.0 * r_l_ * d);
}

bool RopeGeometry::lid_angle_for(double phi_s, double& phi_l) const {
  // Triangle hinge H, lid edge E, seesaw end R: sides 2 r_L, l_R and d = |R - H|; sigma is the
  // angle at H between HR and HE. The lid lies below the rope, so E is turned clockwise from HR.
  const Vec2 hr = seesaw_end(phi_s) - hinge_;
  const double d = norm(hr);
  const double cos_sigma = (4.0 * r_l_ * r_l_ + d * d - l_r_ * l_r_) / (4.0 * r_l_ * d);
  if (!(std::fabs(cos_sigma) <= 1.0)) return false;
  phi_l = wrap(std::atan2(hr.h, hr.x) - std::acos(cos_sigma));
  return true;
}

bool RopeGeometry::lid_below_rope(double phi_s, double phi_l) const {
  return lid_side_of_rope(phi_s, phi_l) < 0.0;
}

double RopeGeometry::cos_rho(double phi_l) const {
  const double de = norm(lid_edge(phi_l));
  return (r_h_ * r_h_ + de * de - l_r_ * l_r_) / (2.0 * r_h_ * de);
}

bool RopeGeometry::seesaw_angle_for(double phi_l, int side, double& phi_s) const {
  const Vec2 e = lid_edge(phi_l);
  const double c = cos_rho(phi_l);
  if (!(std::fabs(c) <= 1.0)) return false;
  // The sum lies in (-2 pi, 2 pi]: wrapped into the seesaw's own range (-pi, pi], where the
  // no-somersault guard reads it (a steep hinge gave -292 deg for what is 68 deg).
  phi_s = wrap(std::atan2(e.h, e.x) + (side > 0 ? 1.0 : -1.0) * std::acos(c));
  return true;
}

namespace {
// std::fmax(x, 0.0) (0 for NaN too) without its call into libm, on the flow's hot path.
double at_least_zero(double x) { return x > 0.0 ? x : 0.0; }

// The rope's triangle, for both closures below: on a base v of squared length q, with sides of
// squared lengths near2 from the base's start and far2 from its end, the third corner is
// v a + perp(v) b, with a and b the cosine and sine (>= 0; |cos| > 1 clamped to 1) of the angle at
// the start times sqrt(near2 / q) (the law of cosines). One division and one square root in a row:
// the flow's hot path waits on each.
struct Corner {
  double a, b;
};
Corner corner(double q, double near2, double far2) {
  const double inv_q = 1.0 / q;
  const double a = 0.5 * (near2 - far2) * inv_q + 0.5;
  return {a, std::sqrt(at_least_zero(near2 * inv_q - a * a))};
}
}  // namespace

RopeGeometry::Linkage RopeGeometry::from_seesaw(double cos_s, double sin_s, bool derivatives) const {
  const Vec2 r = seesaw_end({cos_s, sin_s});
  const Vec2 hr = r - hinge_;
  // The triangle H, R, E (sigma at H; sin sigma >= 0).
  const Corner t = corner(dot(hr, hr), 4.0 * r_l_ * r_l_, l_r_ * l_r_);
  // E - H is HR turned clockwise by sigma and scaled to 2 r_L (the lid below the rope).
  const Vec2 el{hr.x * t.a + hr.h * t.b, hr.h * t.a - hr.x * t.b};
  return linkage_at(r, el, derivatives);
}

RopeGeometry::Linkage RopeGeometry::from_lid(double cos_l, double sin_l, int side, bool derivatives) const {
  const Vec2 el{2.0 * r_l_ * cos_l, 2.0 * r_l_ * sin_l};
  const Vec2 e = hinge_ + el;
  // The triangle O, E, R (rho at the pivot O).
  const Corner t = corner(dot(e, e), r_h_ * r_h_, l_r_ * l_r_);
  const double a = t.a, b = (side > 0 ? 1.0 : -1.0) * t.b;
  // R is the direction of E turned by +-rho (counterclockwise for side +1), scaled to r_H.
  const Vec2 r{e.x * a - e.h * b, e.h * a + e.x * b};
  return linkage_at(r, el, derivatives);
}

// Inline: the flow waits on it, and as a call it returned the partials through memory (the
// 10^4 grid 2.5 % faster inlined).
inline RopeGeometry::Partials RopeGeometry::partials_at(Vec2 r, Vec2 el) const {
  // C = |D|^2 - l^2 with D = R(phiS) - E(phiL). Derivatives of R and E:
  // R_S = perp(R), R_SS = -R; E_L = perp(E - H), E_LL = -(E - H).
  const Vec2 d = r - (hinge_ + el);
  const Vec2 r_s{-r.h, r.x};
  const Vec2 e_l{-el.h, el.x};
  return {2.0 * dot(d, r_s), -2.0 * dot(d, e_l), 2.0 * (dot(r_s, r_s) - dot(d, r)), -2.0 * dot(r_s, e_l),
          2.0 * (dot(e_l, e_l) + dot(d, el))};
}

RopeGeometry::Linkage RopeGeometry::linkage_at(Vec2 r, Vec2 el, bool derivatives) const {
  Linkage g;
  g.cos_s = r.x * inv_rh_;
  g.sin_s = r.h * inv_rh_;
  g.cos_l = el.x * inv_lid_;
  g.sin_l = el.h * inv_lid_;
  if (!derivatives) return g;
  const Partials c = partials_at(r, el);
  const double inv_cl = 1.0 / c.c_l, inv_cs = 1.0 / c.c_s;
  g.transfer.k = -c.c_s * inv_cl;
  g.transfer.dk = -(c.c_ss + 2.0 * c.c_sl * g.transfer.k + c.c_ll * g.transfer.k * g.transfer.k) * inv_cl;
  // The same implicit differentiation with the roles of the angles swapped.
  g.ds = -c.c_l * inv_cs;
  g.dds = -(c.c_ll + 2.0 * c.c_sl * g.ds + c.c_ss * g.ds * g.ds) * inv_cs;
  return g;
}

Transfer RopeGeometry::transfer_at(Vec2 r, Vec2 el) const {
  const Partials c = partials_at(r, el);
  Transfer t;
  t.k = -c.c_s / c.c_l;
  t.dk = -(c.c_ss + 2.0 * c.c_sl * t.k + c.c_ll * t.k * t.k) / c.c_l;
  return t;
}

double RopeGeometry::lid_side_of_rope(Vec2 u_s, Vec2 u_l) const {
  const Vec2 hr = seesaw_end(u_s) - hinge_;
  return cross(hr, u_l) / norm(hr);
}

double RopeGeometry::paper_transfer(double phi_s, double phi_l) const {
  const double d = norm(seesaw_end(phi_s) - hinge_);
  const double alpha = std::acos((4.0 * r_l_ * r_l_ + l_r_ * l_r_ - d * d) / (4.0 * r_l_ * l_r_));
  return r_h_ * std::sin(alpha + phi_s - phi_l) / (2.0 * r_l_ * std::sin(alpha));
}

double RopeGeometry::lid_arm(double phi_s, double phi_l) const {
  const Vec2 el = polar(2.0 * r_l_, phi_l);
  const Vec2 along = seesaw_end(phi_s) - (hinge_ + el);  // from E towards R
  return cross(el, along) / norm(along);
}

double RopeGeometry::seesaw_arm(double phi_s, double phi_l) const {
  const Vec2 r = seesaw_end(phi_s);
  const Vec2 along = lid_edge(phi_l) - r;  // from R towards E
  return -cross(r, along) / norm(along);
}

double RopeGeometry::max_span(double phi_l_min) const {
  // Closed form (a grid search cost more than a whole simulation, and validation runs for every
  // machine of a sweep). For a fixed point, the farthest point of a circular arc is the
  // antipodal one if the arc holds it, else an end of the arc. So at the maximum each of R and E
  // is an arc end or antipodal to the other, and these candidates contain it:
  // both ends; one end and the other's antipode; both antipodal (R, P, H, E on one line).
  const double s_lo = -kHalfPi, s_hi = kHalfPi, l_lo = phi_l_min, l_hi = kHalfPi;
  auto in = [](double a, double lo, double hi) { return a >= lo && a <= hi; };
  double best = 0.0;
  auto consider = [&](double phi_s, double phi_l) { best = std::max(best, span(phi_s, phi_l)); };
  for (double s : {s_lo, s_hi}) {
    for (double l : {l_lo, l_hi}) consider(s, l);
    const Vec2 hr = seesaw_end(s) - hinge_;  // E opposite R as seen from H
    const double l = std::atan2(-hr.h, -hr.x);
    if (in(l, l_lo, l_hi)) consider(s, l);
  }
  for (double l : {l_lo, l_hi}) {
    const Vec2 e = lid_edge(l);  // R opposite E as seen from P
    const double s = std::atan2(-e.h, -e.x);
    if (in(s, s_lo, s_hi)) consider(s, l);
  }
  const double a = std::atan2(hinge_.h, hinge_.x);  // the line through P and H
  for (double s : {a, a + 2.0 * kHalfPi, a - 2.0 * kHalfPi}) {
    for (double l : {a, a + 2.0 * kHalfPi, a - 2.0 * kHalfPi}) {
      if (in(s, s_lo, s_hi) && in(l, l_lo, l_hi)) consider(s, l);
    }
  }
  return best;
}

double BalloonLimit::height_at(double cos_l, double sin_l) const { return -radius * cos_l / (1.0 + sin_l); }

double BalloonLimit::rate_at(double sin_l, double dphi_l) const { return radius * dphi_l / (1.0 + sin_l); }

double BalloonLimit::acceleration_at(double cos_l, double sin_l, double dphi_l, double ddphi_l) const {
  const double s = 1.0 + sin_l;
  return radius * (ddphi_l / s - dphi_l * dphi_l * cos_l / (s * s));
}

void SmallBalloon::face(double x, double c, double s, Limit& out) const {
  // p.x = q cos + r sin = x, so q = (x - r sin) / cos.
  const double r = radius;
  out.q = (x - r * s) / c;
  out.dq = (x * s - r) / (c * c);
  out.ddq = (x * c * c + 2.0 * s * (x * s - r)) / (c * c * c);
}

bool SmallBalloon::limit(double c, double s, Limit& out) const {
  const double r = radius, x = wall();
  if (x * s <= r) {
    face(x, c, s, out);
    return true;
  }
  // Against the corner W: the nearer of the two points of the line p.n = r_B at |p - W| = r_B.
  // With D = W.n = 2 r_L sin phiL: q = 2 r_L cos phiL - sqrt(D (2 r_B - D)).
  const double d = lid * s, dd = lid * c, ddd = -lid * s;
  const double w = d * (2.0 * r - d);
  if (!(w > 0.0)) return false;
  const double root = std::sqrt(w);
  const double droot = (r - d) * dd / root;
  const double ddroot = ((r - d) * ddd - dd * dd - droot * droot) / root;
  out.q = lid * c - root;
  out.dq = -lid * s - droot;
  out.ddq = -lid * c - ddroot;
  return true;
}

}  // namespace whatnext
