#include "whatnext/units.hpp"
#include "whatnext/explore/sweep.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdlib>
#include <limits>
#include <exception>
#include <mutex>
#include <ostream>
#include <random>
#include <thread>

#include <fmt/compile.h>
#include <fmt/format.h>
#include <iterator>

#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext::explore {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string_view trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t");
  const auto b = s.find_last_not_of(" \t");
  return a == std::string_view::npos ? std::string_view() : s.substr(a, b - a + 1);
}

// Whole-string number parse; strtod because it accepts every spelling users write (1e-3, .5).
bool parse_double(std::string_view text, double& out) {
  const std::string s(trim(text));
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

std::string num(double v) { return fmt::format("{}", v); }

// lo + (hi - lo) f without overflow when hi - lo is beyond the largest double.
double between(double lo, double hi, double f) {
  const double span = hi - lo;
  return std::isfinite(span) ? lo + span * f : lo * (1.0 - f) + hi * f;
}

// The value rounded to 15 significant digits: what a user would have typed for it.
double tidy(double v) { return std::strtod(fmt::format("{:.15g}", v).c_str(), nullptr); }

std::string csv_quote(std::string_view s) {
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return out + "\"";
}

// A uniform double in [0, 1) from the raw generator output (the standard fixes mt19937_64's
// sequence but not the distributions', so these are the same on every platform).
double unit(std::mt19937_64& rng) { return static_cast<double>(rng() >> 11) * 0x1.0p-53; }

void set_values(Config& cfg, const std::vector<std::string>& keys, const double* values) {
  for (std::size_t k = 0; k < keys.size(); ++k) set_number(cfg, keys[k], values[k]);
}

// An event's reported time uncertainty is the integrator's local error carried to the event
// (Crossing::uncertainty). Measured against runs at tolerance 1e-14 on random machines, the error
// can be several times that: 1.4 times on docs/performance.md's grid, 5 times where an uncertain rope_slack
// moved the lid's opening after it, and far more where the seesaw has mass or the hinges damp,
// since errors then travel along long pieces and through later impacts (250 times after 1.1 s of
// a heavy seesaw holding the lid; a heavy seesaw's sandbag that grazes the pivot reaches it or
// not by the last digits). An impact also multiplies the error of its own time: located to
// accuracy/100, a rope_taut moved a lid's opening by 0.75 of the accuracy (apply_accuracy
// locates events to accuracy/1000, which costs 1 %). So, besides the tolerance of accuracy/15:
//  * a machine whose reported times are uncertain beyond kUncertaintyTrigger of the accuracy is
//    run again, as tightly as brings the uncertainty to kUncertaintyTarget of it;
//  * a machine with a heavy seesaw, damping or the balloon's drag is run again, each time a
//    hundredfold tighter, until two runs report the same events within kAgreement of the
//    accuracy (the last run's error is then about a hundredth of their difference, whatever the
//    estimate says). With drag the estimate fell 7-fold short once (a lid_open 1.56 times the
//    accuracy off, reported at 0.22: the ex1-hinge-drag family, seed 7, 3,000 machines, 118);
//    those sweeps take 2.4 times as long.
// With these, random machines of seventeen families (examples 1-4 varied, the laws, a heavy
// seesaw, damping, drag, the radio, the built machine, friction, the stretchy rope) are within
// 0.31 of the accuracy (docs/performance.md, "Sweeps"; scripts/check-sweep-accuracy.py).
constexpr double kUncertaintyTrigger = 0.3;
constexpr double kUncertaintyTarget = 0.2;
constexpr double kAgreement = 0.5;
constexpr double kTighter = 0.01;
constexpr int kMaxReruns = 4;
constexpr double kTightestTolerance = 1e-14;
// A run again locates its events to this fraction of the accuracy: an impact's time error comes
// out amplified in the later events, 3,500-fold in a lid that reaches its top slowly (a rope_taut
// placed 3.4e-12 s late, within the tolerance/10 it was asked for, moved its lid_open by 1.2
// times the accuracy; example 1's family in scripts/check-sweep-accuracy.py, seed 7, machine
// 1247). Costs a few more guard evaluations per event.
constexpr double kRerunLocating = 1e-5;

// How uncertain a run's reported times are: the largest time uncertainty of each event type's
// first occurrence and of the stop (what the sweep writes), or of any other event where that is
// larger than the accuracy itself and other events share its instant. Such an event is one the
// later ones follow from one to one: a grazing rope_taut that frees the balloon again, which then
// sets the radio's time. A later event alone at its instant is left out: a contact that closes
// grazing (the rope tightening again at a few mm/s, its time uncertain by 1e-7 s and more) changes
// the motion after it only at second order in that time, since the closing takes only the
// velocity along the contact's normal, which is about zero. On docs/performance.md's grid that leaves 402
// machines instead of 1,038 to run again, with the same worst error (docs/performance.md). An
// event limit is a chatter's count, not a time to get right.
double reported_uncertainty(const Result& res, double accuracy) {
  std::vector<char> seen(event_types().size(), 0);
  double u = 0.0;
  for (std::size_t k = 0; k < res.events.size(); ++k) {
    const Event& e = res.events[k];
    const auto idx = static_cast<std::size_t>(e.type);
    if (e.type == EventType::event_limit) continue;
    const bool first = idx < seen.size() && !seen[idx];
    if (idx < seen.size()) seen[idx] = 1;
    const bool alone =
        (k == 0 || res.events[k - 1].t != e.t) && (k + 1 == res.events.size() || res.events[k + 1].t != e.t);
    if (first || k + 1 == res.events.size() || (e.time_uncertainty > accuracy && !alone))
      u = std::fmax(u, e.time_uncertainty);
  }
  return u;
}

// What a sweep reports of a run: each event type's first time, and the stop.
struct Reported {
  std::vector<double> first;
  EventType outcome = EventType::timeout;
  double outcome_t = 0.0;
};
Reported reported(const Result& res) {
  Reported r;
  r.first.assign(event_types().size(), kNaN);
  for (const Event& e : res.events) {
    const auto idx = static_cast<std::size_t>(e.type);
    if (idx < r.first.size() && std::isnan(r.first[idx])) r.first[idx] = e.t;
  }
  r.outcome = res.outcome().type;
  r.outcome_t = res.outcome().t;
  return r;
}
// The largest difference of two runs' reported times; infinite where they report other events.
double difference(const Reported& a, const Reported& b) {
  if (a.outcome != b.outcome) return kInf;
  double d = std::fabs(a.outcome_t - b.outcome_t);
  for (std::size_t i = 0; i < a.first.size(); ++i) {
    if (std::isnan(a.first[i]) != std::isnan(b.first[i])) return kInf;
    if (!std::isnan(a.first[i])) d = std::fmax(d, std::fabs(a.first[i] - b.first[i]));
  }
  return d;
}

// Runs one machine in a scratch config that already holds the base values.
Outcome evaluate_in(Config& work, const std::vector<std::string>& keys, const double* values,
                    double accuracy) {
  Outcome o;
  o.first.assign(event_types().size(), kNaN);
  try {
    set_values(work, keys, values);
    Scenario sc = build_scenario(work);
    const bool tolerance_given = work.has("run.tolerance");
    if (accuracy > 0.0) apply_accuracy(sc, accuracy, tolerance_given);
    Result res = simulate(sc);
    require_finite(res);  // a NaN state is a failed run, not a row of nan
    if (accuracy > 0.0 && !tolerance_given && sc.run.integrator == IntegratorKind::adaptive) {
      const Machine& m = sc.machine;
      const bool carries_errors = m.seesaw_inertia > 0.0 || m.pivot_damping > 0.0 || m.lid_hinge_damping > 0.0 ||
                                  m.balloon_drag_rate() > 0.0;
      double u = reported_uncertainty(res, accuracy);
      // A run again locates its events for its tighter tolerance: an earlier event placed less
      // exactly than that would move the later ones as much (and see kRerunLocating).
      const auto locate_for_tolerance = [&sc, accuracy] {
        sc.run.event_time_tolerance =
            std::fmin(std::fmin(sc.run.event_time_tolerance, sc.run.tolerance / 10.0), kRerunLocating * accuracy);
      };
      if (carries_errors) {
        Reported before = reported(res);
        for (int again = 0; again < kMaxReruns && sc.run.tolerance > kTightestTolerance; ++again) {
          sc.run.tolerance = std::fmax(kTightestTolerance, sc.run.tolerance * kTighter);
          locate_for_tolerance();
          res = simulate(sc);
          require_finite(res);
          Reported now = reported(res);
          const bool agree = difference(before, now) <= kAgreement * accuracy;
          before = std::move(now);
          if (agree) break;
        }
      } else {
        for (int again = 0; again < kMaxReruns && u > kUncertaintyTrigger * accuracy &&
                            sc.run.tolerance > kTightestTolerance;
             ++again) {
          sc.run.tolerance =
              std::fmax(kTightestTolerance, sc.run.tolerance * kUncertaintyTarget * accuracy / u);
          locate_for_tolerance();
          res = simulate(sc);
          require_finite(res);
          u = reported_uncertainty(res, accuracy);
        }
      }
    }
    Reported r = reported(res);
    o.first = std::move(r.first);
    o.outcome = r.outcome;
    o.outcome_t = r.outcome_t;
    const Event& last = res.outcome();
    o.final_r = last.after.r;
    o.final_phi_l_deg = last.after.phi_l * units::kDegreesPerRadian;
    o.valid = true;
  } catch (const InputError& e) {
    o.error = e.what();
  } catch (const SimulationError& e) {
    o.failed = true;
    o.error = e.what();
  } catch (const std::exception& e) {  // a bug, but one machine must not sink the whole sweep
    o.error = fmt::format("internal error: {}", e.what());
  }
  return o;
}

}  // namespace

namespace {
void check_numeric_key(const std::string& key, const std::string& where) {
  if (!find_key(key)) {
    const std::string near = nearest_key(key);
    throw InputError(
        near.empty() ? fmt::format("{}: unknown key '{}'", where, printable(key))
                     : fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, printable(key), near));
  }
  try {  // set_number knows which kinds of key hold one number (text, pairs and flags do not)
    Config probe;
    set_number(probe, key, 0.0);
  } catch (const InputError&) {
    throw InputError(fmt::format("{}: {} is not a single number and cannot be varied", where, key));
  }
}

// A standard normal draw from two raw outputs (Box-Muller; no library distribution, whose
// sequence the standard leaves open).
double normal(std::mt19937_64& rng) {
  const double u1 = 1.0 - unit(rng);  // (0, 1]: the logarithm stays finite
  const double u2 = unit(rng);
  return std::sqrt(-2.0 * std::log(u1)) * std::cos(2.0 * 3.14159265358979323846 * u2);
}
}  // namespace

Spread parse_spread(std::string_view spec, std::string_view option) {
  const std::string where = fmt::format("{} {}", option, printable(spec));
  const auto eq = spec.find('=');
  if (eq == std::string_view::npos)
    throw InputError(fmt::format("{}: expected KEY=±X (given no '=')", where));
  Spread s;
  s.key = std::string(trim(spec.substr(0, eq)));
  check_numeric_key(s.key, where);
  std::string_view rest = trim(spec.substr(eq + 1));
  constexpr std::string_view kPlusMinus = "\u00b1";
  if (rest.substr(0, kPlusMinus.size()) == kPlusMinus) {
    rest.remove_prefix(kPlusMinus.size());
  } else if (rest.substr(0, 2) == "+-") {
    rest.remove_prefix(2);
  } else {
    throw InputError(fmt::format("{}: expected KEY=±X (or KEY=+-X): ± before the spread X (given '{}')",
                                 where, printable(rest)));
  }
  if (!parse_double(rest, s.x)) {
    throw InputError(fmt::format("{}: X must be a finite number (given '{}')", where, printable(trim(rest))));
  }
  if (!(s.x > 0.0)) throw InputError(fmt::format("{}: X must be > 0 (given {})", where, num(s.x)));
  return s;
}

SpreadKind parse_spread_kind(std::string_view kind, std::string_view option) {
  if (kind == "normal") return SpreadKind::normal;
  if (kind == "uniform") return SpreadKind::uniform;
  throw InputError(fmt::format("{}: normal or uniform (given '{}')", option, printable(kind)));
}

double base_value(const Config& config, const std::string& key, std::string_view option) {
  const auto it = config.values.find(key);
  if (it != config.values.end() && it->second.type == ConfigValue::Type::number) return it->second.number;
  const KeySpec* spec = find_key(key);
  const double v = key_default(key);
  if (it == config.values.end() && !std::isnan(v)) return v;
  throw InputError(
      fmt::format("{} {}: the machine does not give {} as a number (its default is '{}'); give it "
                  "with --set {}=VALUE",
                  option, key, key, spec ? spec->default_text : "?", key));
}

Range parse_range(std::string_view spec, std::string_view option, bool need_count) {
  const std::string where = fmt::format("{} {}", option, printable(spec));
  const std::string_view form = need_count ? "KEY=A:B:N" : "KEY=A:B";
  const auto eq = spec.find('=');
  if (eq == std::string_view::npos) {
    throw InputError(fmt::format("{}: expected {} (given no '=')", where, form));
  }
  Range r;
  r.key = std::string(trim(spec.substr(0, eq)));
  check_numeric_key(r.key, where);
  std::vector<std::string_view> parts;
  std::string_view rest = spec.substr(eq + 1);
  for (;;) {
    const auto colon = rest.find(':');
    parts.push_back(rest.substr(0, colon));
    if (colon == std::string_view::npos) break;
    rest = rest.substr(colon + 1);
  }
  const bool count_given = parts.size() == 3;
  if (parts.size() != 2 && !count_given) {
    throw InputError(fmt::format("{}: expected {} ({} fields after '=')", where, form, parts.size()));
  }
  if (need_count && !count_given) {
    throw InputError(fmt::format("{}: expected {}: a grid needs the number of values N", where, form));
  }
  if (!parse_double(parts[0], r.lo)) {
    throw InputError(
        fmt::format("{}: A must be a finite number (given '{}')", where, printable(trim(parts[0]))));
  }
  if (!parse_double(parts[1], r.hi)) {
    throw InputError(
        fmt::format("{}: B must be a finite number (given '{}')", where, printable(trim(parts[1]))));
  }
  if (r.lo > r.hi) {
    throw InputError(fmt::format("{}: needs A <= B (given A = {}, B = {})", where, num(r.lo), num(r.hi)));
  }
  if (count_given) {
    double n = 0.0;
    if (!parse_double(parts[2], n) || n != std::floor(n) || n < 1.0 || n > 1e9) {
      throw InputError(fmt::format("{}: N must be a whole number from 1 to 10^9 (given '{}')", where,
                                   printable(trim(parts[2]))));
    }
    r.n = static_cast<int>(n);
  }
  return r;
}

std::vector<std::string> Plan::keys() const {
  std::vector<std::string> out;
  for (const Range& r : ranges) out.push_back(r.key);
  return out;
}

Machines::Machines(const Plan& plan) : plan_(plan) {
  if (plan_.ranges.empty()) throw InputError("--vary: give at least one KEY=A:B:N to vary");
  for (std::size_t i = 0; i < plan_.ranges.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      if (plan_.ranges[i].key == plan_.ranges[j].key) {
        throw InputError(
            fmt::format("--vary: each key may be varied once ({} is given twice)", plan_.ranges[i].key));
      }
    }
  }
  const auto dims = plan_.ranges.size();
  if (!plan_.spread.empty()) {
    if (plan_.spread.size() != dims || plan_.samples < 1) {
      throw InputError("--spread: a Monte Carlo needs one spread per key and --samples >= 1");
    }
    if (plan_.samples > kMaxMachines) {
      throw InputError(fmt::format("--samples: at most {} machines (given {})", kMaxMachines, plan_.samples));
    }
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
    if (plan_.samples > kMaxMachines) {
      throw InputError(fmt::format("--samples: at most {} machines (given {})", kMaxMachines, plan_.samples));
    }
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
  Machines m = of_keys(std::move(keys));
  const std::size_t dims = m.plan_.ranges.size();
  if (points.empty() || points.size() % dims != 0)
    throw InputError("sweep: the machines need one value per key each, and at least one machine");
  const auto n = static_cast<std::int64_t>(points.size() / dims);
  if (n > kMaxMachines)
    throw InputError(fmt::format("sweep: at most {} machines (given {})", kMaxMachines, n));
  m.size_ = n;
  m.plan_.samples = n;  // point() reads machine i's values from lhs_
  m.lhs_ = std::move(points);
  return m;
}

void Machines::point(std::int64_t i, double* out) const {
  const auto dims = plan_.ranges.size();
  if (plan_.samples > 0) {
    for (std::size_t d = 0; d < dims; ++d) out[d] = lhs_[static_cast<std::size_t>(i) * dims + d];
    return;
  }
  for (std::size_t d = dims; d-- > 0;) {  // the last range varies fastest
    const std::int64_t n = plan_.ranges[d].n;
    const std::int64_t j = i % n;
    i /= n;
    out[d] = grid_[d].empty() ? grid_value(d, j) : grid_[d][static_cast<std::size_t>(j)];
  }
}

double Machines::grid_value(std::size_t d, std::int64_t j) const {
  // The ends are exactly A and B; a single value is A. Inner values are rounded to 15 digits,
  // so 0.62:0.9:29 gives 0.82 rather than the 0.8200000000000001 that the arithmetic makes.
  const Range& r = plan_.ranges[d];
  return r.n == 1       ? r.lo
         : j == r.n - 1 ? r.hi
                        : tidy(between(r.lo, r.hi, static_cast<double>(j) / static_cast<double>(r.n - 1)));
}

const std::vector<EventType>& event_types() {
  // EventType is a scoped enum (underlying int) with contiguous values from 0, and names.cpp
  // names every one of them: the first value without a name is one past the last.
  static const std::vector<EventType> types = [] {
    std::vector<EventType> out;
    for (int i = 0; i < 1000; ++i) {
      const auto t = static_cast<EventType>(i);
      if (to_string(t) == "?") break;
      out.push_back(t);
    }
    return out;
  }();
  return types;
}

void check_accuracy(double accuracy, std::string_view option) {
  if (!(accuracy >= kMinAccuracy && accuracy <= kMaxAccuracy)) {
    throw InputError(fmt::format("{}: must be in [{:g}, {:g}] s (given {})", option, kMinAccuracy,
                                 kMaxAccuracy, accuracy));
  }
}

void apply_accuracy(Scenario& scenario, double accuracy, bool tolerance_given) {
  if (!tolerance_given) scenario.run.tolerance = std::fmax(1e-15, accuracy / 15.0);  // run.tolerance's floor
  scenario.run.event_time_tolerance = accuracy / 1000.0;
}

Outcome evaluate(const Config& base, const std::vector<std::string>& keys, const double* values,
                 double accuracy) {
  Config work = base;
  return evaluate_in(work, keys, values, accuracy);
}

std::vector<std::string> value_names() {
  std::vector<std::string> out{"outcome_t", "final_r", "final_phi_l_deg"};
  for (EventType t : event_types()) out.emplace_back(to_string(t));
  return out;
}

void check_value_name(std::string_view name, std::string_view option) {
  for (const std::string& v : value_names()) {
    if (v == name) return;
  }
  const std::string near = nearest_word(name, value_names());
  throw InputError(
      fmt::format("{} {}: unknown value{} (use outcome_t, final_r, final_phi_l_deg or an event name "
                  "such as lid_open)",
                  option, printable(name), near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near)));
}

double value_of(const Outcome& o, std::string_view name) {
  if (!o.valid) return kNaN;
  if (name == "outcome_t") return o.outcome_t;
  if (name == "final_r") return o.final_r;
  if (name == "final_phi_l_deg") return o.final_phi_l_deg;
  const auto& types = event_types();
  for (std::size_t i = 0; i < types.size(); ++i) {
    if (to_string(types[i]) == name) return o.first[i];
  }
  return kNaN;
}

std::string csv_header(const Plan& plan) {
  fmt::memory_buffer line;
  auto put = [&line](std::string_view text) { line.append(text.data(), text.data() + text.size()); };
  put("index");
  for (const Range& r : plan.ranges) fmt::format_to(std::back_inserter(line), ",{}", r.key);
  put(",outcome,outcome_t,final_r,final_phi_l_deg");
  for (EventType t : event_types()) fmt::format_to(std::back_inserter(line), ",{}", to_string(t));
  put(",error\n");
  return std::string(line.data(), line.size());
}

namespace {
void write_header(std::ostream& out, const Plan& plan) {
  const std::string line = csv_header(plan);
  out.write(line.data(), static_cast<std::streamsize>(line.size()));
}
}  // namespace

double Distribution::quantile(double p) const {
  if (values.empty()) return kNaN;
  const double h = std::clamp(p, 0.0, 1.0) * static_cast<double>(values.size() - 1);
  const auto lo = static_cast<std::size_t>(std::floor(h));
  const std::size_t hi = std::min(lo + 1, values.size() - 1);
  return values[lo] + (h - static_cast<double>(lo)) * (values[hi] - values[lo]);
}

Distribution distribution(const SweepResult& result, std::string_view value) {
  Distribution d;
  for (std::size_t i = 0; i < result.rows.size(); ++i) {
    if (i >= result.done.size() || !result.done[i] || !result.rows[i].valid) continue;
    ++d.run;
    const double v = value_of(result.rows[i], value);
    if (!std::isnan(v)) d.values.push_back(v);
  }
  d.happened = static_cast<std::int64_t>(d.values.size());
  std::sort(d.values.begin(), d.values.end());
  return d;
}

namespace {
// One sweep as it runs: what its workers and the calling thread, which writes their rows, share.
// Workers claim small blocks of indices; each row lands in its own slot, so the rows (and the
// CSV) do not depend on which thread ran which machine. A finished block is marked done under
// the lock, which also hands its lines to the calling thread.
class SweepRun {
 public:
  SweepRun(const Config& base, const Machines& machines, const RunOptions& options)
      : base_(base),
        machines_(machines),
        options_(options),
        total_(machines.size()),
        keys_(machines.plan().keys()) {}

  SweepResult run() {
    prepare();
    std::vector<std::thread> pool = start_workers();
    write_while_running();
    for (std::thread& t : pool) t.join();
    if (failure_) std::rethrow_exception(failure_);
    return finish();
  }

 private:
  static constexpr std::int64_t kBlock = 8, kWake = 256;

  // The result's slots, and a resumed sweep's rows: those already in the file and the known ones
  // are done before any worker starts (workers skip them; nothing else writes their slots).
  void prepare() {
    if (options_.keep_rows) res_.rows.resize(static_cast<std::size_t>(total_));
    res_.done.assign(static_cast<std::size_t>(total_), 0);
    res_.lines.resize(static_cast<std::size_t>(total_));
    const std::int64_t already = std::clamp<std::int64_t>(options_.rows_written, 0, total_);
    for (std::int64_t i = 0; i < already; ++i) res_.done[static_cast<std::size_t>(i)] = 1;
    for (const auto& [index, line] : options_.known) {
      if (index < already || index >= total_ || res_.done[static_cast<std::size_t>(index)]) continue;
      res_.done[static_cast<std::size_t>(index)] = 1;
      res_.lines[static_cast<std::size_t>(index)] = line;
      ++known_;
    }
    next_ = already, completed_ = already + known_, written_ = already;
  }

  bool stopped() const {
    return failed_.load(std::memory_order_relaxed) ||
           (options_.stop && options_.stop->load(std::memory_order_relaxed));
  }

  // A worker's life. An exception in it (out of memory) stops the others and is thrown again by
  // the calling thread; escaping a worker it would end whatnext through std::terminate, with the
  // .part file left.
  void work() {
    try {
      Config work = base_;
      std::vector<double> values(keys_.size());
      for (;;) {
        const std::int64_t start = next_.fetch_add(kBlock);
        if (start >= total_) break;
        const std::int64_t end = run_block(work, values, start, std::min(total_, start + kBlock));
        {
          std::lock_guard<std::mutex> lock(m_);
          for (std::int64_t j = start; j < end; ++j) res_.done[static_cast<std::size_t>(j)] = 1;
        }
        // A few hundred lines waiting: time for the writer (cheap when it is awake already).
        if (options_.csv &&
            completed_.load(std::memory_order_relaxed) - written_.load(std::memory_order_relaxed) >= kWake) {
          cv_.notify_one();
        }
        if (stopped()) break;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(m_);
      if (!failure_) failure_ = std::current_exception();
      failed_ = true;
    }
    std::lock_guard<std::mutex> lock(m_);
    --running_;
    cv_.notify_all();
  }

  // Runs machines start..end-1 (until a stop) into their slots; returns where it stopped.
  std::int64_t run_block(Config& work, std::vector<double>& values, std::int64_t start, std::int64_t end) {
    std::int64_t i = start;
    for (; i < end && !stopped(); ++i) {
      const auto slot = static_cast<std::size_t>(i);
      if (known_ > 0 && res_.done[slot]) continue;  // a known row of a resumed sweep
      machines_.point(i, values.data());
      Outcome o = evaluate_in(work, keys_, values.data(), options_.accuracy);
      if (!o.valid) (o.failed ? failed_runs_ : invalid_).fetch_add(1, std::memory_order_relaxed);
      res_.lines[slot] = csv_row(i, values, o);  // formatted here, on all cores
      if (options_.keep_rows) res_.rows[slot] = std::move(o);
      completed_.fetch_add(1, std::memory_order_relaxed);
    }
    return i;
  }

  // As many workers as asked and there are machines.
  std::vector<std::thread> start_workers() {
    const int threads =
        static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(options_.threads, total_)));
    running_ = threads;
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(threads));
    try {
      for (int i = 0; i < threads; ++i) pool.emplace_back([this] { work(); });
    } catch (...) {  // no thread to be had (out of memory): stop those started, then say so
      failed_ = true;
      for (std::thread& t : pool) t.join();
      throw;
    }
    return pool;
  }

  // Meanwhile the calling thread writes the rows that are done, in index order, and lets their
  // lines go (their memory is used again: every page a sweep touches costs), every kWake rows
  // (waking it for every block cost more than it saved), and reports progress about ten times a
  // second, until the workers end.
  void write_while_running() {
    if (options_.csv && !options_.header_written) write_header(*options_.csv, machines_.plan());
    std::unique_lock<std::mutex> lock(m_);
    auto last_progress = std::chrono::steady_clock::now();
    auto last_checkpoint = last_progress;
    for (;;) {
      if (options_.csv) collect_ready();
      const bool finished = running_ == 0;
      if (!ready_.empty()) {
        lock.unlock();
        write_ready();
        lock.lock();
      }
      if (finished) break;
      const auto now = std::chrono::steady_clock::now();
      if (options_.checkpoint && now - last_checkpoint >= std::chrono::seconds(1)) {
        last_checkpoint = now;
        lock.unlock();
        options_.checkpoint();
        lock.lock();
      }
      if (options_.progress && now - last_progress >= std::chrono::milliseconds(100)) {
        last_progress = now;
        lock.unlock();
        options_.progress(completed_.load(), total_);
        lock.lock();
      }
      // The last worker may have ended while the rows above were written without the lock: its
      // notification is gone, and waiting for one would wait the whole 100 ms (one sweep in about
      // 25 took 0.1 s longer so). Under the lock from here to the wait, none is lost.
      if (running_ == 0) continue;
      if (options_.progress || options_.csv || options_.checkpoint) {
        cv_.wait_for(lock, std::chrono::milliseconds(100));
      } else {
        cv_.wait(lock);  // until a worker ends
      }
    }
  }

  // Under the lock: the lines of the rows done from the first one not written on, in order.
  void collect_ready() {
    std::int64_t w = written_.load(std::memory_order_relaxed);
    while (w < total_ && res_.done[static_cast<std::size_t>(w)]) {
      ready_.push_back(std::move(res_.lines[static_cast<std::size_t>(w)]));
      ++w;
    }
    written_.store(w, std::memory_order_relaxed);
  }

  void write_ready() {
    for (std::string& line : ready_) {
      options_.csv->write(line.data(), static_cast<std::streamsize>(line.size()));
      std::string().swap(line);
    }
    ready_.clear();
  }

  // The rows left to write after a stop, the final count (not the last tick's) and the tally.
  SweepResult finish() {
    if (options_.csv) {  // after a stop: the rows done beyond the first one that is not
      for (std::int64_t i = written_.load(); i < total_; ++i) {
        const auto slot = static_cast<std::size_t>(i);
        if (res_.done[slot]) ready_.push_back(std::move(res_.lines[slot]));
      }
      write_ready();
      res_.lines.clear();
    }
    if (options_.progress) options_.progress(completed_.load(), total_);
    res_.completed = completed_.load();
    res_.invalid = invalid_.load();
    res_.failed = failed_runs_.load();
    res_.interrupted = res_.completed < total_;
    return std::move(res_);
  }

  const Config& base_;
  const Machines& machines_;
  const RunOptions& options_;
  const std::int64_t total_;
  const std::vector<std::string> keys_;
  SweepResult res_;
  std::int64_t known_ = 0;  // rows of a resumed sweep given as known lines (not yet written)
  std::atomic<std::int64_t> next_{0}, completed_{0}, written_{0}, invalid_{0}, failed_runs_{0};
  int running_ = 0;  // workers not yet ended (under m_)
  std::mutex m_;
  std::condition_variable cv_;
  std::exception_ptr failure_;
  std::atomic<bool> failed_{false};
  std::vector<std::string> ready_;  // lines taken under the lock, to be written without it
};
}  // namespace

SweepResult run(const Config& base, const Machines& machines, const RunOptions& options) {
  return SweepRun(base, machines, options).run();
}

void write_csv(std::ostream& out, const Machines& machines, const SweepResult& result) {
  const Plan& plan = machines.plan();
  write_header(out, plan);
  std::vector<double> values(plan.ranges.size());
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    const auto slot = static_cast<std::size_t>(i);
    if (!result.done[slot]) continue;
    if (slot < result.lines.size() && !result.lines[slot].empty()) {
      out.write(result.lines[slot].data(), static_cast<std::streamsize>(result.lines[slot].size()));
      continue;
    }
    machines.point(i, values.data());
    const std::string row = csv_row(i, values, result.rows[slot]);
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
}

namespace {
// The start of machine i's row: its index and values, and the comma before its outcome.
std::string row_start(const Machines& machines, std::int64_t i, std::vector<double>& values) {
  machines.point(i, values.data());
  std::string out = fmt::format(FMT_COMPILE("{}"), i);
  for (double v : values) fmt::format_to(std::back_inserter(out), FMT_COMPILE(",{}"), v);
  return out + ",";
}

// The varied keys of a header line, for a message: "a, b" of "index,a,b,outcome,...".
std::string header_keys(std::string_view line) {
  const auto a = line.find(',');
  const auto b = line.find(",outcome,");
  if (line.rfind("index,", 0) != 0 || a == std::string_view::npos || b == std::string_view::npos || b <= a) {
    return fmt::format("'{}'", printable(line, 60));
  }
  std::string keys(line.substr(a + 1, b - a - 1));
  for (std::size_t p = 0; (p = keys.find(',', p)) != std::string::npos; p += 2) keys.replace(p, 1, ", ");
  return printable(keys, 120);
}

// The header line. Another sweep's columns are refused; false when the line is incomplete (the
// sweep was killed before it was written whole), and then nothing is kept.
bool check_header(std::string_view text, const std::string& header, std::string_view what,
                  const ResumeWords& words) {
  const auto eol = text.find('\n');
  if (eol == std::string_view::npos) {
    if (header.compare(0, text.size(), text) != 0 && text.find('\0') == std::string_view::npos) {
      throw InputError(fmt::format("{}: is not a CSV of this sweep (its first line is '{}'); {}", what,
                                   printable(text, 60), words.remedy));
    }
    return false;
  }
  const std::string_view first = text.substr(0, eol + 1);
  if (first != header) {
    throw InputError(
        fmt::format("{}: was written by a sweep over other columns (it varies {}; this sweep varies {}); {}",
                    what, header_keys(first.substr(0, first.size() - 1)),
                    header_keys(std::string_view(header).substr(0, header.size() - 1)), words.remedy));
  }
  return true;
}

// A row's machine index, or -1 for a damaged line (the zeros a power cut can leave, a line cut
// short): it and all after it are run again.
std::int64_t row_index(std::string_view line) {
  if (line.find('\0') != std::string_view::npos) return -1;
  std::int64_t index = 0;
  std::size_t k = 0;
  while (k < line.size() && line[k] >= '0' && line[k] <= '9' && k < 12)
    index = index * 10 + (line[k++] - '0');
  if (k == 0 || k >= line.size() || line[k] != ',') return -1;
  return index;
}

// A row of machine index (after the row of machine previous) must be this sweep's: in order, and
// with this plan's values. Returns what follows the values: the outcome's columns.
std::string_view checked_outcome(std::string_view line, std::int64_t index, std::int64_t previous,
                                 const Machines& machines, std::vector<double>& values, std::string_view what,
                                 const ResumeWords& words) {
  if (index <= previous || index >= machines.size()) {
    throw InputError(
        fmt::format("{}: holds a row for machine {}{}, which this sweep does not have there; the "
                    "file is another sweep's ({}): {}",
                    what, index, index <= previous ? " out of order" : "", words.plan, words.remedy));
  }
  const std::string start = row_start(machines, index, values);
  if (line.compare(0, start.size(), start) != 0) {
    throw InputError(
        fmt::format("{}: its row for machine {} has other values than this sweep's ({}); the file "
                    "is another sweep's ({}): {}",
                    what, index, printable(start.substr(0, start.size() - 1), 80), words.plan, words.remedy));
  }
  return line.substr(start.size());
}

// Running the first and the last kept machine again checks what the rows do not show: the
// machine the values were set on and the accuracy.
void check_by_running_again(const std::pair<std::int64_t, std::string_view> (&rows)[2],
                            const Machines& machines, const Config& base, double accuracy,
                            std::string_view what, const ResumeWords& words) {
  std::vector<double> values(machines.plan().ranges.size());
  const std::vector<std::string> keys = machines.plan().keys();
  for (const auto& [index, line] : rows) {
    machines.point(index, values.data());
    const std::string again = csv_row(index, values, evaluate(base, keys, values.data(), accuracy));
    if (again != line) {
      throw InputError(
          fmt::format("{}: machine {} gives another row now than in the file; the file is another "
                      "sweep's ({}): {}",
                      what, index, words.machine, words.remedy));
    }
  }
}
}  // namespace

Resumable read_resumable(std::string_view text, const Machines& machines, const Config& base, double accuracy,
                         std::string_view what, const ResumeWords& words) {
  Resumable r;
  const std::string header = csv_header(machines.plan());
  if (!check_header(text, header, what, words)) return r;
  r.header = true;
  r.prefix_bytes = header.size();
  std::vector<double> values(machines.plan().ranges.size());
  std::int64_t previous = -1;
  std::pair<std::int64_t, std::string_view> checked[2] = {{-1, {}}, {-1, {}}};  // the first and last row
  for (std::size_t pos = header.size(); pos < text.size();) {
    const auto end = text.find('\n', pos);
    if (end == std::string_view::npos) break;  // a partial last line
    const std::string_view line = text.substr(pos, end + 1 - pos);
    const std::int64_t index = row_index(line);
    if (index < 0) break;
    const std::string_view rest = checked_outcome(line, index, previous, machines, values, what, words);
    if (rest.rfind("invalid,", 0) == 0) ++r.invalid;
    if (rest.rfind("failed,", 0) == 0) ++r.failed;
    if (index == r.prefix_rows && r.later.empty()) {
      ++r.prefix_rows;
      r.prefix_bytes = end + 1;
    } else {
      r.later.emplace_back(index, std::string(line));
    }
    if (checked[0].first < 0) checked[0] = {index, line};
    checked[1] = {index, line};
    previous = index;
    ++r.kept;
    pos = end + 1;
  }
  if (checked[1].first >= 0) check_by_running_again(checked, machines, base, accuracy, what, words);
  return r;
}

std::string csv_row(std::int64_t index, const std::vector<double>& values, const Outcome& o) {
  // Compiled formats: the row is formatted for every machine, and the format strings' parsing
  // took as long as the formatting (callgrind).
  fmt::memory_buffer line;
  auto put = [&line](std::string_view text) { line.append(text.data(), text.data() + text.size()); };
  fmt::format_to(std::back_inserter(line), FMT_COMPILE("{}"), index);
  // "{}" prints the shortest text that reads back to the same double: lossless and deterministic.
  for (double v : values) fmt::format_to(std::back_inserter(line), FMT_COMPILE(",{}"), v);
  if (o.valid) {
    put(",");
    put(to_string(o.outcome));
    fmt::format_to(std::back_inserter(line), FMT_COMPILE(",{},{},{}"), o.outcome_t, o.final_r,
                   o.final_phi_l_deg);
    for (double t : o.first) {
      put(",");
      if (!std::isnan(t)) fmt::format_to(std::back_inserter(line), FMT_COMPILE("{}"), t);
    }
    put(",\n");
  } else {
    put(o.failed ? ",failed,,," : ",invalid,,,");
    for (std::size_t k = 0; k < o.first.size(); ++k) put(",");
    put(",");
    put(csv_quote(o.error));
    put("\n");
  }
  return std::string(line.data(), line.size());
}

}  // namespace whatnext::explore
