// Placeholder until `whatnext sweep` is built.
#include "cli_common.hpp"

namespace whatnext::cli {

void register_sweep(CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand("sweep", "(not built yet)");
  cmd->callback([&exit_code] { exit_code = 3; });
}

}  // namespace whatnext::cli
