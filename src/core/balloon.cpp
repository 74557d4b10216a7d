// A balloon smaller than the box (docs/extensions.md "A balloon smaller than the box"): a disc of
// radius r_B in the box, buoyant, touching the lid's underside and the far wall without friction,
// moved by the lid but not acting on it. Its own small contact problem: the lid and the wall (or
// the wall's top corner) push, never pull; which of them holds is decided by the signs of their
// pushes, as for the machine's contacts.
#include <cmath>

#include "model.hpp"
#include "model_internal.hpp"

namespace whatnext {

using namespace model_detail;

namespace {
// A push that is zero within rounding (the wall's under a level lid) is no release.
double slack(double a_b, double g) { return 1e-9 * (std::fabs(a_b) + g); }

// A free balloon of radius r at p, moving at v, that meets a wall of the box (x = r), the wall's top
// (h = 0) or the far wall's top edge (lid, 0) from beside: its velocity after, without the part into
// it (inelastic, without friction). tol: what is still at the near wall.
Vec2 off_the_box(Vec2 p, Vec2 v, double r, double lid, double tol) {
  if (p.x - r <= tol) {
    v.x = std::fmax(v.x, 0.0);
  } else if (p.h <= 0.0) {
    v.x = std::fmin(v.x, 0.0);
  } else {
    const Vec2 m = (1.0 / norm(p - Vec2{lid, 0.0})) * (p - Vec2{lid, 0.0});
    const double into = dot(v, m);
    if (into < 0.0) v = v - into * m;
  }
  return v;
}

// The same where it meets the lid's free edge e, moving at ve, from beside: it loses its velocity
// into e relative to e's own.
Vec2 off_the_edge(Vec2 p, Vec2 v, Vec2 e, Vec2 ve) {
  const Vec2 m = (1.0 / norm(p - e)) * (p - e);
  const double into = dot(v - ve, m);
  if (into < 0.0) v = v - into * m;
  return v;
}
}  // namespace

Vec2 Model::small_balloon_force(const Kinematics& k) const {
  // Net lift upwards, quadratic drag against the velocity (the paper's balloon's, in the plane).
  const double v = std::hypot(k.balloon_vx, k.balloon_v);
  return {-c_.drag * v * k.balloon_vx, c_.a_b - c_.drag * v * k.balloon_v};
}

double Model::small_balloon_slide(const Kinematics& k) const {
  // p = q u + r_B n: along u, q'' - q phiL'^2 + r_B phiL'' = f.u (the lid pushes along n only).
  const Vec2 f = small_balloon_force(k);
  const double fu = f.x * k.cos_l + f.h * k.sin_l;
  return fu - sb_.radius * k.ddphi_l + k.balloon_q * k.dphi_l * k.dphi_l;
}

// Round the free edge E = 2 r_L u: p = E + r_B e, e = (cos psi, sin psi), e_perp = (-sin psi, cos psi);
// E'' = 2 r_L (phiL'' u_perp - phiL'^2 u). Along e_perp: r_B psi'' = (f - E'').e_perp; along e the
// edge pushes with E''.e - r_B psi'^2 - f.e.
double Model::small_balloon_roll(const Kinematics& k, double psi) const {
  const Vec2 f = small_balloon_force(k), e{std::cos(psi), std::sin(psi)}, ep{-e.h, e.x};
  const Vec2 u{k.cos_l, k.sin_l}, up{-k.sin_l, k.cos_l};
  const Vec2 edge = sb_.lid * (k.ddphi_l * up - (k.dphi_l * k.dphi_l) * u);
  return dot(f - edge, ep) / sb_.radius;
}

double Model::small_balloon_edge_push(const Kinematics& k, double psi, double dpsi) const {
  const Vec2 f = small_balloon_force(k), e{std::cos(psi), std::sin(psi)};
  const Vec2 u{k.cos_l, k.sin_l}, up{-k.sin_l, k.cos_l};
  const Vec2 edge = sb_.lid * (k.ddphi_l * up - (k.dphi_l * k.dphi_l) * u);
  return dot(edge, e) - sb_.radius * dpsi * dpsi - dot(f, e);
}

Model::BalloonForces Model::small_balloon_forces(const Discrete& d, const Kinematics& k) const {
  BalloonForces out;
  if (!d.balloon_stuck) return out;
  const double c = k.cos_l, s = k.sin_l, r = sb_.radius, w1 = k.dphi_l, w2 = k.ddphi_l;
  const Vec2 f = small_balloon_force(k);
  const Vec2 u{c, s}, up{-s, c}, n{s, -c};
  const double q = k.balloon_q, dq = k.balloon_dq;
  if (d.balloon_edge) {
    out.lid = small_balloon_edge_push(k, k.balloon_q, k.balloon_dq);
    return out;
  }
  if (!d.balloon_held) {
    // Across the lid: (2 q' phiL' + r_B phiL'^2 + q phiL'') = f.u_perp - push.
    out.lid = dot(f, up) - (2.0 * dq * w1 + r * w1 * w1 + q * w2);
    return out;
  }
  SmallBalloon::Limit lim{0.0, 0.0, 0.0};
  if (!small_balloon_wall(d.balloon_side, c, s, lim)) {  // the corner no longer holds it: the lid alone does
    out.wall = -1.0;
    return out;
  }
  // Held at q_max(phiL): p'' = P_phiphi phiL'^2 + P_phi phiL'' with P_phi = (q' + r) u + q u_perp,
  // P_phiphi = q'' u + (2 q' + r) u_perp - q u (derivatives along phiL).
  const Vec2 p_1 = (lim.dq + r) * u + lim.q * up;
  const Vec2 p_2 = (lim.ddq - lim.q) * u + (2.0 * lim.dq + r) * up;
  const Vec2 b = (w1 * w1) * p_2 + w2 * p_1 - f;
  // The wall's push: off the far wall's face (-1, 0), or off its top corner W = (2 r_L, 0)
  // radially; off the hinge's wall (1, 0).
  const bool face = sb_.wall() * s <= r;
  const Vec2 p = sb_.centre(lim.q, c, s);
  const Vec2 m = d.balloon_side < 0 ? Vec2{1.0, 0.0}
                 : face             ? Vec2{-1.0, 0.0}
                                    : (1.0 / r) * (p - Vec2{sb_.lid, 0.0});
  const double det = cross(n, m);
  out.lid = cross(b, m) / det;
  out.wall = cross(n, b) / det;
  return out;
}

void Model::small_balloon_guards(const Discrete& d, const Kinematics& k, GuardValues& g,
                                 GuardValues* rates) const {
  const double tol = slack(c_.a_b, c_.g), r = sb_.radius;
  if (d.balloon_out && !d.balloon_stuck) return;  // nothing is in its way any more
  if (d.balloon_stuck) {
    const BalloonForces f = small_balloon_forces(d, k);
    if (d.balloon_held) {
      g[kGuardBalloon] = -std::fmin(f.lid, f.wall) - tol;
      return;
    }
    g[kGuardBalloon] = -f.lid - tol;
    if (d.balloon_edge) {  // round the edge until its push vanishes, at most to the lid's top
      g[kGuardBalloonEscape] = k.balloon_q - (std::atan2(k.sin_l, k.cos_l) + kHalfPi);
      return;
    }
    if (d.balloon_out) {  // outside, under the lid: it leaves the lid at its free edge
      g[kGuardBalloonEscape] = k.balloon_q - sb_.lid;
      if (rates) (*rates)[kGuardBalloonEscape] = k.balloon_dq;
      return;
    }
    // The walls' gaps along the lid: q - q_max (far wall or its top), q_min - q (hinge's wall).
    SmallBalloon::Limit lim{0.0, 0.0, 0.0}, hinge{0.0, 0.0, 0.0};
    sb_.hinge(k.cos_l, k.sin_l, hinge);
    g[kGuardBalloonCorner] = hinge.q - k.balloon_q;
    if (rates) (*rates)[kGuardBalloonCorner] = hinge.dq * k.dphi_l - k.balloon_dq;
    if (sb_.limit(k.cos_l, k.sin_l, lim) && k.balloon_q - lim.q > g[kGuardBalloonCorner]) {
      g[kGuardBalloonCorner] = k.balloon_q - lim.q;
      if (rates) (*rates)[kGuardBalloonCorner] = k.balloon_dq - lim.dq * k.dphi_l;
    }
    // Out once its centre passes the line from the wall's top W square to the lid, q = W.u =
    // 2 r_L cos phiL: the narrowest place between lid and wall, which it can pass only where the
    // gap there, 2 r_L sin phiL, is at least 2 r_B (else q_max < W.u holds it back).
    g[kGuardBalloonEscape] = k.balloon_q - sb_.lid * k.cos_l;
    if (rates) (*rates)[kGuardBalloonEscape] = k.balloon_dq + sb_.lid * k.sin_l * k.dphi_l;
    return;
  }
  // Free (below the lid: it comes from there): the lid's underside catches it, beside the lid its
  // free edge E stops it. Out of the box once it is higher than the lid can ever reach, or beside
  // the lid and above the lid's line (nothing of the box over it any more).
  const Vec2 p{k.balloon_x, k.balloon_h};
  const Vec2 u{k.cos_l, k.sin_l}, n{k.sin_l, -k.cos_l};
  const bool beside = dot(p, u) > sb_.lid;
  if (!beside) {
    g[kGuardBalloon] = r - dot(p, n);
    if (rates) (*rates)[kGuardBalloon] = -(k.balloon_vx * n.x + k.balloon_v * n.h + k.dphi_l * dot(p, u));
  } else {
    g[kGuardBalloon] = r - norm(p - sb_.lid * u);
  }
  g[kGuardBalloonEscape] = std::fmax(k.balloon_h - (sb_.lid + r), beside ? -dot(p, n) : kInactive);
  // The walls: the far wall's face below its top, the top corner W above it, the hinge's wall.
  double wall = r - p.x;
  if (p.h <= 0.0) {
    wall = std::fmax(wall, p.x - sb_.wall());
  } else if (p.x < sb_.lid) {
    wall = std::fmax(wall, r - norm(p - Vec2{sb_.lid, 0.0}));
  }
  g[kGuardBalloonCorner] = wall;
}

void Model::small_balloon_free(HybridState& hs, const Kinematics& k) const {
  hs.d.balloon_stuck = false;
  hs.d.balloon_held = false;
  hs.d.balloon_edge = false;
  hs.y[slot::balloon_x] = k.balloon_x;
  hs.y[slot::balloon_h] = k.balloon_h;
  hs.y[slot::balloon_vx] = k.balloon_vx;
  hs.y[slot::balloon_v] = k.balloon_v;
}

void Model::small_balloon_settle(HybridState& hs, Mode before, std::vector<Event>& out) const {
  // Which of lid and wall hold on: the pushes' signs, at most a few changes at one instant. Half
  // the guards' slack: a guard found at its zero lets go here, and one kept starts below zero.
  const double tol = 0.5 * slack(c_.a_b, c_.g);
  for (int round = 0; round < 4 && hs.d.balloon_stuck; ++round) {
    const Kinematics k = kinematics(hs.d, hs.y);
    const BalloonForces f = small_balloon_forces(hs.d, k);
    if (hs.d.balloon_held) {
      if (f.wall >= -tol && f.lid >= -tol) return;
      // Let the wall go first: sliding along the lid, the lid's push is decided again.
      Discrete slide = hs.d;
      slide.balloon_held = false;
      State y = hs.y;
      y[slot::balloon_h] = k.balloon_q;
      y[slot::balloon_v] = k.balloon_dq;
      const Kinematics ks = kinematics(slide, y);
      SmallBalloon::Limit lim{0.0, 0.0, 0.0};
      const int side = hs.d.balloon_side;
      const bool corner = small_balloon_wall(side, ks.cos_l, ks.sin_l, lim);
      // Sliding must move it off the wall: q'' below q_max'' (above q_min'' at the hinge's wall),
      // or no wall any more.
      const double apart =
          corner ? side * (small_balloon_slide(ks) - (lim.ddq * ks.dphi_l * ks.dphi_l + lim.dq * ks.ddphi_l))
                 : -1.0;
      if (apart <= tol && small_balloon_forces(slide, ks).lid >= -tol) {
        hs.d.balloon_held = false;
        hs.y = y;
        continue;
      }
      small_balloon_free(hs, k);
      out.push_back(make_event(EventType::balloon_free, hs, before, before));
      return;
    }
    if (f.lid < -tol) {
      const bool edge = hs.d.balloon_edge;
      small_balloon_free(hs, k);
      // Leaving the lid's free edge, out of the box, is no event: it is on its way up.
      if (!edge) out.push_back(make_event(EventType::balloon_free, hs, before, before));
      return;
    }
    if (hs.d.balloon_out) return;
    bool held = false;
    for (int side : {1, -1}) {
      SmallBalloon::Limit lim{0.0, 0.0, 0.0};
      if (!small_balloon_wall(side, k.cos_l, k.sin_l, lim) ||
          side * (k.balloon_q - lim.q) < -1e-12 * c_.length_scale) {
        continue;
      }
      // At a wall: held there if it moves into it (an inelastic stop), or, at the wall's own
      // rate, if it would accelerate into it.
      const double closing = side * (k.balloon_dq - lim.dq * k.dphi_l),
                   rate_tol = 1e-9 * std::sqrt(c_.g * c_.length_scale);
      const double apart =
          side * (small_balloon_slide(k) - (lim.ddq * k.dphi_l * k.dphi_l + lim.dq * k.ddphi_l));
      if (closing > rate_tol || (closing >= -rate_tol && apart > tol)) {
        hs.d.balloon_held = true;
        hs.d.balloon_side = side;
        held = true;
        break;
      }
    }
    if (!held) return;
  }
}

void Model::small_balloon_jump(Guard fired, HybridState& hs, const Kinematics& k0, Mode before,
                               std::vector<Event>& out) const {
  Discrete& d = hs.d;
  if (fired == kGuardBalloonEscape) {
    if (d.balloon_edge) {  // round the edge onto the lid's top: free from now on
      small_balloon_free(hs, k0);
      d.balloon_edge = false;
      book(hs);
      return;
    }
    if (d.balloon_out) {  // at the lid's free edge: it rolls round it while the edge pushes
      d.balloon_edge = true;
      hs.y[slot::balloon_h] = std::atan2(k0.sin_l, k0.cos_l) - kHalfPi;
      hs.y[slot::balloon_v] = (k0.balloon_dq + sb_.radius * k0.dphi_l) / sb_.radius;
      small_balloon_settle(hs, before, out);
      book(hs);
      return;
    }
    d.balloon_out = true;  // past the wall's top, still under the lid, or free above its reach
    out.push_back(make_event(EventType::balloon_escapes, hs, before, before));
    small_balloon_settle(hs, before, out);
    book(hs);
    return;
  }
  if (fired == kGuardBalloonCorner && !d.balloon_stuck) {
    // A free balloon meets a wall or the wall's top: it loses its velocity into it (inelastic,
    // without friction) and goes on free.
    const Vec2 v = off_the_box({k0.balloon_x, k0.balloon_h}, {k0.balloon_vx, k0.balloon_v}, sb_.radius,
                               sb_.lid, 1e-9 * c_.length_scale);
    hs.y[slot::balloon_vx] = v.x;
    hs.y[slot::balloon_v] = v.h;
    book(hs);
    return;
  }
  if (fired == kGuardBalloon && !d.balloon_stuck &&
      k0.balloon_x * k0.cos_l + k0.balloon_h * k0.sin_l > sb_.lid) {
    // It meets the lid's free edge E from beside: it loses its velocity into E relative to E's
    // own (inelastic, without friction) and goes on free.
    const Vec2 e{sb_.lid * k0.cos_l, sb_.lid * k0.sin_l};
    const Vec2 v = off_the_edge({k0.balloon_x, k0.balloon_h}, {k0.balloon_vx, k0.balloon_v}, e,
                                {-e.h * k0.dphi_l, e.x * k0.dphi_l});
    hs.y[slot::balloon_vx] = v.x;
    hs.y[slot::balloon_v] = v.h;
    book(hs);
    return;
  }
  if (fired == kGuardBalloon && !d.balloon_stuck) {
    // Caught by the lid: its velocity across the lid becomes the lid's there, along it is kept.
    const double c = k0.cos_l, s = k0.sin_l;
    const double q = k0.balloon_x * c + k0.balloon_h * s;
    d.balloon_stuck = true;
    d.balloon_held = false;
    hs.y[slot::balloon_h] = q;
    hs.y[slot::balloon_v] = k0.balloon_vx * c + k0.balloon_v * s - sb_.radius * k0.dphi_l;
    SmallBalloon::Limit lim{0.0, 0.0, 0.0};
    if (sb_.limit(c, s, lim) && q >= lim.q - 1e-12 * c_.length_scale) {
      // Lid and wall found at one instant: the centre is put on both exactly. The step (of the
      // order of the events' location error) changes its lift's potential: booked with the catch.
      d.balloon_held = true;
      d.balloon_side = 1;
      const double h1 = kinematics(d, hs.y).balloon_h;
      d.books.balloon_catch += c_.m_b * c_.a_b * (h1 - k0.balloon_h);
    }
    out.push_back(make_event(EventType::balloon_caught, hs, before, before));
  } else if (fired == kGuardBalloonCorner) {
    // Reached a wall (or the far wall's top) sliding into it: stopped there.
    SmallBalloon::Limit far{0.0, 0.0, 0.0}, hinge{0.0, 0.0, 0.0};
    sb_.hinge(k0.cos_l, k0.sin_l, hinge);
    const bool corner = sb_.limit(k0.cos_l, k0.sin_l, far);
    d.balloon_side = corner && k0.balloon_q - far.q >= hinge.q - k0.balloon_q ? 1 : -1;
    d.balloon_held = true;
  }
  small_balloon_settle(hs, before, out);
  book(hs);
}

void Model::small_balloon_after_lid_jump(HybridState& hs, const Kinematics& k0,
                                         std::vector<Event>& out) const {
  // The machine's impact changed the lid's rate: the balloon keeps its velocity along the lid; a
  // lid that jumped away from it leaves it behind.
  if (!hs.d.balloon_stuck) return;
  const Kinematics k = kinematics(hs.d, hs.y);
  if (k.dphi_l == k0.dphi_l) return;
  if (hs.d.balloon_edge) {
    // Round the edge: its velocity across e kept; an edge that jumped away from it leaves it.
    const double psi = hs.y[slot::balloon_h];
    const Vec2 e{std::cos(psi), std::sin(psi)}, ep{-e.h, e.x};
    const Vec2 v0{k0.balloon_vx, k0.balloon_v},
        ve{-sb_.lid * k.sin_l * k.dphi_l, sb_.lid * k.cos_l * k.dphi_l};
    if (dot(v0 - ve, e) > 1e-7 * std::sqrt(c_.g * c_.length_scale)) {
      small_balloon_free(hs, k0);
    } else {
      hs.y[slot::balloon_v] = dot(v0 - ve, ep) / sb_.radius;
    }
    return;
  }
  const double c = k.cos_l, s = k.sin_l, q = k.balloon_q;
  const double v_n = k0.balloon_vx * s - k0.balloon_v * c;  // the balloon's velocity along n
  const double lid_n = -q * k.dphi_l;                       // the lid's there
  const Mode m = hs.d.mode();
  if (v_n > lid_n + 1e-7 * std::sqrt(c_.g * c_.length_scale)) {
    small_balloon_free(hs, k0);
    out.push_back(make_event(EventType::balloon_free, hs, m, m));
    return;
  }
  if (!hs.d.balloon_held) {
    hs.y[slot::balloon_h] = q;
    hs.y[slot::balloon_v] = k0.balloon_vx * c + k0.balloon_v * s - sb_.radius * k.dphi_l;
  }
  small_balloon_settle(hs, m, out);
}

}  // namespace whatnext
