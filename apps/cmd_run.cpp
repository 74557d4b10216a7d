// `whatnext run`: one machine, its timeline on stdout and the requested files.
#include <cstdio>
#include <memory>
#include <string>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/output.hpp"
#if WHATNEXT_FULL
#include "whatnext/viz/animation.hpp"
#include "whatnext/viz/plots.hpp"
#endif

namespace whatnext::cli {

namespace {
struct RunOptions {
  InputOptions input;
  std::string events, csv, dat;
  std::string plots, animate;  // pictures (whatnext plot / animate with their defaults)
  bool quiet = false, force_large = false;
};

// Upper bounds of what one output row takes, for the size check: a CSV row of 32 numbers and a
// .dat row (9F8.3 and a newline).
constexpr double kCsvRowBytes = 400.0, kDatRowBytes = 73.0;

// The outputs' sizes against what a run may write or hold without --force-large.
void check_sizes(const CLI::App& cmd, const RunOptions& opts, const Scenario& sc) {
  if (given(cmd, "--csv")) check_size(sc, kCsvRowBytes, "--csv", opts.force_large);
  if (given(cmd, "--dat")) check_size(sc, kDatRowBytes, "--dat", opts.force_large);
  if (given(cmd, "--plots") || given(cmd, "--animate")) {
    check_size(sc, kStateBytes, given(cmd, "--plots") ? "--plots" : "--animate", opts.force_large,
               "hold in memory");
  }
}

// The run, its rows written to the CSV and .dat files that are asked for.
Result simulate_into(const Scenario& sc, AtomicFile* csv_file, AtomicFile* dat_file) {
  Fanout fan;
  std::unique_ptr<CsvWriter> csv;
  std::unique_ptr<DatWriter> dat;
  // Both make their rows on two threads: example 3 at the paper's step writes 80,000 rows, and
  // their positions and text cost ten times the run (docs/performance.md).
  if (csv_file) {
    csv = std::make_unique<CsvWriter>(csv_file->stream(), Writing::parallel, impulse_columns(sc.machine));
    fan.add(csv.get());
  }
  if (dat_file) {
    dat = std::make_unique<DatWriter>(dat_file->stream(), Writing::parallel);
    fan.add(dat.get());
  }
  Observer* observer = csv && dat ? &fan : csv ? static_cast<Observer*>(csv.get()) : dat.get();
  return simulate(sc, observer);
}

#if WHATNEXT_FULL
// The pictures' targets made ready before the run: the --plots folder, and the --animate file
// (returned; empty without it).
std::string prepare_pictures(const CLI::App& cmd, const RunOptions& opts) {
  if (given(cmd, "--plots")) prepare_picture_dir(opts.plots, "--plots");
  std::string animation;
  if (given(cmd, "--animate")) {
    animation = regular_output_target(opts.animate, "--animate");
    viz::check_animation_target(animation, "--animate");
    check_unclaimed("--animate", animation);  // not the input, not --csv/--dat/--events
  }
  return animation;
}

// The --plots figures and the --animate film of the run, each named on `text` unless --quiet.
void draw_pictures(const CLI::App& cmd, const RunOptions& opts, const LoadedInput& in,
                   const std::string& animation, std::FILE* text) {
  if (!given(cmd, "--plots") && !given(cmd, "--animate")) return;
  const viz::Recording rec = viz::record(in.scenario);
  if (given(cmd, "--plots")) {
    viz::FigureOptions fig;
    fig.title = in.source;
    const auto files = viz::write_run_figures(rec, opts.plots, fig);
    if (!opts.quiet) fmt::print(text, "Plots: {} files in {}\n", files.size(), printable(opts.plots, 96));
  }
  if (given(cmd, "--animate")) {
    const int frames = viz::write_animation(rec, animation, viz::AnimationOptions{}, "", "--animate");
    if (!opts.quiet) fmt::print(text, "Animation: {} ({} frames)\n", printable(opts.animate, 96), frames);
  }
}
#endif
}  // namespace

void register_run(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "simulate one machine and print its timeline");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--events", opts->events, "write the events as JSON to this file ('-': standard output)");
  cmd->add_option("--csv", opts->csv, "write the sampled state as CSV to this file ('-': standard output)");
  cmd->add_option("--dat", opts->dat,
                  "write the paper's whatnext.dat layout to this file ('-': standard output)");
  cmd->add_option("--plots", opts->plots, "also draw the paper's figures into this directory");
  cmd->add_option("--animate", opts->animate, "also write an animation to this .gif (or .mp4)");
  cmd->add_flag("-q,--quiet", opts->quiet, "print only the outcome line");
  cmd->add_flag("--force-large", opts->force_large,
                "write outputs even when they would be larger than 256 MB");
  cmd->callback([opts, cmd, &exit_code] {
#if !WHATNEXT_FULL
    if (given(*cmd, "--plots") || given(*cmd, "--animate")) hand_over_to_full();
#endif
    check_leftovers(*cmd);
    const LoadedInput in = load_input(opts->input);
    // Every output is checked (and its temporary opened) before any work; files appear only when
    // all of them are complete.
    check_sizes(*cmd, *opts, in.scenario);
    Outputs outputs;
    AtomicFile* csv_file = outputs.add(*cmd, "--csv", opts->csv);
    AtomicFile* dat_file = outputs.add(*cmd, "--dat", opts->dat);
    AtomicFile* events_file = outputs.add(*cmd, "--events", opts->events);
    outputs.check_distinct();
#if WHATNEXT_FULL
    // The pictures last: a directory made for --plots is removed again if anything else fails.
    const std::string animation = prepare_pictures(*cmd, *opts);
#endif
    // With an output on standard output, the timeline goes to standard error.
    std::FILE* text = outputs.any_to_stdout() ? stderr : stdout;
    const Result result = simulate_into(in.scenario, csv_file, dat_file);
    if (events_file) events_file->stream() << events_json(result, in.scenario, in.source);
    outputs.commit_all();
    if (opts->quiet) {
      fmt::print(text, "{}\n", outcome_sentence(result));
    } else {
      fmt::print(text, "{}", timeline_text(result, in.scenario, in.source));
    }
#if WHATNEXT_FULL
    draw_pictures(*cmd, *opts, in, animation, text);
#endif
    exit_code = 0;
  });
}

}  // namespace whatnext::cli
