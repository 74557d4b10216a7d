// `whatnext optimize`: the best machine within bounds for one outcome, written as TOML.
#include <cmath>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "cli_common.hpp"
#if WHATNEXT_FULL
#include "whatnext/explore/optimize.hpp"
#endif
#include "whatnext/output.hpp"

namespace whatnext::cli {

namespace {
struct OptimizeCliOptions {
  InputOptions input;
  std::vector<std::string> vary;
  std::string minimize, maximize, out;
  int threads = 0, grid = 0, starts = 3, max_evals = 400;
};
}  // namespace

namespace {

void add_optimize_options(CLI::App& cmd, OptimizeCliOptions& o) {
  add_input_options(cmd, o.input);
  cmd.add_option("--vary", o.vary, "KEY=A:B: search KEY between A and B; repeat for more keys")
      ->required()
      ->type_name("KEY=A:B")
      ->take_all()
      ->allow_extra_args(false);
  auto* mn = cmd.add_option("--minimize", o.minimize,
                            "value to minimise: an event name (its first time, e.g. lid_open), outcome_t, "
                            "final_r or final_phi_l_deg")
                 ->type_name("VALUE");
  auto* mx =
      cmd.add_option("--maximize", o.maximize, "value to maximise (as --minimize)")->type_name("VALUE");
  mn->excludes(mx);
  cmd.add_option("--out", o.out, "write the best machine to this TOML file ('-': standard output)")
      ->required()
      ->type_name("FILE");
  cmd.add_option("--threads", o.threads, "threads for the coarse grid (default: all cores)")
      ->transform(number_text(true, 1, 1024));
  cmd.add_option("--grid", o.grid, "coarse grid points per key (default: about 400 machines in all)")
      ->transform(number_text(true, 2, 100000));
  cmd.add_option("--starts", o.starts, "local searches from the best grid points")
      ->transform(number_text(true, 1, 100));
  cmd.add_option("--max-evals", o.max_evals, "machines per local search")
      ->transform(number_text(true, 1, 1000000));
}

#if WHATNEXT_FULL
// The search the command line asks for, checked against the machine.
explore::OptimizeOptions search_of(const OptimizeCliOptions& opts, const LoadedInput* in) {
  if (opts.minimize.empty() == opts.maximize.empty())
    throw InputError("optimize: give one of --minimize VALUE or --maximize VALUE");
  explore::OptimizeOptions o;
  o.maximize = !opts.maximize.empty();
  o.value = o.maximize ? opts.maximize : opts.minimize;
  const std::string option = o.maximize ? "--maximize" : "--minimize";
  explore::check_value_name(o.value, option);
  for (const std::string& v : opts.vary) {
    o.bounds.push_back(explore::parse_range(v, "--vary", false));
    if (o.bounds.back().n != 0) {
      throw InputError(
          fmt::format("--vary {}: optimize searches the whole range; write KEY=A:B without a count "
                      "(--grid sets the coarse grid)",
                      printable(v)));
    }
  }
  o.threads =
      opts.threads > 0 ? opts.threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  o.grid_points = opts.grid;
  o.starts = opts.starts;
  o.max_evaluations = opts.max_evals;
  if (!in) return o;
  bool radio_varied = false;
  for (const explore::Range& r : o.bounds) radio_varied = radio_varied || r.key.rfind("radio.", 0) == 0;
  if (o.value == "radio_on" && !in->scenario.machine.radio && !radio_varied) {
    throw InputError(
        fmt::format("{} radio_on: the radio is off in this machine, so it never switches on "
                    "(add --set radio.enabled=true)",
                    option));
  }
  return o;
}

// The file is only useful if it is the optimum: run it again from its own text, as the search
// ran it (at the sweep's accuracy where the input gave no run.tolerance; to_toml writes one).
void check_written(const std::string& toml, const Config& best, const Scenario& sc,
                   const explore::OptimizeOptions& o, const explore::OptimizeResult& r,
                   const std::string& out) {
  Config written = parse_toml(toml, out);
  if (!best.has("run.tolerance")) written.values.erase("run.tolerance");
  const double v = explore::value_of(explore::evaluate(written, {}, nullptr), o.value);
  const auto same = [&](double x) { return std::fabs(x - r.value) <= 1e-9 * (1.0 + std::fabs(r.value)); };
  if (!same(v)) {
    fmt::print(stderr,
               "whatnext: warning: {} gives {} = {}, not {}: to_toml() does not write every input key "
               "that was set\n",
               printable(out, 96), o.value, shortest(v), shortest(r.value));
  } else if (!best.has("run.tolerance")) {
    // At the file's own tolerance: an optimum where an event is grazed (a lid that just reaches
    // the vertical, or just fails to) changes with the last digits.
    const double own = explore::value_of(explore::evaluate(parse_toml(toml, out), {}, nullptr), o.value);
    if (!same(own)) {
      fmt::print(stderr,
                 "whatnext: warning: {} run at its own run.tolerance = {} gives {} = {}, not {}: the optimum "
                 "lies on a knife edge of the machine (an event that only just happens or not); give "
                 "run.tolerance to search at it\n",
                 printable(out, 96), shortest(sc.run.tolerance), o.value, shortest(own), shortest(r.value));
    }
  }
}

int run_optimize(const CLI::App& cmd, const OptimizeCliOptions& opts) {
  check_leftovers(cmd);
  (void)search_of(opts, nullptr);  // the command line checked before the machine is read
  const LoadedInput in = load_input(opts.input);
  const explore::OptimizeOptions o = search_of(opts, &in);
  Outputs outputs;
  AtomicFile* out = outputs.add(cmd, "--out", opts.out);  // a bad path fails before the search
  std::FILE* text = outputs.any_to_stdout() ? stderr : stdout;
  const explore::OptimizeResult r = explore::optimize(in.config, o);
  if (!r.found) {
    fmt::print(
        stderr,
        "whatnext: optimize: {} never happens within the bounds ({} machines tried); no file written\n",
        o.value, r.evaluations);
    return 1;
  }
  Config best = in.config;
  std::string values;
  for (std::size_t k = 0; k < o.bounds.size(); ++k) {
    set_number(best, o.bounds[k].key, r.best[k]);
    values += fmt::format("{}{} = {}", k ? ", " : "", o.bounds[k].key, shortest(r.best[k]));
  }
  const Scenario sc = build_scenario(best);
  if (r.at_time_limit) {
    fmt::print(stderr,
               "whatnext: optimize: {} = {} s is the end of the run (run.t_max = {} s): within the "
               "bounds it can be put off as long as the run lasts, so there is no {}; no file written\n",
               o.value, shortest(r.value), shortest(sc.run.t_max), o.maximize ? "maximum" : "minimum");
    return 1;
  }
  const std::string toml = to_toml(sc, &best);  // the hinge in the form the input gave it
  out->stream() << fmt::format("# whatnext optimize: {} {} over {} ({} machines): {}; {} = {}\n",
                               o.maximize ? "maximise" : "minimise", o.value, in.source, r.evaluations,
                               values, o.value, shortest(r.value))
                << toml;
  outputs.commit_all();
  check_written(toml, best, sc, o, r, opts.out);
  fmt::print(text, "best: {}\n{} = {}; outcome {} at {:.6f} s ({} machines tried)\nwritten to {}\n", values,
             o.value, shortest(r.value), to_string(r.outcome.outcome), r.outcome.outcome_t, r.evaluations,
             printable(opts.out, 96));
  return 0;
}
#endif

}  // namespace

void register_optimize(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<OptimizeCliOptions>();
  CLI::App* cmd =
      app.add_subcommand("optimize", "find the machine within bounds that minimises or maximises an outcome");
  add_optimize_options(*cmd, *opts);
#if !WHATNEXT_FULL
  (void)exit_code;
  cmd->callback([opts] { hand_over_to_full(); });  // opts: the options write into it
#else
  cmd->callback([opts, cmd, &exit_code] { exit_code = run_optimize(*cmd, *opts); });
#endif
}

}  // namespace whatnext::cli
