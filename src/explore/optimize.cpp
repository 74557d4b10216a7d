#include "whatnext/explore/optimize.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>

#include <fmt/format.h>
#include <nlopt.hpp>

namespace whatnext::explore {

namespace {

// Everything the NLopt callback needs, and the best machine seen by any stage.
struct Search {
  const Config* base;
  std::vector<std::string> keys;
  std::string value;
  double sign;     // +1 minimise, -1 maximise: NLopt always minimises sign * value
  double penalty;  // for machines where the value did not happen
  OptimizeResult* res;
  double best_f = std::numeric_limits<double>::infinity();

  // Keeps the first of equal values, so the result does not depend on float noise in ties.
  void consider(const std::vector<double>& x, const Outcome& o, double f) {
    if (std::isnan(f) || !(f < best_f)) return;
    best_f = f;
    res->found = true;
    res->best = x;
    res->outcome = o;
    res->value = sign * f;
  }
  double objective(const std::vector<double>& x) {
    const Outcome o = evaluate(*base, keys, x.data());
    ++res->evaluations;
    const double f = sign * value_of(o, value);
    consider(x, o, f);
    return std::isnan(f) ? penalty : f;
  }
};

double nlopt_objective(const std::vector<double>& x, std::vector<double>& grad, void* data) {
  (void)grad;  // derivative-free algorithm: never asked for
  return static_cast<Search*>(data)->objective(x);
}

// Bad bounds or value names are the user's, so they get one clear line before any machine runs.
void check_options(const OptimizeOptions& opt) {
  check_value_name(opt.value, opt.maximize ? "--maximize" : "--minimize");
  if (opt.bounds.empty()) throw InputError("--vary: give at least one KEY=A:B to optimise over");
  for (const Range& r : opt.bounds) {
    if (!(r.lo < r.hi)) {
      throw InputError(fmt::format("--vary {}={}:{}: optimisation needs A < B", r.key, r.lo, r.hi));
    }
  }
}

// The coarse grid's points per key: as asked, else about 400 machines in all (at least 3 per key).
int grid_points(const OptimizeOptions& opt) {
  const std::size_t dims = opt.bounds.size();
  int g = opt.grid_points;
  if (g <= 0) g = std::max(3, static_cast<int>(std::floor(std::pow(400.0, 1.0 / dims) + 1e-9)));
  return g;
}

// Stage 1: the coarse grid, on all cores (outcomes jump where the event sequence changes, so a
// local method alone gets trapped). Returns each machine's sign * value (NaN where it did not
// happen), lets the search see every machine, and sets the penalty beyond the worst value seen.
std::vector<double> search_grid(Search& s, const Config& base, const Machines& grid, int threads) {
  RunOptions ro;
  ro.threads = threads;
  const SweepResult sweep = run(base, grid, ro);
  s.res->evaluations = grid.size();
  std::vector<double> f(static_cast<std::size_t>(grid.size()));
  double worst = -std::numeric_limits<double>::infinity();
  std::vector<double> x(s.keys.size());
  for (std::int64_t i = 0; i < grid.size(); ++i) {
    const Outcome& o = sweep.rows[static_cast<std::size_t>(i)];
    f[static_cast<std::size_t>(i)] = s.sign * value_of(o, s.value);
    if (std::isnan(f[static_cast<std::size_t>(i)])) continue;
    worst = std::max(worst, f[static_cast<std::size_t>(i)]);
    grid.point(i, x.data());
    s.consider(x, o, f[static_cast<std::size_t>(i)]);
  }
  if (s.res->found) s.penalty = worst + (worst - s.best_f) + 1.0;
  return f;
}

// Stage 2's starting points: the best grid points, at most `starts`, skipping a point next to an
// earlier start (it would descend into the same basin).
std::vector<std::int64_t> start_points(const std::vector<double>& f, std::size_t dims, int g, int starts) {
  std::vector<std::int64_t> order;
  for (std::size_t i = 0; i < f.size(); ++i) {
    if (!std::isnan(f[i])) order.push_back(static_cast<std::int64_t>(i));
  }
  std::stable_sort(order.begin(), order.end(), [&](std::int64_t a, std::int64_t b) {
    return f[static_cast<std::size_t>(a)] < f[static_cast<std::size_t>(b)];
  });
  auto grid_index = [&](std::int64_t i) {
    std::vector<std::int64_t> idx(dims);
    for (std::size_t d = dims; d-- > 0;) idx[d] = i % g, i /= g;
    return idx;
  };
  std::vector<std::vector<std::int64_t>> chosen;
  std::vector<std::int64_t> out;
  for (std::int64_t i : order) {
    if (static_cast<int>(chosen.size()) >= starts) break;
    const auto idx = grid_index(i);
    bool near = false;
    for (const auto& st : chosen) {
      bool all = true;
      for (std::size_t d = 0; d < dims; ++d) all = all && std::llabs(st[d] - idx[d]) <= 1;
      near = near || all;
    }
    if (near) continue;
    chosen.push_back(idx);
    out.push_back(i);
  }
  return out;
}

// Stage 2: one BOBYQA search from grid point i, its first steps a grid cell long. The search
// keeps the best machine it sees.
void descend_from(Search& s, const Machines& grid, std::int64_t i, int g, const OptimizeOptions& opt) {
  const std::vector<Range>& ranges = grid.plan().ranges;
  const std::size_t dims = ranges.size();
  std::vector<double> x0(dims), lb(dims), ub(dims), step(dims), xtol(dims);
  grid.point(i, x0.data());
  for (std::size_t d = 0; d < dims; ++d) {
    const Range& r = ranges[d];
    lb[d] = r.lo, ub[d] = r.hi;
    step[d] = (r.hi - r.lo) / (g - 1);
    xtol[d] = opt.x_tolerance * (r.hi - r.lo);
  }
  nlopt::opt local(nlopt::LN_BOBYQA, static_cast<unsigned>(dims));
  local.set_lower_bounds(lb);
  local.set_upper_bounds(ub);
  local.set_initial_step(step);
  local.set_xtol_abs(xtol);
  local.set_maxeval(opt.max_evaluations);
  local.set_min_objective(nlopt_objective, &s);
  double fx = 0.0;
  try {
    local.optimize(x0, fx);
  } catch (const std::exception&) {
    // Round-off limits and the like end this search; the best machine so far is kept.
  }
}

// A time pushed to the run's end is no optimum: say so (final_r and the lid's angle are no times).
bool at_time_limit(const Config& base, const std::vector<Range>& ranges, const OptimizeResult& res,
                   std::string_view value) {
  if (value == "final_r" || value == "final_phi_l_deg") return false;
  Config best = base;
  for (std::size_t d = 0; d < ranges.size(); ++d) set_number(best, ranges[d].key, res.best[d]);
  return res.value >= build_scenario(best).run.t_max * (1.0 - 1e-3);
}

}  // namespace

OptimizeResult optimize(const Config& base, const OptimizeOptions& opt) {
  check_options(opt);
  const int g = grid_points(opt);
  Plan plan;
  plan.ranges = opt.bounds;
  for (Range& r : plan.ranges) r.n = g;
  const Machines grid(plan);  // throws for duplicate keys or too many machines

  OptimizeResult res;
  Search s{&base, plan.keys(), opt.value, opt.maximize ? -1.0 : 1.0, 0.0, &res};
  const std::vector<double> f = search_grid(s, base, grid, opt.threads);
  if (!res.found) return res;  // the value never happened on the grid: nothing to descend from
  for (std::int64_t i : start_points(f, plan.ranges.size(), g, opt.starts)) descend_from(s, grid, i, g, opt);
  res.at_time_limit = at_time_limit(base, plan.ranges, res, opt.value);
  return res;
}

}  // namespace whatnext::explore
