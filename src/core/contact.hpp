// Unilateral contacts decided by complementarity: the event-driven method for rigid bodies with
// unilateral constraints (Pfeiffer & Glocker). At a contact change, impacts are a complementarity
// problem on velocities (impulses >= 0, no contact left closing) and the contacts that carry the
// motion on are one on accelerations (forces >= 0, released contacts separate).
//
// It knows nothing of seesaws: coordinates with a diagonal mass matrix (a zero entry is a massless
// coordinate, held by the contacts acting on it, or at rest when none does), generalized forces,
// and for each contact the gradient of its gap (gap >= 0 open, 0 touching) and the velocity terms
// of the gap's second derivative. The problems are small (at most kMaxContacts contacts), so every
// candidate set is tried and the valid one kept; where a massless coordinate makes several valid
// (their forces all zero), the caller's preferences choose.
//
// Coulomb friction joins the same problem (docs/extensions.md "Friction"): a friction contact is a
// tangent whose gradient gives the slip velocity. Closed, it sticks: its slip held at zero, its
// multiplier of either sign within the bound (mu times its normal contact's multiplier, or a fixed
// Coulomb force or torque). Open while its normal contact is closed, it slips: a force of the
// bound's size against the slip, whose sign is the slip velocity's, or where that is zero, the one
// the resulting motion takes. In 2-D the friction cone is exact with these two directions.
#pragma once

#include <array>

namespace whatnext::contact {

constexpr int kMaxCoords = 4;
constexpr int kMaxContacts = 10;

using Coords = std::array<double, kMaxCoords>;
using PerContact = std::array<double, kMaxContacts>;
using Set = unsigned;  // bit i: contact i
constexpr bool has(Set s, int i) { return (s >> i) & 1u; }

struct System {
  int coords = 0, contacts = 0;
  Coords mass{};      // diagonal of the mass matrix; 0: massless
  Coords force{};     // generalized forces (gravity, dampers) at this state
  Coords velocity{};  // generalized velocities
  // The first `contacts` entries of these are set (not zeroed beyond: the paper's machine has 3).
  std::array<Coords, kMaxContacts> normal;  // W_i = d gap_i / dq
  PerContact curvature;                     // gap_i'' = W_i . q'' + curvature_i (the velocity-product terms)
  // Friction: friction[i] = n + 1 makes contact i the tangent of normal contact n, bounded by
  // bound[i] = mu times n's multiplier; friction[i] = kFixedBound bounds it by the force bound[i]
  // itself (a Coulomb torque, transmitting no impulse); 0: an ordinary unilateral contact.
  // Only `friction` is zeroed: bound and slip are read for friction contacts alone, which set them
  // (zeroing all three for every contact problem of the flow cost the paper's machine 2-3 %).
  std::array<int, kMaxContacts> friction{};
  PerContact bound;
  // The sign each open friction contact slips with in the motion being described (multipliers_for);
  // the solvers decide it themselves.
  std::array<int, kMaxContacts> slip;
  double rate(int i, const Coords& v) const;  // gap_i' = W_i . v
};
constexpr int kFixedBound = -1;

// How much each contact should stay as it is when the physics leaves a choice (only a massless
// coordinate does): want +1 closed, -1 open, 0 no wish; ties between sets of equal cost go to the
// smaller bit pattern. Also the tolerances that decide "zero".
struct Choice {
  std::array<int, kMaxContacts> want{};
  std::array<int, kMaxContacts> weight{};
  double force_tol = 1e-9;     // multipliers >= -force_tol count as pulling/pushing
  double impulse_tol = 1e-9;   // likewise for impulses
  double rate_tol = 1e-9;      // gap rates within rate_tol of 0 are zero (held, decided on forces)
  double closing_tol = 1e-12;  // an impact leaves no contact closing faster than this
  double accel_tol = 1e-9;     // gap accelerations >= -accel_tol count as separating or holding
  // A sticking friction force may exceed its bound by this much: below the band in which its
  // guard counts as zero, so that a guard that fires finds the stick broken.
  double friction_tol = 1e-9;
  // Contacts that exist only together with others (an edge on a surface: the end stop holds the
  // sandbag only while it lies on the arm): in a set without all of needs[i], contact i is
  // neither closed nor checked for separation.
  std::array<Set, kMaxContacts> needs{};
  bool present(Set s, int i) const { return (needs[i] & ~s) == 0; }
  bool consistent(Set s) const {
    for (int i = 0; i < kMaxContacts; ++i)
      if (has(s, i) && !present(s, i)) return false;
    return true;
  }
};

struct Impact {
  bool ok = false;                       // false: no set satisfies the conditions (degenerate geometry)
  Set impulsive = 0;                     // contacts that end the impact closed (zero gap rate)
  PerContact impulse{};                  // >= 0 on impulsive contacts
  Coords velocity{};                     // after the impact
  PerContact rate{};                     // gap rates after the impact, of every touching contact
  std::array<int, kMaxContacts> slip{};  // open friction contacts: the sign they slip with
};

// Perfectly inelastic impact of the touching contacts: closed ones get impulses >= 0 and end with
// zero gap rate, the others separate (rate >= 0); touching friction contacts stick (zero slip,
// impulse within mu times the normal's) or slip on (mu times the normal's impulse against the slip
// that is left). Friction of a fixed bound gives no impulse. With `after`, the contacts that take an impulse
// end with that gap rate instead (Newton's restitution: -e times the rate they came with).
Impact solve_impact(const System& sys, Set touching, const Choice& choice, const PerContact* after = nullptr);

struct Motion {
  bool ok = false;
  Set active = 0;
  PerContact force{};  // multipliers of the active contacts (>= 0)
  Coords acceleration{};
  PerContact gap_acceleration{};         // of every candidate (0 on active ones)
  std::array<int, kMaxContacts> slip{};  // open friction contacts: the sign they slip with
};

// Among the candidates (touching, with zero gap rate), the set whose forces are all >= 0 and whose
// released contacts do not close (gap acceleration >= 0).
Motion solve_motion(const System& sys, Set candidates, const Choice& choice);

// The velocities after a perfectly inelastic impact with exactly the given contacts closed (no
// sign checks): the projection that leaves them all at zero gap rate.
bool constrained_velocity(const System& sys, Set closed, Coords& velocity);

// The accelerations and contact forces with exactly the given contacts closed (no sign checks):
// what the motion is while that set holds. false where the set does not determine it.
bool constrained_motion(const System& sys, Set active, Coords& acceleration, PerContact& force);

// The forces of the given contacts that make the given accelerations, M a = f + sum_i W_i force_i
// (inverse dynamics, no sign checks): where the caller has the motion already (a flow), the same
// forces as constrained_motion's at a fraction of its cost. false where the set's gradients are
// dependent.
bool multipliers_for(const System& sys, Set active, const Coords& acceleration, PerContact& force);

}  // namespace whatnext::contact
