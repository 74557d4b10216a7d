// The whatnext command: a thin layer over the library. Exit codes (docs/inputs.md): 0 done, 1 an
// output could not be written or nothing was found, 2 bad input (one line on stderr, no file
// written), 3 a run failed (no file written); an interrupted command ends by its signal, an
// interrupted sweep with 128 + the signal's number.
#include <algorithm>
#include <cerrno>
#include <cstring>
#include <cstdio>
#include <exception>
#include <new>
#include <sstream>
#include <string>
#include <string_view>
#include <csignal>
#include <pthread.h>
#include <system_error>
#include <vector>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/simulate.hpp"

namespace {

using namespace whatnext;

void print_error(const std::string& message) {
  // fputs, not fmt::print, which throws when stderr is closed (whatnext ... 2>&- aborted).
  std::fputs(fmt::format("whatnext: error: {}\n", printable(message, 400)).c_str(), stderr);
}

// Standard output is buffered: a failed write (a full disk, /dev/full) shows when it is flushed, or
// as fmt's exception mid-way. Either is exit code 1 with one line, never a truncated success.
int stdout_failed(int err) {
  print_error(fmt::format("standard output: writing failed: {}", std::strerror(err != 0 ? err : EIO)));
  return 1;
}

// err: the errno of what wrote last, in case its failure set stdout's error indicator already.
int finish_stdout(int code, int err = 0) {
  errno = 0;
  if (std::fflush(stdout) != 0 || std::ferror(stdout))
    return code == 0 ? stdout_failed(errno != 0 ? errno : err) : code;
  return code;
}

// CLI11's --help and --version, written through std::cout (on stdout's buffer).
int finish_stdout(CLI::App& app, const CLI::Error& e) {
  errno = 0;
  const int code = app.exit(e);
  return finish_stdout(code, errno);
}

// `whatnext examples [N]`: the shipped examples, or one of them as TOML to copy.
void register_examples(CLI::App& app) {
  auto n = std::make_shared<std::string>();
  CLI::App* cmd =
      app.add_subcommand("examples", "list the shipped examples, or print example N (1-4, konstanz) as TOML");
  cmd->add_option("N", *n, "print this example's TOML (to copy and change)");
  cmd->callback([n, cmd] {
    cli::check_leftovers(*cmd);
    auto toml_of = [](const std::string& id) {
      return id.size() == 1 && id[0] >= '1' && id[0] <= '4' ? example_toml(id[0] - '0')
                                                            : example_toml(std::string_view(id));
    };
    if (!n->empty()) {
      const std::string_view text = toml_of(*n);
      if (text.empty()) {
        throw InputError(fmt::format(
            "examples: the examples are 1 to 4 (the paper's) and konstanz (given '{}')", printable(*n)));
      }
      fmt::print("{}", text);
      return;
    }
    std::vector<std::string> ids{"1", "2", "3", "4"};
    for (std::string_view name : kNamedExamples) ids.emplace_back(name);
    for (const std::string& id : ids) {
      // The first sentence of each example's opening comment says what it is.
      std::istringstream toml{std::string(toml_of(id))};
      std::string line, text;
      while (std::getline(toml, line) && line.rfind("# ", 0) == 0) {
        if (!text.empty()) text += ' ';
        text += line.substr(2);
      }
      std::size_t end = text.find(". ");
      while (end != std::string::npos && end >= 3 && text.compare(end - 3, 3, "Fig") == 0)
        end = text.find(". ", end + 1);
      text = text.substr(0, end);
      if (text.size() > 100 && text.find("; ") != std::string::npos) text = text.substr(0, text.find("; "));
      fmt::print("{}  {}\n", id, text);
    }
    fmt::print("Run one with `whatnext run --example N`; `whatnext examples N` prints it as TOML.\n");
  });
}

// `whatnext keys`: every input key with its unit, default and meaning.
void register_keys(CLI::App& app) {
  CLI::App* cmd = app.add_subcommand("keys", "list every input key with its unit, default and meaning");
  cmd->callback([cmd] {
    cli::check_leftovers(*cmd);
    std::size_t wk = 3, wu = 4, wd = 7;
    for (const KeySpec& k : known_keys()) {
      wk = std::max(wk, k.key.size());
      wu = std::max(wu, k.unit.size());
      wd = std::max(wd, k.default_text.size());
    }
    fmt::print("{:<{}}  {:<{}}  {:<{}}  {}\n", "key", wk, "unit", wu, "default", wd, "meaning");
    for (const KeySpec& k : known_keys()) {
      fmt::print("{:<{}}  {:<{}}  {:<{}}  {}\n", k.key, wk, k.unit, wu, k.default_text, wd, k.help);
    }
    fmt::print(
        "Set them in a TOML file ([section] then name = value) or with --set section.name=value; "
        "docs/inputs.md has the rules and limits.\n");
  });
}

// The commands' names, in the order `whatnext help` lists them (kCommands, below).
std::vector<std::string> command_names();

std::string joined(const std::vector<std::string>& words) {
  std::string out;
  for (const std::string& w : words) {
    if (!out.empty()) out += ", ";
    out += w;
  }
  return out;
}

// `whatnext help [COMMAND]`.
void register_help(CLI::App& app) {
  auto topic = std::make_shared<std::string>();
  CLI::App* cmd = app.add_subcommand("help", "show the commands, or one command's options");
  cmd->add_option("COMMAND", *topic, "the command to explain");
  cmd->callback([topic, cmd, &app] {
    cli::check_leftovers(*cmd);
    // Straight to the formatter: App::help() would describe the command being run, `help` itself.
    if (topic->empty()) {
      fmt::print("{}", app.get_formatter()->make_help(&app, app.get_name(), CLI::AppFormatMode::Normal));
      return;
    }
    for (const CLI::App* sub : app.get_subcommands([](const CLI::App*) { return true; })) {
      if (sub->get_name() == *topic) {
        fmt::print("{}", sub->get_formatter()->make_help(sub, app.get_name() + " " + sub->get_name(),
                                                         CLI::AppFormatMode::Normal));
        return;
      }
    }
    const std::string near = nearest_word(*topic, command_names());
    throw InputError(fmt::format("help: unknown command '{}'{}; the commands are {}", printable(*topic),
                                 near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                                 joined(command_names())));
  });
}

// The commands, in the order `whatnext help` lists them.
struct Command {
  const char* name;
  void (*add)(CLI::App& app, int& exit_code);
};
constexpr Command kCommands[] = {
    {"run", whatnext::cli::register_run},
    {"plot", whatnext::cli::register_plot},
    {"animate", whatnext::cli::register_animate},
    {"sweep", whatnext::cli::register_sweep},
    {"optimize", whatnext::cli::register_optimize},
    {"examples", [](CLI::App& app, int&) { register_examples(app); }},
    {"keys", [](CLI::App& app, int&) { register_keys(app); }},
    {"help", [](CLI::App& app, int&) { register_help(app); }},
};

std::vector<std::string> command_names() {
  std::vector<std::string> names;
  for (const Command& c : kCommands) names.emplace_back(c.name);
  return names;
}

// Interrupts are caught first thing: one that lands while the command line is read ends the
// command as any later one does (a sweep with 128 + its number), never half-way by default.
void catch_interrupts(int argc, char** argv) {
  whatnext::install_interrupt_cleanup();
  if (argc > 1 && std::string_view(argv[1]) == "sweep") whatnext::cli::hold_early_interrupts();
  // Started with them blocked (a parent's mask is inherited), one pending lands now, handled.
  sigset_t interrupts;
  sigemptyset(&interrupts);
  for (int sig : {SIGINT, SIGTERM, SIGHUP}) sigaddset(&interrupts, sig);
  pthread_sigmask(SIG_UNBLOCK, &interrupts, nullptr);
}

// A command line that names its command needs that command's options only. Making every
// command's (CLI11's options, their names and checks) was three quarters of a command's start,
// about 0.2 ms; `help` describes them all, and anything else is told about them all.
void add_commands(CLI::App& app, int argc, char** argv, int& exit_code) {
  const Command* named = nullptr;
  for (const Command& c : kCommands) {
    if (argc > 1 && std::string_view(argv[1]) == c.name && std::string_view(c.name) != "help") named = &c;
  }
  for (const Command& c : kCommands) {
    if (!named || &c == named) c.add(app, exit_code);
  }
}

// The line for a command line CLI11 could not read: a mistyped option rather than a missing one,
// and an unknown option before the command with a suggestion.
std::string parse_error_message(const CLI::App& app, const CLI::ParseError& e, const std::string& first) {
  std::string message = e.what();
  // A missing required option is often a mistyped one: say that instead, with a suggestion.
  for (const CLI::App* sub : app.get_subcommands()) {
    try {
      whatnext::cli::check_leftovers(*sub);
    } catch (const whatnext::InputError& leftover) {
      message = leftover.what();
    }
  }
  if (first[0] == '-' && first != "--help" && first != "-h" && first != "--version") {
    const std::string near = nearest_word(first.substr(0, first.find('=')), {"--help", "--version"});
    message =
        fmt::format("unknown option '{}' before the command{}; say what to do: {}", first,
                    near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near), joined(command_names()));
  }
  return message;
}

// The command run, and what each failure means as an exit code (the header's list).
int run_command(CLI::App& app, int argc, char** argv, int& exit_code) {
  const std::string first = argv[1];
  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return finish_stdout(app, e);
  } catch (const CLI::CallForAllHelp& e) {
    return finish_stdout(app, e);
  } catch (const CLI::CallForVersion& e) {
    return finish_stdout(app, e);
  } catch (const CLI::ParseError& e) {
    print_error(parse_error_message(app, e, first));
    return 2;
  } catch (const whatnext::InputError& e) {
    whatnext::cli::remove_empty_picture_dirs();
    print_error(e.what());
    return 2;
  } catch (const whatnext::SimulationError& e) {
    whatnext::cli::remove_empty_picture_dirs();
    print_error(fmt::format("the run failed: {}; no file written", e.what()));
    return 3;
  } catch (const std::bad_alloc&) {
    // std::bad_alloc's own text says nothing a user can act on.
    whatnext::cli::remove_empty_picture_dirs();
    print_error(
        "out of memory: the machine cannot hold this job (fewer machines, samples or threads, or a "
        "coarser run.output_step); no file written");
    return 1;
  } catch (const std::system_error& e) {
    whatnext::cli::remove_empty_picture_dirs();
    if (std::ferror(stdout)) return stdout_failed(e.code().value());
    print_error(e.what());
    return 1;
  } catch (const std::exception& e) {
    whatnext::cli::remove_empty_picture_dirs();
    print_error(e.what());
    return 1;
  }
  return finish_stdout(exit_code);
}

}  // namespace

int main(int argc, char** argv) {
  catch_interrupts(argc, argv);
  CLI::App app{"whatnext: Kermit's What-Happens-Next machine, simulated event by event", "whatnext"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("whatnext ") + WHATNEXT_VERSION);
  int exit_code = 0;
  add_commands(app, argc, argv, exit_code);
  const std::vector<std::string> commands = command_names();
  if (argc == 1) {
    print_error(fmt::format("say what to do: {} (see whatnext help)", joined(commands)));
    return 2;
  }
  const std::string first = argv[1];
  if (first[0] != '-' && std::find(commands.begin(), commands.end(), first) == commands.end()) {
    const std::string near = nearest_word(first, commands);
    print_error(fmt::format("unknown command '{}'{}; the commands are {}", printable(first),
                            near.empty() ? "" : fmt::format(" (did you mean '{}'?)", near),
                            joined(commands)));
    return 2;
  }
  whatnext::cli::keep_command_line(argc, argv);
  return run_command(app, argc, argv, exit_code);
}
