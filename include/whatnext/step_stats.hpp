// What an integration cost: a run's work, reported with its result (Result::stats).
#pragma once

#include <cstdint>

namespace whatnext {

struct StepStats {
  std::int64_t steps = 0;             // accepted and rejected steps of the integrator
  std::int64_t root_evaluations = 0;  // guard evaluations while locating events
};

}  // namespace whatnext
