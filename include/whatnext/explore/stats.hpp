// The distribution of one value over a sweep's machines (a Monte Carlo's summary and histogram).
#pragma once

#include <cstdint>
#include <string_view>
#include <vector>

#include "whatnext/explore/evaluate.hpp"

namespace whatnext::explore {

// The quantiles of a value over a sweep's machines where it happened.
struct Distribution {
  std::int64_t run = 0;        // machines that ran (valid)
  std::int64_t happened = 0;   // of them, where the value happened
  std::vector<double> values;  // those values, sorted
  // The p-quantile (0 <= p <= 1) by linear interpolation between order statistics; NaN if none.
  double quantile(double p) const;
};
// Over the machines i with done[i] (value_of's names).
Distribution distribution(const std::vector<Outcome>& rows, const std::vector<char>& done,
                          std::string_view value);

}  // namespace whatnext::explore
