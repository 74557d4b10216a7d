// `whatnext run`: one machine, its timeline on stdout and the requested files.
#include <cstdio>
#include <memory>
#include <optional>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/output.hpp"
#include "whatnext/viz/animation.hpp"
#include "whatnext/viz/plots.hpp"

namespace whatnext::cli {

namespace {
struct RunOptions {
  InputOptions input;
  std::string events, csv, dat;
  std::string plots, animate;  // pictures (whatnext plot / animate with their defaults)
  bool quiet = false;
};
}  // namespace

void register_run(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<RunOptions>();
  CLI::App* cmd = app.add_subcommand("run", "simulate one machine and print its timeline");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--events", opts->events, "write the events as JSON to this file");
  cmd->add_option("--csv", opts->csv, "write the sampled state as CSV to this file");
  cmd->add_option("--dat", opts->dat, "write the paper's whatnext.dat layout to this file");
  cmd->add_option("--plots", opts->plots, "also draw the paper's figures into this directory");
  cmd->add_option("--animate", opts->animate, "also write an animation to this .gif (or .mp4)");
  cmd->add_flag("-q,--quiet", opts->quiet, "print only the outcome line");
  cmd->callback([opts, &exit_code] {
    const LoadedInput in = load_input(opts->input);
    if (!opts->plots.empty()) viz::prepare_output_dir(opts->plots, "--plots");
    if (!opts->animate.empty()) viz::check_animation_target(opts->animate, "--animate");
    // Open every output first so that a bad path fails before any work; files appear only when done.
    std::optional<AtomicFile> csv_file, dat_file, events_file;
    Fanout fan;
    std::unique_ptr<CsvWriter> csv;
    std::unique_ptr<DatWriter> dat;
    if (!opts->csv.empty()) {
      csv_file.emplace(opts->csv);
      csv = std::make_unique<CsvWriter>(csv_file->stream());
      fan.add(csv.get());
    }
    if (!opts->dat.empty()) {
      dat_file.emplace(opts->dat);
      dat = std::make_unique<DatWriter>(dat_file->stream());
      fan.add(dat.get());
    }
    if (!opts->events.empty()) events_file.emplace(opts->events);
    const Result result = simulate(in.scenario, fan.empty() ? nullptr : &fan);
    if (events_file) events_file->stream() << events_json(result, in.scenario, in.source);
    for (auto* f : {&csv_file, &dat_file, &events_file}) {
      if (*f) (*f)->commit();
    }
    if (opts->quiet) {
      fmt::print("{}\n", outcome_sentence(result));
    } else {
      fmt::print("{}", timeline_text(result, in.scenario, in.source));
    }
    if (!opts->plots.empty() || !opts->animate.empty()) {
      const viz::Recording rec = viz::record(in.scenario);
      if (!opts->plots.empty()) {
        viz::FigureOptions fig;
        fig.title = in.source;
        const auto files = viz::write_run_figures(rec, opts->plots, fig);
        if (!opts->quiet) fmt::print("Plots: {} files in {}\n", files.size(), opts->plots);
      }
      if (!opts->animate.empty()) {
        const int frames = viz::write_animation(rec, opts->animate, viz::AnimationOptions{}, "", "--animate");
        if (!opts->quiet) fmt::print("Animation: {} ({} frames)\n", opts->animate, frames);
      }
    }
    exit_code = 0;
  });
}

}  // namespace whatnext::cli
