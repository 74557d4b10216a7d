#include "whatnext/explore/plan.hpp"

#include <cmath>
#include <cstdlib>
#include <random>
#include <utility>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/units.hpp"

namespace whatnext::explore {

namespace {

// lo + (hi - lo) f without overflow when hi - lo is beyond the largest double.
double between(double lo, double hi, double f) {
  const double span = hi - lo;
  return std::isfinite(span) ? lo + span * f : lo * (1.0 - f) + hi * f;
}

// The value rounded to 15 significant digits: what a user would have typed for it.
double tidy(double v) { return std::strtod(fmt::format("{:.15g}", v).c_str(), nullptr); }

// A uniform double in [0, 1) from the raw generator output (the standard fixes mt19937_64's
// sequence but not the distributions', so these are the same on every platform).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

// A standard normal draw from two raw outputs (Box-Muller; no library distribution, whose
// sequence the standard leaves open).
double normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - unit(rng);  // (0, 1]: the logarithm stays finite
  const double u2 = unit(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * units::kPi * u2);
}

void check_samples(std::int64_t samples) {
  if (samples > kMaxMachines)
    throw InputError(fmt::format("--samples: at most {} machines (given {})", kMaxMachines, samples));
}

}  // namespace

std::vector<std::string> Plan::keys() const {
  std::vector<std::string> out;
  for (const Range& r : ranges) out.push_back(r.key);
  return out;
}

Machines::Machines(const Plan& plan) : plan_(plan) {
  // The option that gave the keys, for messages: a Monte Carlo's come from --spread.
  const char* option = plan_.spread.empty() ? "--vary" : "--spread";
  if (plan_.ranges.empty()) throw InputError("--vary: give at least one KEY=A:B:N to vary");
  for (std::size_t i = 0; i < plan_.ranges.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (plan_.ranges[i].key == plan_.ranges[j].key) {
        throw InputError(fmt::format("{}: each key may be {} once ({} is given twice)", option,
                                     plan_.spread.empty() ? "varied" : "spread", plan_.ranges[i].key));
      }
    }
  }
  const auto dims = plan_.ranges.size();
  if (!plan_.spread.empty()) {
    if (plan_.spread.size() != dims || plan_.samples < 1) {
      throw InputError("--spread: a Monte Carlo needs one spread per key and --samples >= 1");
    }
    check_samples(plan_.samples);
    size_ = plan_.samples;
    std::mt19937_64 rng(plan_.seed);
    lhs_.assign(static_cast<std::size_t>(size_) * dims, 0.0);
    for (std::int64_t i = 0; i < size_; ++i) {
      for (std::size_t d = 0; d < dims; ++d) {
        const double z = plan_.spread_kind == SpreadKind::normal ? normal(rng) : 2.0 * unit(rng) - 1.0;
        lhs_[static_cast<std::size_t>(i) * dims + d] = plan_.ranges[d].lo + plan_.spread[d] * z;
      }
    }
    return;
  }
  if (plan_.samples > 0) {
    check_samples(plan_.samples);
    size_ = plan_.samples;
    // Latin hypercube: in every dimension each of the `samples` strata holds exactly one point.
    std::mt19937_64 rng(plan_.seed);
    lhs_.assign(static_cast<std::size_t>(size_) * dims, 0.0);
    std::vector<std::int64_t> perm(static_cast<std::size_t>(size_));
    for (std::size_t d = 0; d < dims; ++d) {
      for (std::int64_t i = 0; i < size_; ++i) perm[static_cast<std::size_t>(i)] = i;
      for (std::int64_t i = size_ - 1; i > 0; --i) {  // Fisher-Yates
        const auto j = static_cast<std::int64_t>(rng() % static_cast<std::uint64_t>(i + 1));
        std::swap(perm[static_cast<std::size_t>(i)], perm[static_cast<std::size_t>(j)]);
      }
      const Range& r = plan_.ranges[d];
      for (std::int64_t i = 0; i < size_; ++i) {
        const double u =
            (static_cast<double>(perm[static_cast<std::size_t>(i)]) + unit(rng)) / static_cast<double>(size_);
        lhs_[static_cast<std::size_t>(i) * dims + d] = between(r.lo, r.hi, u);
      }
    }
    return;
  }
  size_ = 1;
  for (const Range& r : plan_.ranges) {
    if (r.n < 1) {
      throw InputError(
          fmt::format("--vary {}: a grid needs KEY=A:B:N with N >= 1 (or use --samples)", r.key));
    }
    if (size_ > kMaxMachines / r.n) {
      throw InputError(
          fmt::format("--vary: the grid has more than {} machines; use fewer values", kMaxMachines));
    }
    size_ *= r.n;
  }
  grid_.resize(dims);
  for (std::size_t d = 0; d < dims; ++d) {
    if (plan_.ranges[d].n > kCachedValues) continue;
    for (std::int64_t j = 0; j < plan_.ranges[d].n; ++j) grid_[d].push_back(grid_value(d, j));
  }
}

Machines Machines::of_keys(std::vector<std::string> keys) {
  if (keys.empty()) throw InputError("sweep: give at least one key to vary");
  Machines m;
  for (std::string& k : keys) {
    for (const Range& r : m.plan_.ranges) {
      if (r.key == k)
        throw InputError(fmt::format("sweep: each key may be varied once ({} is given twice)", k));
    }
    Range r;
    r.key = std::move(k);
    m.plan_.ranges.push_back(std::move(r));
  }
  return m;
}

Machines Machines::grid_of(std::vector<std::string> keys, std::vector<std::vector<double>> axes) {
  if (axes.size() != keys.size()) throw InputError("sweep: one sequence of values per key");
  Machines m = of_keys(std::move(keys));
  m.size_ = 1;
  for (std::size_t d = 0; d < axes.size(); ++d) {
    Range& r = m.plan_.ranges[d];
    const auto n = static_cast<std::int64_t>(axes[d].size());
    if (n < 1) throw InputError(fmt::format("sweep: {} needs at least one value", r.key));
    if (m.size_ > kMaxMachines / n) {
      throw InputError(
          fmt::format("sweep: the grid has more than {} machines; use fewer values", kMaxMachines));
    }
    m.size_ *= n;
    r.n = static_cast<int>(n);
    r.lo = axes[d].front();
    r.hi = axes[d].back();
  }
  m.grid_ = std::move(axes);  // point() reads every value from here, whatever the axis's length
  return m;
}

Machines Machines::points_of(std::vector<std::string> keys, std::vector<double> points) {
  return points_from(std::move(keys), std::move(points), 0);
}

Machines Machines::points_from(std::vector<std::string> keys, std::vector<double> points,
                               std::int64_t first) {
  Machines m = of_keys(std::move(keys));
  const std::size_t dims = m.plan_.ranges.size();
  if (points.empty() || points.size() % dims != 0)
    throw InputError("sweep: the machines need one value per key each, and at least one machine");
  const auto n = static_cast<std::int64_t>(points.size() / dims);
  if (n > kMaxMachines || first < 0 || first > kMaxMachines - n)
    throw InputError(fmt::format("sweep: at most {} machines (given {} from {})", kMaxMachines, n, first));
  m.size_ = n;
  m.first_ = first;
  m.plan_.samples = n;  // point() reads machine i's values from lhs_
  m.lhs_ = std::move(points);
  return m;
}

void Machines::point(std::int64_t i, double* out) const {
  const auto dims = plan_.ranges.size();
  if (plan_.samples > 0) {
    const auto row = static_cast<std::size_t>(i - first_) * dims;
    for (std::size_t d = 0; d < dims; ++d) out[d] = lhs_[row + d];
    return;
  }
  for (std::size_t d = dims; d-- > 0;) {  // the last range varies fastest
    const std::int64_t n = plan_.ranges[d].n;
    const std::int64_t j = i % n;
    i /= n;
    out[d] = grid_[d].empty() ? grid_value(d, j) : grid_[d][static_cast<std::size_t>(j)];
  }
}

std::vector<double> Machines::axis(std::size_t d) const {
  if (!grid_[d].empty()) return grid_[d];
  std::vector<double> out(static_cast<std::size_t>(plan_.ranges[d].n));
  for (std::size_t j = 0; j < out.size(); ++j) out[j] = grid_value(d, static_cast<std::int64_t>(j));
  return out;
}

double Machines::grid_value(std::size_t d, std::int64_t j) const {
  // The ends are exactly A and B; a single value is A. Inner values are rounded to 15 digits,
  // so 0.62:0.9:29 gives 0.82 rather than the 0.8200000000000001 that the arithmetic makes.
  const Range& r = plan_.ranges[d];
  return r.n == 1       ? r.lo
         : j == r.n - 1 ? r.hi
                        : tidy(between(r.lo, r.hi, static_cast<double>(j) / static_cast<double>(r.n - 1)));
}

}  // namespace whatnext::explore
