// Pieces shared by the subcommands of the whatnext command: how a run's input is chosen.
#pragma once

#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "whatnext/config.hpp"

namespace whatnext::cli {

struct InputOptions {
  std::string file;
  int example = 0;
  std::vector<std::string> sets;
};

// FILE | --example N, and any number of --set KEY=VALUE.
void add_input_options(CLI::App& cmd, InputOptions& opts);

struct LoadedInput {
  Config config;  // as read, with the --set overrides applied
  Scenario scenario;
  std::string source;  // for messages and the timeline
};
// Throws InputError for anything wrong with the input.
LoadedInput load_input(const InputOptions& opts);

// Each subcommand registers itself and sets `exit_code` when it runs.
void register_run(CLI::App& app, int& exit_code);       // cmd_run.cpp
void register_plot(CLI::App& app, int& exit_code);      // cmd_plot.cpp
void register_animate(CLI::App& app, int& exit_code);   // cmd_animate.cpp
void register_sweep(CLI::App& app, int& exit_code);     // cmd_sweep.cpp
void register_optimize(CLI::App& app, int& exit_code);  // cmd_optimize.cpp

}  // namespace whatnext::cli
