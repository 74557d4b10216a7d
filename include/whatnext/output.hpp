// Observers and writers: the readable timeline, events JSON, CSV and the paper's .dat layout.
// Files are written beside their target and renamed into place only when complete.
#pragma once

#include <fstream>
#include <memory>
#include <string>
#include <vector>

#include "whatnext/simulate.hpp"

namespace whatnext {

// A file that appears under its name only after commit(); otherwise nothing is left behind.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  std::ofstream& stream() { return out_; }
  const std::string& path() const { return path_; }
  void commit();

 private:
  std::string path_, tmp_;
  std::ofstream out_;
  bool committed_ = false;
};

// "lid open at 0.820 s" and its relatives.
std::string outcome_sentence(const Result& result);
// The timeline printed by `whatnext run`.
std::string timeline_text(const Result& result, const Scenario& scenario, const std::string& source);
// {"outcome": {...}, "events": [...]} with MODEL.md's event names.
std::string events_json(const Result& result, const Scenario& scenario, const std::string& source);

// Keeps every sample and event in memory (for plots, animation and tests).
class Recorder : public Observer {
 public:
  void on_sample(const Snapshot& s) override { samples.push_back(s); }
  void on_event(const Event& e) override { events.push_back(e); }
  std::vector<Snapshot> samples;
  std::vector<Event> events;
};

// CSV: a row per output sample and a row (with the event's name) after each event.
class CsvWriter : public Observer {
 public:
  explicit CsvWriter(std::ostream& out);
  void on_sample(const Snapshot& s) override;
  void on_event(const Event& e) override;
  static const char* header();

 private:
  void row(const Snapshot& s, const char* event);
  std::ostream& out_;
};

// The paper's whatnext.dat: t, xs, hs, phiS, phiL, hbl, hb, cr, straight in Fortran 9F8.3.
class DatWriter : public Observer {
 public:
  explicit DatWriter(std::ostream& out) : out_(out) {}
  void on_sample(const Snapshot& s) override;
  void on_event(const Event& e) override;

 private:
  std::ostream& out_;
  bool slack_since_last_row_ = false;
};

// Fortran's Fw.d edit descriptor: right-justified, asterisks when the number does not fit.
std::string fortran_f(double value, int width, int decimals);

// Sends each sample and event to several observers.
class Fanout : public Observer {
 public:
  void add(Observer* o) { targets_.push_back(o); }
  bool empty() const { return targets_.empty(); }
  void on_sample(const Snapshot& s) override {
    for (Observer* o : targets_) o->on_sample(s);
  }
  void on_event(const Event& e) override {
    for (Observer* o : targets_) o->on_event(e);
  }

 private:
  std::vector<Observer*> targets_;
};

}  // namespace whatnext
