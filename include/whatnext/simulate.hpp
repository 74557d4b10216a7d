// One run of the machine: the automaton of model.hpp driven by the chosen integrator.
#pragma once

#include <cstddef>
#include <stdexcept>
#include <vector>

#include "whatnext/events.hpp"
#include "whatnext/params.hpp"
#include "whatnext/state.hpp"
#include "whatnext/step_stats.hpp"

namespace whatnext {

// A run that cannot go on: the state turned non-finite, or the integrator exhausted its step budget.
// The message is one line naming the time and the mode; nothing of the run should be written.
class SimulationError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// A run ended early because its observer's keep_going() returned false (Ctrl-C in Python).
class Cancelled : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

class Model;  // model.hpp

// Samples of one smooth piece of a run, in time order, as the integrator left them: each becomes
// a Snapshot only when asked for, at the detail its observer reads. snapshot() may be called from
// several threads at once (the writers make their rows on two; output.hpp).
class SampleBatch {
 public:
  SampleBatch(const Model& model, bool full) : model_(&model), full_(full) {}
  std::size_t size() const { return times_.size(); }
  double time(std::size_t i) const { return times_[i]; }
  Snapshot snapshot(std::size_t i) const;
  // snapshot(i)'s positions (the same bits), without the rest of a Snapshot.
  Positions positions(std::size_t i) const;
  // For simulate(): a new piece in discrete state d, and its samples.
  void start(const Discrete& d) {
    d_ = d;
    clear();
  }
  void add(double t, const State& y) {
    times_.push_back(t);
    states_.push_back(y);
  }
  void clear() {
    times_.clear();
    states_.clear();
  }
  void reserve(std::size_t n) {
    times_.reserve(n);
    states_.reserve(n);
  }

 private:
  const Model* model_;
  bool full_;
  Discrete d_;
  std::vector<double> times_;
  std::vector<State> states_;
};

// Receives the run as it happens: samples on the run.output_step grid and every event.
// Called per output sample (or batch of them) and per event, never per integration step.
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
  // The samples come in batches, each within one piece (all of them before the events that end
  // it) and in time order. By default each is handed to on_sample.
  virtual void on_samples(const SampleBatch& batch) {
    for (std::size_t i = 0; i < batch.size(); ++i) on_sample(batch.snapshot(i));
  }
  virtual void on_event(const Event& e) { (void)e; }
  // Polled every 256 integration steps: false ends the run with Cancelled. Keep it cheap.
  virtual bool keep_going() { return true; }
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
