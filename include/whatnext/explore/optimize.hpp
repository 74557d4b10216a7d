// The best machine within bounds for one outcome value: a coarse grid (outcomes jump where the
// event sequence changes, so a local method alone gets trapped) and then NLopt's derivative-free
// BOBYQA from the best few grid points.
#pragma once

#include <string>
#include <vector>

#include "whatnext/explore/sweep.hpp"

namespace whatnext::explore {

struct OptimizeOptions {
  std::vector<Range> bounds;  // lo < hi; the count is ignored
  std::string value;          // a value_names() entry, e.g. "lid_open" or "outcome_t"
  bool maximize = false;
  int threads = 1;             // for the coarse grid
  int grid_points = 0;         // per key; 0: about 400 machines in all, at least 3 per key
  int starts = 3;              // local searches from the best distinct grid points
  int max_evaluations = 400;   // per local search
  double x_tolerance = 1e-10;  // relative to each key's range
};

struct OptimizeResult {
  bool found = false;        // false: the value never happened anywhere we looked
  std::vector<double> best;  // values of the bounds' keys
  Outcome outcome;           // of the best machine
  double value = 0.0;        // its value
  std::int64_t evaluations = 0;
  // A time pushed to within 0.1 % of the best machine's run.t_max: the run's end cuts the value
  // off, so this is no optimum (maximising lid_open finds "as late as the run allows").
  bool at_time_limit = false;
};

// Machines where the value did not happen (or whose inputs are invalid) get a penalty worse than
// every value seen on the grid. Deterministic: the same input gives the same result.
// Throws InputError for bad bounds or value names.
OptimizeResult optimize(const Config& base, const OptimizeOptions& options);

}  // namespace whatnext::explore
