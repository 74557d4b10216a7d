// What every output writer shares: angles in degrees, no -0 in a file, and no state that is not
// finite.
#pragma once

#include <cmath>

#include <fmt/format.h>

#include "whatnext/units.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext::io {

// Never let -0.000 reach a file.
inline double clean(double v) { return (std::isfinite(v) && v != 0.0) ? v : 0.0; }

// Nor a NaN or an infinity: a state that is not finite ends the run as failed (the writers are
// called from inside simulate(), so the run stops there and no file is committed).
template <class Where>  // Snapshot or Positions
[[noreturn]] inline void not_finite(const Where& s) {
  throw SimulationError(
      fmt::format("the state is not finite at t = {} s in mode {}", s.t, to_string(s.mode)));
}

inline void require_finite(const Snapshot& s) {
  const double values[] = {s.t,
                           s.x,
                           s.h,
                           s.r,
                           s.dr,
                           s.phi_s,
                           s.dphi_s,
                           s.phi_l,
                           s.dphi_l,
                           s.balloon_h,
                           s.balloon_v,
                           s.tension,
                           s.energy(),
                           s.total_energy(),
                           s.ledger_residual()};
  for (const double v : values) {
    if (!std::isfinite(v)) not_finite(s);
  }
}

}  // namespace whatnext::io
