// Placeholder until `whatnext optimize` is built.
#include "cli_common.hpp"

namespace whatnext::cli {

void register_optimize(CLI::App& app, int& exit_code) {
  CLI::App* cmd = app.add_subcommand("optimize", "(not built yet)");
  cmd->callback([&exit_code] { exit_code = 3; });
}

}  // namespace whatnext::cli
