#include "whatnext/explore/evaluate.hpp"

#include <cmath>
#include <exception>
#include <limits>
#include <utility>

#include <fmt/format.h>

#include "whatnext/writers.hpp"
#include "whatnext/simulate.hpp"
#include "whatnext/units.hpp"

namespace whatnext::explore {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
constexpr double kInf = std::numeric_limits<double>::infinity();

void set_values(Config& cfg, const std::vector<std::string>& keys, const double* values) {
  for (std::size_t k = 0; k < keys.size(); ++k) set_number(cfg, keys[k], values[k]);
}

// An event's reported time uncertainty is the integrator's local error carried to the event
// (Crossing::uncertainty). Measured against runs at tolerance 1e-14 on random machines, the error
// can be several times that: 1.4 times on docs/performance.md's 10^4 grid, 5 times where an uncertain
// rope_slack moved the lid's opening after it, and far more where the seesaw has mass or the hinges damp,
// since errors then travel along long pieces and through later impacts (250 times after 1.1 s of
// a heavy seesaw holding the lid; a heavy seesaw's sandbag that grazes the pivot reaches it or
// not by the last digits). An impact also multiplies the error of its own time: located to
// accuracy/100, a rope_taut moved a lid's opening by 0.75 of the accuracy (apply_accuracy now
// locates events to accuracy/1000, which costs 1 %). So, besides the tolerance of accuracy/15:
//  * a machine whose reported times are uncertain beyond kUncertaintyTrigger of the accuracy is
//    run again, as tightly as brings the uncertainty to kUncertaintyTarget of it;
//  * a machine with a heavy seesaw, damping or the balloon's drag is run again, each time a
//    hundredfold tighter, until two runs report the same events within kAgreement of the
//    accuracy (the last run's error is then about a hundredth of their difference, whatever the
//    estimate says). With drag the estimate fell 7-fold short once (a lid_open 1.56 times the
//    accuracy off, reported at 0.22: the ex1-hinge-drag family, seed 7, 3,000 machines, 118);
//    those sweeps now take 2.4 times as long.
// With these, 5,000 random machines of each of fifteen families (examples 1-4 varied, the laws,
// a heavy seesaw, damping, drag, the radio, the built machine, friction, the stretchy rope) are
// within 0.66 of the accuracy for three seeds (scripts/check-sweep-accuracy.py reproduces it;
// docs/performance.md).
constexpr double kUncertaintyTrigger = 0.3;
constexpr double kUncertaintyTarget = 0.2;
constexpr double kAgreement = 0.5;
constexpr double kTighter = 0.01;
constexpr int kMaxReruns = 4;
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
// velocity along the contact's normal, which is about zero. On that grid it leaves 402
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
Outcome run_machine(Config& work, const std::vector<std::string>& keys, const double* values,
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
      const bool carries_errors = m.seesaw_inertia > 0.0 || m.pivot_damping > 0.0 ||
                                  m.lid_hinge_damping > 0.0 || m.balloon_drag_rate() > 0.0;
      double u = reported_uncertainty(res, accuracy);
      // A run again locates its events for its tighter tolerance: an earlier event placed less
      // exactly than that would move the later ones as much (and see kRerunLocating).
      const auto locate_for_tolerance = [&sc, accuracy] {
        sc.run.event_time_tolerance = std::fmin(
            std::fmin(sc.run.event_time_tolerance, sc.run.tolerance / 10.0), kRerunLocating * accuracy);
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

Evaluator::Evaluator(const Config& base, std::vector<std::string> keys, double accuracy)
    : work_(base), keys_(std::move(keys)), accuracy_(accuracy) {}

Outcome Evaluator::operator()(const double* values) { return run_machine(work_, keys_, values, accuracy_); }

Outcome evaluate(const Config& base, const std::vector<std::string>& keys, const double* values,
                 double accuracy) {
  Config work = base;
  return run_machine(work, keys, values, accuracy);
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

}  // namespace whatnext::explore
