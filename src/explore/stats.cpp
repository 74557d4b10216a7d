#include "whatnext/explore/stats.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace whatnext::explore {

double Distribution::quantile(double p) const {
  if (values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const double h = std::clamp(p, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

Distribution distribution(const std::vector<Outcome>& rows, const std::vector<char>& done,
                          std::string_view value) {
  Distribution d;
  for (std::size_t i = 0; i < rows.size(); ++i) {
    if (i >= done.size() || !done[i] || !rows[i].valid) continue;
    ++d.run;
    const double v = value_of(rows[i], value);
    if (!std::isnan(v)) d.values.push_back(v);
  }
  d.happened = static_cast<std::int64_t>(d.values.size());
  std::sort(d.values.begin(), d.values.end());
  return d;
}

}  // namespace whatnext::explore
