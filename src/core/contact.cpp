#include "contact.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace whatnext::contact {

namespace {

constexpr int kMaxUnknowns = kMaxContacts + kMaxCoords;

// Dense Gaussian elimination with partial pivoting on an n x n system (n <= kMaxUnknowns).
// false when a pivot is negligible against the matrix's scale: the set does not determine the motion.
bool solve_dense(int n, std::array<std::array<double, kMaxUnknowns>, kMaxUnknowns>& a,
                 std::array<double, kMaxUnknowns>& b) {
  // Rows in units as different as 1/kg and 1/(kg m^2): equilibrate each to a largest entry of 1.
  for (int i = 0; i < n; ++i) {
    double m = 0.0;
    // (A comparison, not std::fmax: a call into libm for every entry, and the same result.)
    for (int j = 0; j < n; ++j) m = std::fabs(a[i][j]) > m ? std::fabs(a[i][j]) : m;
    if (!(m > 0.0) || !std::isfinite(m)) return false;
    const double inv = 1.0 / m;
    for (int j = 0; j < n; ++j) a[i][j] *= inv;
    b[i] *= inv;
  }
  for (int c = 0; c < n; ++c) {
    int p = c;
    for (int r = c + 1; r < n; ++r)
      if (std::fabs(a[r][c]) > std::fabs(a[p][c])) p = r;
    if (!(std::fabs(a[p][c]) > 1e-12)) return false;
    std::swap(a[p], a[c]);
    std::swap(b[p], b[c]);
    for (int r = c + 1; r < n; ++r) {
      const double f = a[r][c] / a[c][c];
      if (f == 0.0) continue;
      for (int j = c; j < n; ++j) a[r][j] -= f * a[c][j];
      b[r] -= f * b[c];
    }
  }
  for (int c = n - 1; c >= 0; --c) {
    double s = b[c];
    for (int j = c + 1; j < n; ++j) s -= a[c][j] * b[j];
    b[c] = s / a[c][c];
  }
  return true;
}

// The directions the closed contacts idx[0..m) of `set` push along (their gradients W, less
// mu s W_f where their friction contact f slips with sign s), and, with `forces`, the slipping
// fixed-bound frictions' forces -s bound W_f added to `given`: what solve_set and multipliers_for
// both build from the slips.
void slip_pushes(const System& sys, Set set, const std::array<int, kMaxContacts>& slip, bool forces,
                 const int* idx, int m, Coords* push, Coords& given) {
  for (int a = 0; a < m; ++a) push[a] = sys.normal[idx[a]];
  for (int f = 0; f < sys.contacts; ++f) {
    if (sys.friction[f] == 0 || has(set, f) || slip[f] == 0) continue;
    if (sys.friction[f] == kFixedBound) {
      if (!forces) continue;
      for (int j = 0; j < sys.coords; ++j) given[j] -= slip[f] * sys.bound[f] * sys.normal[f][j];
      continue;
    }
    for (int a = 0; a < m; ++a) {
      if (idx[a] != sys.friction[f] - 1) continue;
      for (int j = 0; j < sys.coords; ++j) push[a][j] -= slip[f] * sys.bound[f] * sys.normal[f][j];
    }
  }
}

// The linear problem shared by impacts and motion. With the set's contacts closed, the unknowns are
// their multipliers and the accelerations (velocities, for an impact) of the massless coordinates
// they act on; massive coordinates follow from M a = f + sum_b F_b lambda_b. A massless coordinate
// that no closed contact acts on stays at rest.
//   given[j]:  f_j for motion, the velocity before for an impact
//   target[i]: the closed contacts' -curvature_i for motion; for an impact their gap rate after it,
//              0 (inelastic) unless `after` gives one (Newton's restitution)
// F_b is the direction contact b pushes along: its gradient W_b, less mu s W_f where its friction
// contact f slips with sign s (slip[f]); a slipping friction of fixed bound adds -s bound W_f to
// the forces (motion only: a finite force gives no impulse).
// Writes the multipliers and the resulting coordinates' accelerations (or velocities after).
bool solve_set(const System& sys, Set set, bool impact, const std::array<int, kMaxContacts>& slip,
               PerContact& multiplier, Coords& out, const PerContact* after = nullptr) {
  int idx[kMaxContacts];
  int m = 0;
  for (int i = 0; i < sys.contacts; ++i)
    if (has(set, i)) idx[m++] = i;
  // Each closed contact's push direction, and the forces with the fixed-bound slips.
  Coords push[kMaxContacts];
  Coords given = impact ? Coords{} : sys.force;
  slip_pushes(sys, set, slip, !impact, idx, m, push, given);
  // Massless coordinates that a closed contact acts on.
  int free_coord[kMaxCoords];
  int p = 0;
  for (int j = 0; j < sys.coords; ++j) {
    if (sys.mass[j] > 0.0) continue;
    for (int a = 0; a < m; ++a) {
      if (sys.normal[idx[a]][j] != 0.0 || push[a][j] != 0.0) {
        free_coord[p++] = j;
        break;
      }
    }
  }
  double inv_mass[kMaxCoords];
  for (int j = 0; j < sys.coords; ++j) inv_mass[j] = sys.mass[j] > 0.0 ? 1.0 / sys.mass[j] : 0.0;
  // Only the (m + p) x (m + p) block is used: zeroing the whole of it cost the paper's machine (3 of
  // 7 contacts) a tenth of this function.
  std::array<std::array<double, kMaxUnknowns>, kMaxUnknowns> k;
  std::array<double, kMaxUnknowns> rhs;
  for (int a = 0; a < m + p; ++a) std::fill_n(k[a].begin(), m + p, 0.0);
  for (int a = 0; a < m; ++a) {
    const Coords& wa = sys.normal[idx[a]];
    double r = impact ? (after ? (*after)[idx[a]] : 0.0) : -sys.curvature[idx[a]];
    for (int j = 0; j < sys.coords; ++j) {
      if (!(sys.mass[j] > 0.0)) continue;
      const double wm = wa[j] * inv_mass[j];
      r -= impact ? wa[j] * sys.velocity[j] : wm * given[j];
      for (int b = 0; b < m; ++b) k[a][b] += wm * push[b][j];
    }
    for (int c = 0; c < p; ++c) k[a][m + c] = wa[free_coord[c]];
    rhs[a] = r;
  }
  for (int c = 0; c < p; ++c) {
    // Balance on a massless coordinate: its force plus the contacts' is zero (impulses: zero).
    for (int b = 0; b < m; ++b) k[m + c][b] = push[b][free_coord[c]];
    rhs[m + c] = impact ? 0.0 : -given[free_coord[c]];
  }
  if (!solve_dense(m + p, k, rhs)) return false;
  multiplier.fill(0.0);
  for (int a = 0; a < m; ++a) multiplier[idx[a]] = rhs[a];
  out.fill(0.0);
  for (int j = 0; j < sys.coords; ++j) {
    if (!(sys.mass[j] > 0.0)) continue;  // massless: at rest unless solved for below
    double s = impact ? sys.velocity[j] * sys.mass[j] : given[j];
    for (int a = 0; a < m; ++a) s += push[a][j] * rhs[a];
    out[j] = s * inv_mass[j];
  }
  for (int c = 0; c < p; ++c) out[free_coord[c]] = rhs[m + c];
  for (double v : out)
    if (!std::isfinite(v)) return false;
  for (int a = 0; a < m; ++a)
    if (!std::isfinite(rhs[a])) return false;
  return true;
}

// A friction contact's bound in a solution: mu times its normal's multiplier, or the fixed one.
double friction_bound(const System& sys, int f, const PerContact& multiplier) {
  return sys.friction[f] == kFixedBound ? sys.bound[f] : sys.bound[f] * multiplier[sys.friction[f] - 1];
}

// Whether friction contact f acts in set s: a fixed bound always, a tangent while its normal is closed.
bool friction_acts(const System& sys, Set s, int f) {
  return sys.friction[f] == kFixedBound || (sys.friction[f] > 0 && has(s, sys.friction[f] - 1));
}

// Open friction contacts whose slip the closed contacts of s hold at zero already (its gradient
// depends on theirs: sticking would make the set singular) are idle: the load is the closed
// contacts', the friction force between them indeterminate and taken as zero. The others of
// `open_free` are returned, to be decided by sign.
Set without_idle(const System& sys, Set s, Set open_free, bool impact, std::array<int, kMaxContacts>& slip) {
  for (int f = 0; f < sys.contacts; ++f) {
    if (!has(open_free, f)) continue;
    PerContact multiplier;
    Coords out;
    if (!solve_set(sys, s | (1u << f), impact, slip, multiplier, out)) {
      open_free &= ~(1u << f);
      slip[f] = 0;
    }
  }
  return open_free;
}

// Tries each sign for the open friction contacts in `open_free` whose slip the solution decides
// (their slip velocity is zero), in a fixed order, with the others' signs from `slip`: the first
// combination `valid` accepts is kept. false when none is.
template <class F>
bool over_slip_signs(const System& sys, Set open_free, std::array<int, kMaxContacts> slip, F&& valid) {
  int free[kMaxContacts];
  int n = 0;
  for (int f = 0; f < sys.contacts; ++f)
    if (has(open_free, f)) free[n++] = f;
  for (unsigned combo = 0; combo < (1u << n); ++combo) {
    for (int b = 0; b < n; ++b) slip[free[b]] = ((combo >> b) & 1u) ? -1 : 1;
    if (valid(slip)) return true;
  }
  return false;
}

int cost(Set s, Set among, const Choice& choice, int contacts) {
  int c = 0;
  for (int i = 0; i < contacts; ++i) {
    if (!has(among, i) || choice.want[i] == 0) continue;
    const bool closed = has(s, i);
    if (closed != (choice.want[i] > 0)) c += choice.weight[i] > 0 ? choice.weight[i] : 1;
  }
  return c;
}

// Subsets of `among` in order of preference (cost, then bit pattern): the first valid one is the
// choice, so most decisions take one or two solves instead of eight. f returns true when valid.
template <class F>
void in_order_of_preference(Set among, const Choice& choice, int contacts, F&& f) {
  Set sets[1u << kMaxContacts];
  int costs[1u << kMaxContacts];
  int n = 0;
  for (Set s = 0; s <= among; ++s) {
    if ((s & ~among) != 0) continue;
    const int c = cost(s, among, choice, contacts);
    int i = n++;
    for (; i > 0 && (costs[i - 1] > c || (costs[i - 1] == c && sets[i - 1] > s)); --i) {
      sets[i] = sets[i - 1], costs[i] = costs[i - 1];
    }
    sets[i] = s, costs[i] = c;
  }
  for (int i = 0; i < n; ++i)
    if (f(sets[i])) return;
}

}  // namespace

double System::rate(int i, const Coords& v) const {
  double s = 0.0;
  for (int j = 0; j < coords; ++j) s += normal[i][j] * v[j];
  return s;
}

Impact solve_impact(const System& sys, Set touching, const Choice& choice, const PerContact* after) {
  // A Coulomb torque gives no impulse: its contacts take no part.
  for (int f = 0; f < sys.contacts; ++f)
    if (sys.friction[f] == kFixedBound) touching &= ~(1u << f);
  Impact best;
  in_order_of_preference(touching, choice, sys.contacts, [&](Set s) {
    if (!choice.consistent(s)) return false;
    for (int f = 0; f < sys.contacts; ++f)
      if (has(s, f) && sys.friction[f] != 0 && !friction_acts(sys, s, f)) return false;
    // Open friction contacts whose normal takes an impulse slip with the sign the impact leaves.
    Set open_free = 0;
    for (int f = 0; f < sys.contacts; ++f)
      if (has(touching, f) && !has(s, f) && sys.friction[f] > 0 && friction_acts(sys, s, f))
        open_free |= 1u << f;
    std::array<int, kMaxContacts> none{};
    open_free = without_idle(sys, s, open_free, true, none);
    return over_slip_signs(sys, open_free, none, [&](const std::array<int, kMaxContacts>& slip) {
      Impact cand;
      if (!solve_set(sys, s, true, slip, cand.impulse, cand.velocity, after)) return false;
      for (int i = 0; i < sys.contacts; ++i) {
        if (!has(touching, i) || !choice.present(s, i)) continue;
        const bool tangent = sys.friction[i] != 0;
        cand.rate[i] = has(s, i) ? (after && !tangent ? (*after)[i] : 0.0) : sys.rate(i, cand.velocity);
        if (tangent) {
          if (has(s, i) &&
              std::fabs(cand.impulse[i]) > friction_bound(sys, i, cand.impulse) + choice.impulse_tol)
            return false;
          if (has(open_free, i) && slip[i] * cand.rate[i] < -choice.closing_tol) return false;
          continue;
        }
        if (has(s, i) ? cand.impulse[i] < -choice.impulse_tol : cand.rate[i] < -choice.closing_tol)
          return false;
      }
      cand.ok = true;
      cand.impulsive = s;
      cand.slip = slip;
      best = cand;
      return true;
    });
  });
  return best;
}

namespace {
// The open friction contacts that act in set s: slip[f] the sign of the velocity of those slipping;
// those at rest among the candidates (sticking, or just stopped) are returned, to take the sign the
// motion gives them.
Set acting_open_friction(const System& sys, Set s, Set candidates, const Choice& choice,
                         std::array<int, kMaxContacts>& slip) {
  Set open_free = 0;
  for (int f = 0; f < sys.contacts; ++f) {
    if (sys.friction[f] == 0 || has(s, f) || !friction_acts(sys, s, f)) continue;
    const double v = sys.rate(f, sys.velocity);
    if (has(candidates, f) && std::fabs(v) <= choice.rate_tol) {
      open_free |= 1u << f;
    } else {
      slip[f] = v > 0.0 ? 1 : (v < 0.0 ? -1 : 0);
    }
  }
  return open_free;
}

// Whether a sticking Coulomb torque of s should give way to an idle one before it: two such torques
// holding one degree of freedom stick as one, as the first of them (the same choice at every
// tolerance, not the one rounding happens to favour). The first is idle here only because the
// second sticks if it could stick in its place.
bool sticks_in_place_of_first(const System& sys, Set s, Set idle_fixed,
                              const std::array<int, kMaxContacts>& slip) {
  for (int i = 0; i < sys.contacts; ++i) {
    if (!has(s, i) || sys.friction[i] != kFixedBound) continue;
    for (int f = 0; f < i; ++f) {
      if (!has(idle_fixed, f)) continue;
      PerContact m;
      Coords a;
      if (solve_set(sys, (s & ~(1u << i)) | (1u << f), false, slip, m, a)) return true;
    }
  }
  return false;
}

// The complementarity of the motion cand solved with active set s and slip signs: closed contacts
// push and stick within their friction bound (a fixed bound helped by the idle torques in
// idle_fixed), open ones do not close, those free to slip slip the way they were given.
bool complementary(const System& sys, Set s, Set candidates, const Choice& choice, Set open_free,
                   Set idle_fixed, const std::array<int, kMaxContacts>& signs, Motion& cand) {
  auto idle_share = [&](int i) {  // what the idle torques can take off stuck contact i's load
    double share = 0.0;
    for (int f = 0; f < sys.contacts; ++f) {
      if (!has(idle_fixed, f)) continue;
      std::array<int, kMaxContacts> pushed = signs;
      pushed[f] = -1;  // its full bound along its coordinate
      PerContact m;
      Coords a;
      if (solve_set(sys, s, false, pushed, m, a)) share += std::fabs(m[i] - cand.force[i]);
    }
    return share;
  };
  for (int i = 0; i < sys.contacts; ++i) {
    if (!has(candidates, i) || !choice.present(s, i)) continue;
    if (sys.friction[i] != 0) {
      if (has(s, i)) {
        double bound = friction_bound(sys, i, cand.force);
        if (std::fabs(cand.force[i]) > bound + choice.friction_tol && sys.friction[i] == kFixedBound)
          bound += idle_share(i);
        if (std::fabs(cand.force[i]) > bound + choice.friction_tol) return false;
        continue;
      }
      cand.gap_acceleration[i] = sys.rate(i, cand.acceleration) + sys.curvature[i];
      if (has(open_free, i) && signs[i] * cand.gap_acceleration[i] < -choice.accel_tol) return false;
      continue;
    }
    if (has(s, i)) {
      if (cand.force[i] < -choice.force_tol) return false;
      continue;
    }
    cand.gap_acceleration[i] = sys.rate(i, cand.acceleration) + sys.curvature[i];
    if (cand.gap_acceleration[i] < -choice.accel_tol) return false;
  }
  return true;
}
}  // namespace

Motion solve_motion(const System& sys, Set candidates, const Choice& choice) {
  Motion best;
  in_order_of_preference(candidates, choice, sys.contacts, [&](Set s) {
    if (!choice.consistent(s)) return false;
    for (int f = 0; f < sys.contacts; ++f)
      if (has(s, f) && sys.friction[f] != 0 && !friction_acts(sys, s, f)) return false;
    std::array<int, kMaxContacts> slip{};
    Set open_free = acting_open_friction(sys, s, candidates, choice, slip);
    const Set free_before = open_free;
    open_free = without_idle(sys, s, open_free, false, slip);
    // Idle Coulomb torques held by a sticking one (the taut rope couples pivot and hinge): they can
    // take up to their bound of its load, so it sticks as long as the two together hold.
    Set idle_fixed = 0;
    for (int f = 0; f < sys.contacts; ++f)
      if (has(free_before & ~open_free, f) && sys.friction[f] == kFixedBound) idle_fixed |= 1u << f;
    if (sticks_in_place_of_first(sys, s, idle_fixed, slip)) return false;
    return over_slip_signs(sys, open_free, slip, [&](const std::array<int, kMaxContacts>& signs) {
      Motion cand;
      if (!solve_set(sys, s, false, signs, cand.force, cand.acceleration)) return false;
      if (!complementary(sys, s, candidates, choice, open_free, idle_fixed, signs, cand)) return false;
      cand.ok = true;
      cand.active = s;
      cand.slip = signs;
      best = cand;
      return true;
    });
  });
  return best;
}

bool constrained_velocity(const System& sys, Set closed, Coords& velocity) {
  // Without friction: the projection in the kinetic energy's metric, which can only lose energy
  // (a slip's push direction would make it oblique).
  PerContact impulse;
  return solve_set(sys, closed, true, {}, impulse, velocity);
}

bool constrained_motion(const System& sys, Set active, Coords& acceleration, PerContact& force) {
  return solve_set(sys, active, false, sys.slip, force, acceleration);
}

bool multipliers_for(const System& sys, Set active, const Coords& acceleration, PerContact& force) {
  // F^T lambda = M a - f over all coordinates (a massless one's row reads -f_j = sum F_ij lambda_i),
  // in the least-squares sense: (F F^T) lambda = F (M a - f), an m x m system for m active contacts,
  // symmetric and positive definite unless the directions are dependent: Cholesky, no pivoting.
  // F: the directions the contacts push along (their gradients W, with the slips of sys.slip).
  int idx[kMaxContacts];
  int m = 0;
  for (int i = 0; i < sys.contacts; ++i)
    if (has(active, i)) idx[m++] = i;
  Coords push[kMaxContacts];
  Coords given = sys.force;
  slip_pushes(sys, active, sys.slip, true, idx, m, push, given);
  Coords residual{};
  for (int j = 0; j < sys.coords; ++j) residual[j] = sys.mass[j] * acceleration[j] - given[j];
  double l[kMaxContacts][kMaxContacts];  // Cholesky: every entry is written before it is read
  double y[kMaxContacts];
  force.fill(0.0);
  for (int a = 0; a < m; ++a) {
    const Coords& wa = push[a];
    for (int b = 0; b <= a; ++b) {
      const Coords& wb = push[b];
      double gram = 0.0;  // W_a . W_b
      for (int j = 0; j < sys.coords; ++j) gram += wa[j] * wb[j];
      double s = gram;
      for (int c = 0; c < b; ++c) s -= l[a][c] * l[b][c];
      if (b < a) {
        l[a][b] = s / l[b][b];
      } else {
        if (!(s > 1e-24 * gram)) return false;  // what is left of |W_a|^2 must not be rounding
        l[a][a] = std::sqrt(s);
      }
    }
    double r = 0.0;
    for (int j = 0; j < sys.coords; ++j) r += wa[j] * residual[j];
    for (int c = 0; c < a; ++c) r -= l[a][c] * y[c];
    y[a] = r / l[a][a];
  }
  for (int a = m - 1; a >= 0; --a) {
    double s = y[a];
    for (int c = a + 1; c < m; ++c) s -= l[c][a] * force[idx[c]];
    force[idx[a]] = s / l[a][a];
    if (!std::isfinite(force[idx[a]])) return false;
  }
  return true;
}

}  // namespace whatnext::contact
