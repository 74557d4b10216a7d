// Many machines at once: a parameter grid or a Latin hypercube over input keys, run on all cores,
// one outcome row per machine. Rows depend only on the plan, never on the thread count.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <iosfwd>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"

namespace whatnext::explore {

// One varied key: values lo..hi, n of them on a grid (n = 0 where no count is needed).
struct Range {
  std::string key;
  double lo = 0.0, hi = 0.0;
  int n = 0;
};

// Parses "KEY=A:B:N" (need_count) or "KEY=A:B" (count optional) as given to the option named by
// option ("--vary"). Checks the key against the input keys (with a suggestion), A <= B, N >= 1.
// Throws InputError with one line naming the option, the rule and the value.
Range parse_range(std::string_view spec, std::string_view option, bool need_count);

// Monte Carlo over building tolerances (docs/explore.md, "Would the built machine work?"):
// each machine is the base machine with every spread key off by a random amount.
enum class SpreadKind { normal, uniform };
struct Spread {
  std::string key;
  double x = 0.0;  // normal: standard deviation; uniform: half-width (in the key's input unit)
};
// Parses "KEY=±X" (or KEY=+-X) as given to option ("--spread"): a numeric input key and X > 0.
// Throws InputError with one line naming the option, the rule and the value.
Spread parse_spread(std::string_view spec, std::string_view option);
// Throws InputError naming option unless kind is "normal" or "uniform".
SpreadKind parse_spread_kind(std::string_view kind, std::string_view option);
// The value a machine gives a numeric key (in its input unit): its own, or the documented default.
// Throws InputError naming option when the default is not a number (it follows from other keys).
double base_value(const Config& config, const std::string& key, std::string_view option);

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
  std::int64_t size() const { return size_; }
  const Plan& plan() const { return plan_; }
  // Values of machine i, one per range, written to out[0..ranges).
  void point(std::int64_t i, double* out) const;

 private:
  Machines() = default;
  static Machines of_keys(std::vector<std::string> keys);
  Plan plan_;
  std::int64_t size_ = 0;
  std::vector<double> lhs_;  // Latin hypercube: size_ x ranges values, row-major
  // A grid's values per range, made once (tidying a value formats and parses it), for ranges of
  // up to kCachedValues values; longer ones are computed per machine.
  static constexpr std::int64_t kCachedValues = 1 << 16;
  std::vector<std::vector<double>> grid_;
  double grid_value(std::size_t d, std::int64_t j) const;
};

// At most this many machines in one sweep (every row is kept in memory until the CSV is written).
constexpr std::int64_t kMaxMachines = 20'000'000;

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

// Builds the machine (base with the given values set) and runs it, to the event-time accuracy
// given (0: the machine's own settings). Invalid inputs and failed runs give an Outcome with
// valid == false and the reason, never an exception.
Outcome evaluate(const Config& base, const std::vector<std::string>& keys, const double* values,
                 double accuracy = kDefaultAccuracy);
// One CSV row of a sweep (write_csv's layout, with its newline).
std::string csv_row(std::int64_t index, const std::vector<double>& values, const Outcome& o);

// Names usable as a value of an outcome: "outcome_t", "final_r", "final_phi_l_deg" and every
// event name (its first occurrence time).
std::vector<std::string> value_names();
// Throws InputError (naming option) for an unknown value name.
void check_value_name(std::string_view name, std::string_view option);
// The named value of an outcome; NaN when it did not happen or the machine is invalid.
double value_of(const Outcome& o, std::string_view name);

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
  // A resumed sweep (docs/explore.md, "Resuming a sweep"): csv already holds the header (when
  // header_written) and the rows of machines 0..rows_written-1, and `known` holds finished rows
  // further on as (index, CSV line), in increasing index order. None of them runs again; the
  // known lines are written in their places. rows_written > 0 needs header_written.
  bool header_written = false;
  std::int64_t rows_written = 0;
  std::vector<std::pair<std::int64_t, std::string>> known;
  // Called on the calling thread, after it wrote rows, about once a second: where the CSV is
  // made durable as it goes (flushed and synced), so that a kill or a power cut keeps those rows.
  std::function<void()> checkpoint;
};

struct SweepResult {
  std::vector<Outcome> rows;  // by machine index (empty unless RunOptions::keep_rows)
  std::vector<std::string>
      lines;               // rows[i] as its CSV line, formatted by the workers (or empty: RunOptions::csv)
  std::vector<char> done;  // done[i]: machine i has run (its outcome in rows[i] where kept)
  std::int64_t completed = 0;
  std::int64_t invalid = 0, failed = 0;  // of the completed machines: invalid inputs, failed runs
  bool interrupted = false;
};

// The quantiles of a value over a sweep's machines where it happened.
struct Distribution {
  std::int64_t run = 0;        // machines that ran (valid)
  std::int64_t happened = 0;   // of them, where the value happened
  std::vector<double> values;  // those values, sorted
  // The p-quantile (0 <= p <= 1) by linear interpolation between order statistics; NaN if none.
  double quantile(double p) const;
};
Distribution distribution(const SweepResult& result, std::string_view value);

// Runs every machine.
SweepResult run(const Config& base, const Machines& machines, const RunOptions& options);

// CSV with a header and one row per finished machine in index order: index, the varied values,
// outcome (an event name, "invalid" or "failed"), outcome_t, final_r, final_phi_l_deg, one column
// per event type (first time, empty if none), error. Numbers in the shortest form that reads back
// as the same double.
void write_csv(std::ostream& out, const Machines& machines, const SweepResult& result);

// The header line of a sweep's CSV (with its newline).
std::string csv_header(const Plan& plan);

// What an interrupted sweep's CSV holds that a resumed sweep can keep (RunOptions).
struct Resumable {
  std::size_t prefix_bytes = 0;  // text[0, prefix_bytes): the header and the rows of 0..prefix_rows-1
  bool header = false;           // the header is complete (else nothing is kept)
  std::int64_t prefix_rows = 0;
  std::vector<std::pair<std::int64_t, std::string>> later;  // complete rows after a gap
  std::int64_t kept = 0, invalid = 0, failed = 0;           // rows kept, and of them invalid / failed
};
// Reads the text of a CSV written by a sweep that was stopped (Ctrl-C), killed or cut off by a
// power cut: every complete row (ending in a newline) up to the first damaged one (a partial or
// garbled line, say the zeros a power cut leaves) is kept, the rest is run again. Throws InputError
// naming `what` (the option and file) when the file is another sweep's: other columns, a row
// whose index or values are not this plan's, or a kept row that running its machine again (with
// base and accuracy) does not reproduce byte for byte (another machine or --accuracy).
// The words of read_resumable's messages for what the user can change: the command's by default.
struct ResumeWords {
  std::string_view remedy = "give another --out or drop --resume";
  std::string_view plan = "other --vary, --samples or --seed";
  std::string_view machine = "another machine, --set or --accuracy";
};
Resumable read_resumable(std::string_view text, const Machines& machines, const Config& base, double accuracy,
                         std::string_view what, const ResumeWords& words = {});

}  // namespace whatnext::explore
