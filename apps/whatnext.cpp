// The whatnext command: a thin layer over the library. Bad input: one line on stderr, exit code 2.
#include <cstdio>
#include <exception>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_common.hpp"

int main(int argc, char** argv) {
  CLI::App app{"whatnext: Kermit's What-Happens-Next machine, simulated event by event"};
  app.require_subcommand(1);
  int exit_code = 0;
  whatnext::cli::register_run(app, exit_code);
  whatnext::cli::register_plot(app, exit_code);
  whatnext::cli::register_animate(app, exit_code);
  whatnext::cli::register_sweep(app, exit_code);
  whatnext::cli::register_optimize(app, exit_code);
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    if (argc == 1) {
      fmt::print(stderr, "whatnext: error: say what to do: run, plot, animate, sweep or optimize (see whatnext --help)\n");
    } else {
      fmt::print(stderr, "whatnext: error: {}\n", e.what());
    }
    return 2;
  } catch (const whatnext::InputError& e) {
    fmt::print(stderr, "whatnext: error: {}\n", e.what());
    return 2;
  } catch (const std::exception& e) {
    fmt::print(stderr, "whatnext: error: {}\n", e.what());
    return 2;
  }
  return exit_code;
}
