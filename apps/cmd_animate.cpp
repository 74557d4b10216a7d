// Placeholder until `whatnext animate` is built.
#include "cli_common.hpp"

namespace whatnext::cli {

void register_animate(CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand("animate", "(not built yet)");
  cmd->callback([&exit_code] { exit_code = 3; });
}

}  // namespace whatnext::cli
