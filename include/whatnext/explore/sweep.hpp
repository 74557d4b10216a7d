// Many machines at once: a parameter grid, a Latin hypercube or a Monte Carlo over input keys, run
// on all cores, one outcome row per machine. Rows depend only on the plan, never on the thread
// count. The rooms: spec.hpp (what is varied), plan.hpp (which machines), evaluate.hpp (one
// machine), pool.hpp (the threads), rows.hpp (the CSV's rows), stats.hpp (a value's distribution),
// sweep_job.hpp (a sweep written to a file, resumably).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <utility>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/explore/evaluate.hpp"
#include "whatnext/explore/plan.hpp"
#include "whatnext/explore/rows.hpp"
#include "whatnext/explore/spec.hpp"
#include "whatnext/explore/stats.hpp"

namespace whatnext::explore {

struct RunOptions {
  int threads = 1;
  double accuracy = kDefaultAccuracy;       // event times [s]; see apply_accuracy
  const std::atomic<bool>* stop = nullptr;  // set (e.g. by SIGINT) to stop early
  // Called on the calling thread about ten times a second with (done, total).
  std::function<void(std::int64_t, std::int64_t)> progress;
  // If given, the CSV (write_csv's layout) is written here by the calling thread while the
  // machines run, rows in index order as they are done, and SweepResult::lines is left empty.
  std::ostream* csv = nullptr;
  // false: SweepResult::rows stays empty, for a caller that wants the CSV alone (with csv given):
  // every outcome kept is memory touched, and on a virtual machine a fresh page costs as much as
  // a third of a machine's run (docs/performance.md).
  bool keep_rows = true;
  // A resumed sweep (SweepJob): csv already holds the header (when header_written) and the rows
  // of machines 0..rows_written-1, and `known` holds finished rows further on as (index, CSV
  // line), in increasing index order. None of them runs again; the known lines are written in
  // their places. rows_written > 0 needs header_written.
  bool header_written = false;
  std::int64_t rows_written = 0;
  std::vector<std::pair<std::int64_t, std::string>> known;
  // Called on the calling thread, after it wrote rows, about once a second: where the CSV is
  // made durable as it goes (flushed and synced), so that a kill or a power cut keeps those rows.
  std::function<void()> checkpoint;
};

struct SweepResult {
  std::vector<Outcome> rows;  // by machine index (empty unless RunOptions::keep_rows)
  // rows[i] as its CSV line, formatted by the workers (or empty: RunOptions::csv)
  std::vector<std::string> lines;
  std::vector<char> done;  // done[i]: machine i has run (its outcome in rows[i] where kept)
  std::int64_t completed = 0;
  std::int64_t invalid = 0, failed = 0;  // of the completed machines: invalid inputs, failed runs
  bool interrupted = false;
};

// Runs every machine.
SweepResult run(const Config& base, const Machines& machines, const RunOptions& options);

// Runs machines begin..end-1 of `machines` (threads, accuracy, stop and progress of options; a
// stop leaves the machines not run with a default Outcome, and `done` says which ran): the
// evaluation of one chunk of a distributed sweep (Python's Dask sweeps). Each row depends only on
// its machine, so chunks run anywhere give the rows of one sweep.
std::vector<Outcome> run_chunk(const Config& base, const Machines& machines, std::int64_t begin,
                               std::int64_t end, const RunOptions& options,
                               std::vector<char>* done = nullptr);

inline Distribution distribution(const SweepResult& result, std::string_view value) {
  return distribution(result.rows, result.done, value);
}

}  // namespace whatnext::explore
