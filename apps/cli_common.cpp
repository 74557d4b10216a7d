#include "cli_common.hpp"

#include <fmt/format.h>

namespace whatnext::cli {

void add_input_options(CLI::App& cmd, InputOptions& opts) {
  auto* file = cmd.add_option("FILE", opts.file, "machine as TOML or the paper's whatnext.inp");
  auto* ex = cmd.add_option("--example", opts.example, "the paper's example N (1-4) instead of FILE");
  file->excludes(ex);
  cmd.add_option("--set", opts.sets, "override an input key, e.g. --set geometry.rope_length=0.9")
      ->take_all()
      ->allow_extra_args(false);
}

LoadedInput load_input(const InputOptions& opts) {
  LoadedInput in;
  if (opts.example != 0) {
    in.config = example_config(opts.example);
    in.source = fmt::format("example {}", opts.example);
  } else if (!opts.file.empty()) {
    in.config = load_config_file(opts.file);
    in.source = opts.file;
  } else {
    throw InputError("input: give a machine FILE or --example N (1-4)");
  }
  for (const std::string& s : opts.sets) apply_set(in.config, s);
  if (!opts.sets.empty()) in.source += " with --set";
  in.scenario = build_scenario(in.config);
  return in;
}

}  // namespace whatnext::cli
