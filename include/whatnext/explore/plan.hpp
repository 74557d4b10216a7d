// A sweep's plan: which machines it runs, numbered 0..size()-1. The full grid over its ranges,
// a Latin hypercube over them, or a Monte Carlo around one machine; the values of machine i depend
// only on the plan (and its seed), never on where or when machine i runs.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "whatnext/explore/spec.hpp"

namespace whatnext::explore {

// At most this many machines in one sweep (every row is kept in memory until the CSV is written).
constexpr std::int64_t kMaxMachines = 20'000'000;

// What to sweep: the full grid (samples == 0; the last range varies fastest) or a Latin
// hypercube of `samples` points drawn from `seed` (the same seed gives the same points everywhere:
// only mt19937_64's standardised output is used, no library distribution).
struct Plan {
  std::vector<Range> ranges;
  std::int64_t samples = 0;
  std::uint64_t seed = 1;
  // Monte Carlo (when not empty: one per range): `samples` machines, ranges[d] centred on
  // ranges[d].lo (= hi) and off by spread[d] times a draw from spread_kind, drawn from `seed`
  // machine by machine (so the first N machines of a bigger sample are the same).
  std::vector<double> spread;
  SpreadKind spread_kind = SpreadKind::normal;
  std::vector<std::string> keys() const;
};

// The machines of a plan, numbered 0..size()-1.
class Machines {
 public:
  // Throws InputError for no ranges, a key given twice, a grid range without N, or too many machines.
  explicit Machines(const Plan& plan);
  // Machines given by their values (the Python module's sweeps, whose values may be any numbers):
  // the grid over axes[d] for keys[d] (the last key varies fastest), or machine i's values at
  // points[i * keys.size() ...]. Their plan has the keys (for the CSV's header), not the values.
  // InputError for no keys, a key given twice, an empty axis, or too many machines.
  static Machines grid_of(std::vector<std::string> keys, std::vector<std::vector<double>> axes);
  static Machines points_of(std::vector<std::string> keys, std::vector<double> points);
  // Machines first.. of a plan given by their values: points_of, numbered from `first` (a chunk of
  // a Latin hypercube, carrying its own rows only).
  static Machines points_from(std::vector<std::string> keys, std::vector<double> points, std::int64_t first);
  std::int64_t size() const { return size_; }
  // The first machine's number (0 but for points_from).
  std::int64_t first() const { return first_; }
  const Plan& plan() const { return plan_; }
  // Values of machine i, one per range, written to out[0..ranges).
  void point(std::int64_t i, double* out) const;
  // The values a grid's range d takes (a grid only; computed where not kept).
  std::vector<double> axis(std::size_t d) const;
  bool is_grid() const { return plan_.samples == 0; }

 private:
  Machines() = default;
  static Machines of_keys(std::vector<std::string> keys);
  Plan plan_;
  std::int64_t size_ = 0, first_ = 0;
  std::vector<double> lhs_;  // Latin hypercube: size_ x ranges values, row-major
  // A grid's values per range, made once (tidying a value formats and parses it), for ranges of
  // up to kCachedValues values; longer ones are computed per machine.
  static constexpr std::int64_t kCachedValues = 1 << 16;
  std::vector<std::vector<double>> grid_;
  double grid_value(std::size_t d, std::int64_t j) const;
};

}  // namespace whatnext::explore
