// What the stages of the model share: the contact tolerance, the contacts' bits and the events
// each contact's change is reported as. Internal to the model's stage files in src/core/.
#pragma once

#include <limits>

#include "model.hpp"

// A stage of a hot function (guards(), flow(), kinematics()) called once from it, in the same file:
// a function of its own for reading, inlined for speed (split apart, the guards and the flow cost
// the paper's machine 3 % more instructions).
#if defined(__GNUC__) || defined(__clang__)
#define WHATNEXT_STAGE [[gnu::always_inline]] inline
#else
#define WHATNEXT_STAGE inline
#endif

namespace whatnext::model_detail {

constexpr double kHalfPi = 1.57079632679489661923;
constexpr double kContact = 1e-9;  // docs/model.md §4: touching (on the arm, rope straight) within 1e-9 m
constexpr double kNoEnd =
    std::numeric_limits<double>::infinity();  // the paper's endless arm (docs/model.md §1)
// Lead of an armed guard whose first non-zero derivative is not known (a force that just reached
// zero): only its sign matters to the integrators.
constexpr double kUnknownLead = -1e-300;

using contact::Set;
constexpr Set bit(int i) { return 1u << i; }

inline Mode mode_of(Set s) {
  return Discrete::mode_of(contact::has(s, kBag), contact::has(s, kRope), contact::has(s, kLid));
}

}  // namespace whatnext::model_detail
