// Pieces shared by the subcommands of the whatnext command: how a run's input is chosen, how its
// output files are checked before any work, and how big a job may get without being asked.
#pragma once

#include <cmath>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "whatnext/config.hpp"
#include "whatnext/output.hpp"

// The command is two programs built from these sources. whatnext-full (WHATNEXT_FULL=1) does
// everything. whatnext (WHATNEXT_FULL=0) is what people wait for, run and sweep, and starts in
// about 3 ms more than /bin/true: no picture libraries (PLplot, Cairo, giflib and thirty more), no
// NLopt, and its C++ libraries linked in; loading them took 8-15 ms (docs/performance.md). It hands a command
// that draws (plot, animate, run --plots/--animate, sweep --heatmap) or optimises over to whatnext-full,
// whole and before any work.
#ifndef WHATNEXT_FULL
#define WHATNEXT_FULL 1
#endif

namespace whatnext::cli {

// The command line as main() got it, for hand_over_to_full().
void keep_command_line(int argc, char** argv);
// Replaces this process by whatnext-full with the same arguments (same process, so the same
// exit code and signals). It lies beside this program (the build tree) or in the installed
// libexec directory; a missing one is a broken installation (std::runtime_error: exit 1).
[[noreturn]] void hand_over_to_full();

struct InputOptions {
  std::string file;
  std::string example;  // as typed, so that "--example 0" and "--example x" are named in the error
  std::vector<std::string> sets;
};

// FILE | --example N, and any number of --set KEY=VALUE.
void add_input_options(CLI::App& cmd, InputOptions& opts);

struct LoadedInput {
  Config config;  // as read, with the --set overrides applied
  Scenario scenario;
  std::string source;  // for messages, titles and the timeline: "example 4 with --set masses.lid=0.7"
};
// Throws InputError for anything wrong with the input.
LoadedInput load_input(const InputOptions& opts);

// Arguments CLI11 could not place (each subcommand allows extras so that we can say what they
// are): a mistyped option gets "did you mean", a stray word a hint. Throws InputError.
void check_leftovers(const CLI::App& cmd);

// For a numeric option: the text must be one number, a whole one if `whole` ("1e3" is read as
// 1000), within [lo, hi] if those are given; otherwise "--grid: must be a whole number from 2 to
// 100000 (given 'abc')" instead of CLI11's "Could not convert" or "Value abc not in range". A whole
// number without a range is one an int holds.
CLI::Validator number_text(bool whole, double lo = -HUGE_VAL, double hi = HUGE_VAL);

// For an option that takes a seed: the text must be a whole number from 0 to 2^64 - 1, written
// out in digits (as Python's seed=); "-1", "2^64" and "1e23" are refused in one line instead of
// wrapping around or rounding to another seed.
CLI::Validator seed_text();

// True when the option was given on the command line (even as an empty string).
bool given(const CLI::App& cmd, const std::string& option);

// Throws InputError when `path` is the command's input file or one of its outputs already added
// (as given or through a symlink): an output must never overwrite the machine it was made from,
// nor another output. load_input and Outputs::add register what they see.
void check_unclaimed(const std::string& option, const std::string& path);

// The output files of one command, opened (and so checked) before any work, and committed
// together: if one fails to write, none of the others appears.
class Outputs {
 public:
  // Opens path for `option` if the option was given; nullptr otherwise.
  AtomicFile* add(const CLI::App& cmd, const std::string& option, const std::string& path);
  // Throws InputError when two outputs are the same file.
  void check_distinct() const;
  bool any_to_stdout() const;
  void commit_all();

 private:
  std::vector<std::unique_ptr<AtomicFile>> files_;
};

// Jobs bigger than this need --force-large: the estimate names the size and how to shrink it.
constexpr double kLargeBytes = 256.0 * 1024 * 1024;
// What one state kept in memory for the pictures takes, at most, for check_size.
constexpr double kStateBytes = 600.0;
// Output rows a run may write: one per run.output_step up to run.t_max, and the events.
double max_rows(const Scenario& scenario);
// Throws InputError when `bytes_per_row * max_rows` exceeds kLargeBytes and force is false.
void check_size(const Scenario& scenario, double bytes_per_row, const std::string& option, bool force,
                const std::string& what = "write");
#if WHATNEXT_FULL
// The directory given to --plots or --out of plot: created if missing (and removed again if the
// command then fails or is interrupted while it is still empty); a figure it would hold must not
// be the input or another output (check_unclaimed).
void prepare_picture_dir(const std::string& dir, const std::string& option);
#endif
// Removes the directories prepare_picture_dir created, if they are still empty.
void remove_empty_picture_dirs();

// A sweep's interrupts from the process's start on: one that lands before the sweep can stop
// (cmd_sweep.cpp) is held, and the sweep then ends at once with 128 + its number.
void hold_early_interrupts();

// Each subcommand registers itself and sets `exit_code` when it runs.
void register_run(CLI::App& app, int& exit_code);       // cmd_run.cpp
void register_plot(CLI::App& app, int& exit_code);      // cmd_plot.cpp
void register_animate(CLI::App& app, int& exit_code);   // cmd_animate.cpp
void register_sweep(CLI::App& app, int& exit_code);     // cmd_sweep.cpp
void register_optimize(CLI::App& app, int& exit_code);  // cmd_optimize.cpp

}  // namespace whatnext::cli
