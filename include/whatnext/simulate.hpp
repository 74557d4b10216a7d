// One run of the machine: the automaton of model.hpp driven by the chosen integrator.
#pragma once

#include <stdexcept>
#include <vector>

#include "whatnext/events.hpp"
#include "whatnext/integrate.hpp"
#include "whatnext/params.hpp"
#include "whatnext/state.hpp"

namespace whatnext {

// A run that cannot go on: the state turned non-finite, or the integrator exhausted its step budget.
// The message is one line naming the time and the mode; nothing of the run should be written.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// Receives the run as it happens: samples on the run.output_step grid and every event.
// Called per output sample and per event, never per integration step.
class Observer {
 public:
  // How much of each sample's Snapshot the observer reads. positions: t, the mode and contacts,
  // where everything is (x, h, r, phi_s, phi_l, the balloon's height and its limit), everything
  // else zero; full: also the rates, the contact forces, the energies and the ledger, which cost a
  // contact problem per sample. Event states are always full.
  enum class Detail { positions, full };
  virtual Detail sample_detail() const { return Detail::full; }
  virtual ~Observer() = default;
  virtual void on_sample(const Snapshot& s) { (void)s; }
  virtual void on_event(const Event& e) { (void)e; }
};

struct Result {
  std::vector<Event> events;  // in order; the last one ended the run
  StepStats stats;
  const Event& outcome() const { return events.back(); }
};

// Maximum number of events in one run before it is stopped with event_limit.
constexpr int kMaxEvents = 10000;

// Runs the scenario (which must come from validation, see config.hpp). Samples go to the observer
// only if one is given; without one nothing is sampled.
Result simulate(const Scenario& scenario, Observer* observer = nullptr);

}  // namespace whatnext
