// Observers and writers of a run: the readable timeline, events JSON, CSV and the paper's .dat
// layout.
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <vector>

#include "whatnext/columns.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext {

// The writers below refuse states that are not finite: they throw SimulationError (from inside
// simulate() for the observers), so a run that turned NaN is reported as failed, never written.
// This is their check, for callers that keep a Result: SimulationError if an event's state is not
// finite.
void require_finite(const Result& result);

// "lid open at 0.820 s" and its relatives.
// An impact's impulses per contact, e.g. "sandbag 1.0600 N s, rope 0.7269 N s" ("" for none).
std::string impulse_text(const Event& e);
std::string outcome_sentence(const Result& result);
// The timeline printed by `whatnext run`.
std::string timeline_text(const Result& result, const Scenario& scenario, const std::string& source);
// {"outcome": {...}, "events": [...]} with the event names of docs/model.md §6.
std::string events_json(const Result& result, const Scenario& scenario, const std::string& source);

// Keeps every sample and event in memory (for plots, animation and tests).
class Recorder : public Observer {
 public:
  void on_sample(const Snapshot& s) override { samples.push_back(s); }
  void on_event(const Event& e) override { events.push_back(e); }
  std::vector<Snapshot> samples;
  std::vector<Event> events;
};

// How the CSV and .dat writers make their rows. at_once: on the thread that runs the machine.
// parallel: a batch of samples (SampleBatch: up to 2048, or a piece's) is made into rows on that
// thread and on a helper thread of the writer's own, in chunks, and written in order before
// on_samples returns (example 3 at the paper's step: the text of 80,000 rows and the positions
// they need cost ten times the run). The same bytes either way; on one core, or where no thread
// can be started, parallel is at_once.
enum class Writing { at_once, parallel };
class RowText;  // output.cpp

// CSV: a row per output sample and a row (with the event's name) after each event.
class CsvWriter : public Observer {
 public:
  // impulses: how many of the impulse columns (columns.hpp impulse_columns(machine)).
  explicit CsvWriter(std::ostream& out, Writing writing = Writing::at_once,
                     std::size_t impulses = kPaperImpulses);
  ~CsvWriter() override;
  void on_sample(const Snapshot& s) override;
  void on_samples(const SampleBatch& batch) override;
  void on_event(const Event& e) override;
  static std::string header(std::size_t impulses = kPaperImpulses);

 private:
  std::size_t impulses_;
  std::unique_ptr<RowText> rows_;
};

// The paper's whatnext.dat: t, xs, hs, phiS, phiL, hbl, hb, cr, straight in Fortran 9F8.3.
// Positions only: it asks for samples of Detail::positions.
class DatWriter : public Observer {
 public:
  explicit DatWriter(std::ostream& out, Writing writing = Writing::at_once);
  ~DatWriter() override;
  Detail sample_detail() const override { return Detail::positions; }
  void on_sample(const Snapshot& s) override;
  void on_samples(const SampleBatch& batch) override;
  void on_event(const Event& e) override;

 private:
  std::unique_ptr<RowText> rows_;
  bool slack_since_last_row_ = false;
};

// Fortran's Fw.d edit descriptor: right-justified, asterisks when the number does not fit.
std::string fortran_f(double value, int width, int decimals);

// Sends each sample and event to several observers.
class Fanout : public Observer {
 public:
  void add(Observer* o) { targets_.push_back(o); }
  bool empty() const { return targets_.empty(); }
  Detail sample_detail() const override {
    for (const Observer* o : targets_) {
      if (o->sample_detail() == Detail::full) return Detail::full;
    }
    return Detail::positions;
  }
  void on_sample(const Snapshot& s) override {
    for (Observer* o : targets_) o->on_sample(s);
  }
  void on_samples(const SampleBatch& batch) override {
    for (Observer* o : targets_) o->on_samples(batch);
  }
  void on_event(const Event& e) override {
    for (Observer* o : targets_) o->on_event(e);
  }

 private:
  std::vector<Observer*> targets_;
};

}  // namespace whatnext
