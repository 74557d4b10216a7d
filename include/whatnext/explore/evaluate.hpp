// One machine of a sweep: built from the base machine with the varied values set, run to the
// event-time accuracy asked for (with the second runs that takes), and what became of it.
#pragma once

#include <string>
#include <string_view>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"

namespace whatnext::explore {

// Every event type, in declaration order: the event columns of a sweep. Read from the names
// table, so a type added to events.hpp and names.cpp appears without touching this code.
const std::vector<EventType>& event_types();

// What became of one machine.
struct Outcome {
  bool valid = false;
  bool failed = false;  // valid inputs, but the run stopped with a SimulationError
  std::string error;    // the InputError or SimulationError message when not valid
  EventType outcome = EventType::timeout;
  double outcome_t = 0.0;
  double final_r = 0.0;          // sandbag's distance from the pivot when the run ended [m]
  double final_phi_l_deg = 0.0;  // lid angle when the run ended [deg]
  std::vector<double> first;     // per event_types() entry: first occurrence [s], NaN if none
};

// The event-time accuracy a sweep asks for unless told otherwise [s].
constexpr double kDefaultAccuracy = 1e-8;
// The accuracies a sweep accepts [s]: the tolerance becomes a fifteenth of it (at least 1e-15,
// run.tolerance's floor).
constexpr double kMinAccuracy = 1e-14, kMaxAccuracy = 1e-2;
// Throws InputError naming `option` ("--accuracy", "accuracy") when accuracy is outside that range.
void check_accuracy(double accuracy, std::string_view option);
// Sets the run to locate every event within `accuracy` seconds of the exact time, as cheaply as
// that allows: the integrator's tolerance accuracy / 15, unless the machine gives run.tolerance
// itself, and the events located to accuracy / 1000. A sweep also runs some machines again
// (evaluate(); docs/performance.md, "Sweeps").
void apply_accuracy(Scenario& scenario, double accuracy, bool tolerance_given);

// Evaluates machines one after another on one thread: keeps a scratch copy of the base machine,
// which each machine's values are set in (copying the base for every machine costs).
class Evaluator {
 public:
  Evaluator(const Config& base, std::vector<std::string> keys, double accuracy);
  // Builds the machine (base with values[k] set for keys[k]) and runs it, to the event-time
  // accuracy given (0: the machine's own settings). Invalid inputs and failed runs give an Outcome
  // with valid == false and the reason, never an exception.
  Outcome operator()(const double* values);

 private:
  Config work_;
  std::vector<std::string> keys_;
  double accuracy_;
};

// One machine, as Evaluator does it.
Outcome evaluate(const Config& base, const std::vector<std::string>& keys, const double* values,
                 double accuracy = kDefaultAccuracy);

// Names usable as a value of an outcome: "outcome_t", "final_r", "final_phi_l_deg" and every
// event name (its first occurrence time).
std::vector<std::string> value_names();
// Throws InputError (naming option) for an unknown value name.
void check_value_name(std::string_view name, std::string_view option);
// The named value of an outcome; NaN when it did not happen or the machine is invalid.
double value_of(const Outcome& o, std::string_view name);

}  // namespace whatnext::explore
