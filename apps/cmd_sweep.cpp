// `whatnext sweep`: many machines over a grid or a Latin hypercube, one CSV row each, or a Monte
// Carlo around one machine. The sweep itself is explore::SweepJob; this file turns the command
// line into it and its result into the command's words.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <tuple>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/explore/pool.hpp"
#include "whatnext/explore/sweep_job.hpp"
#include "whatnext/output.hpp"
#if WHATNEXT_FULL
#include "whatnext/viz/heatmap.hpp"
#include "whatnext/viz/histogram.hpp"
#endif

namespace whatnext::cli {

namespace {

struct SweepOptions {
  InputOptions input;
  std::vector<std::string> vary, spread;
  std::string spread_dist = "normal", histogram;
  std::int64_t samples = 0;
  std::uint64_t seed = 1;
  int threads = 0;
  double accuracy = explore::kDefaultAccuracy;
  std::string out, heatmap, heatmap_value = "lid_open";
  bool force_large = false;
  bool resume = false;
};

// Sweeps bigger than this need --force-large: every row is kept in memory until the CSV is
// written (a few hundred bytes each), and the CSV takes about as much again.
constexpr std::int64_t kLargeSweep = 1'000'000;
constexpr double kSweepRowBytes = 600.0;

// An interrupt that landed before the sweep could stop (hold_early_interrupts).
std::atomic<int> early_interrupt{0};

// Interrupts stop the sweep instead of ending the process while this lives.
struct InterruptStops {
  explicit InterruptStops(const std::function<void(int)>& stop) {
    settle_interrupts();  // an interrupt already queued reaches hold_early_interrupts' handler
    set_interrupt_handler(stop);
    if (const int sig = early_interrupt.exchange(0)) stop(sig);
  }
  ~InterruptStops() { set_interrupt_handler({}); }
  InterruptStops(const InterruptStops&) = delete;
  InterruptStops& operator=(const InterruptStops&) = delete;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

void check_png(const std::string& option, const std::string& name, const char* what) {
  if (!ends_with(name, ".png") && !ends_with(name, ".PNG")) {
    throw InputError(
        fmt::format("{} {}: the {} is a PNG; give a name ending in .png", option, printable(name, 96), what));
  }
}

// "[#######.......]  45%  4500/10000 machines, 2 s left" on one terminal line.
class ProgressBar {
 public:
  explicit ProgressBar(bool enabled) : enabled_(enabled), start_(std::chrono::steady_clock::now()) {}
  void update(std::int64_t done, std::int64_t total) {
    if (!enabled_ || total <= 0) return;
    const double elapsed = std::chrono::duration<double>(std::chrono::steady_clock::now() - start_).count();
    const double frac = static_cast<double>(done) / static_cast<double>(total);
    constexpr int kWidth = 30;
    const int filled = static_cast<int>(frac * kWidth);
    std::string left = "?";
    if (done > 0)
      left = fmt::format("{:.0f} s", elapsed / static_cast<double>(done) * static_cast<double>(total - done));
    fmt::print(stderr, "\r[{}{}] {:3.0f}%  {}/{} machines, {} left   ", std::string(filled, '#'),
               std::string(kWidth - filled, '.'), 100.0 * frac, done, total, left);
    std::fflush(stderr);
    shown_ = true;
  }
  void finish() {
    if (shown_) fmt::print(stderr, "\n");
  }

 private:
  bool enabled_;
  bool shown_ = false;
  std::chrono::steady_clock::time_point start_;
};

// A grid or Latin hypercube sweep whose --out is a regular file (new or existing) writes it
// through a SweepFile, resumable; standard output, /dev/null and pipes are written through in place
// (an AtomicFile, which also gives the message for a path that cannot be written).
bool regular_file_output(const std::string& out) {
  if (out == "-") return false;
  try {
    (void)regular_output_target(out, "--out");
    return true;
  } catch (const InputError&) {
    return false;
  }
}

void add_sweep_options(CLI::App& cmd, SweepOptions& o) {
  add_input_options(cmd, o.input);
  cmd.add_option("--vary", o.vary,
                 "KEY=A:B:N: N values of KEY from A to B (KEY=A:B with --samples); repeat for more keys")
      ->take_all()
      ->allow_extra_args(false);
  cmd.add_option(
         "--spread", o.spread,
         "KEY=±X (or KEY=+-X): a Monte Carlo around the machine, KEY off by a random amount of spread "
         "X in its unit; repeat for more keys")
      ->take_all()
      ->allow_extra_args(false);
  cmd.add_option("--spread-dist", o.spread_dist,
                 "normal (X is the standard deviation, the default) or uniform (X is the half-width)");
  cmd.add_option("--histogram", o.histogram,
                 "with --spread: a PNG histogram of the lid's opening time (the radio's, if it is on)");
  cmd.add_option("--samples", o.samples,
                 "a Latin hypercube of this many machines instead of the grid; with --spread, the machines "
                 "drawn (default 1000)")
      ->transform(number_text(true, 1, static_cast<double>(explore::kMaxMachines)));
  cmd.add_option("--seed", o.seed,
                 "seed of the Latin hypercube or the --spread draws (same seed, same machines)")
      ->transform(seed_text());
  cmd.add_option("--threads", o.threads, "worker threads (default: all cores)")
      ->transform(number_text(true, 1, 1024));
  cmd.add_option("--accuracy", o.accuracy,
                 fmt::format("event times to this many seconds (default {:g}); sets the integrator's "
                             "tolerance unless run.tolerance is given",
                             explore::kDefaultAccuracy));
  cmd.add_option("--out", o.out, "CSV file to write, one row per machine ('-': standard output)");
  cmd.add_option("--heatmap", o.heatmap, "also draw a PNG heat map (needs exactly two --vary keys)");
  cmd.add_option("--heatmap-value", o.heatmap_value,
                 "value drawn: an event name (its first time, e.g. lid_open), outcome_t, final_r or "
                 "final_phi_l_deg");
  cmd.add_flag("--resume", o.resume,
               "continue the sweep an interrupted run left in --out (its .part file or the CSV itself); the "
               "file ends the same as an uninterrupted run's");
  cmd.add_flag("--force-large", o.force_large,
               fmt::format("run sweeps of more than {} machines", kLargeSweep));
}

// Which options go together: a grid (--vary) or a Monte Carlo (--spread), and what each takes.
void check_option_mix(const CLI::App& cmd, const SweepOptions& o) {
  const bool monte_carlo = !o.spread.empty();
  if (o.vary.empty() && !monte_carlo)
    throw InputError("sweep: give --vary KEY=A:B:N for a grid (or --spread KEY=±X for a Monte Carlo)");
  if (!o.vary.empty() && monte_carlo)
    throw InputError("sweep: --vary and --spread do not mix: a grid, or a Monte Carlo around one machine");
  if (!monte_carlo) {
    for (const char* opt : {"--spread-dist", "--histogram"}) {
      if (given(cmd, opt))
        throw InputError(fmt::format("{}: goes with --spread KEY=±X (a Monte Carlo)", opt));
    }
    if (!given(cmd, "--out")) throw InputError("--out: give the CSV file to write ('-': standard output)");
  } else {
    for (const char* opt : {"--heatmap", "--heatmap-value", "--resume"}) {
      if (given(cmd, opt))
        throw InputError(
            fmt::format("{}: goes with a grid (--vary), not with a Monte Carlo (--spread)", opt));
    }
    if (given(cmd, "--histogram")) check_png("--histogram", o.histogram, "histogram");
  }
  if (o.resume && given(cmd, "--heatmap")) {
    throw InputError(
        "--resume: draw the heat map from the finished CSV with a sweep of its own; --resume does "
        "not take --heatmap");
  }
}

void check_large(std::int64_t n, const SweepOptions& o) {
  if (n > kLargeSweep && !o.force_large) {
    throw InputError(
        fmt::format("sweep: {} machines would hold about {:.1f} GB in memory and write as much; use fewer, "
                    "or give --force-large",
                    n, static_cast<double>(n) * kSweepRowBytes / 1e9));
  }
}

// The plan of the command line: --vary's ranges (a grid, or a Latin hypercube with --samples), or
// --spread's keys around the machine's own values (a Monte Carlo).
explore::Plan make_plan(const SweepOptions& o, const LoadedInput* in) {
  explore::Plan plan;
  plan.samples = o.samples;
  plan.seed = o.seed;
  if (!o.spread.empty()) {
    plan.spread_kind = explore::parse_spread_kind(o.spread_dist, "--spread-dist");
    if (plan.samples == 0) plan.samples = 1000;
  }
  for (const std::string& v : o.spread) {
    const explore::Spread sp = explore::parse_spread(v, "--spread");
    if (!in) continue;  // the specs checked; the values come with the machine
    const double centre = explore::base_value(in->config, sp.key, "--spread");
    plan.ranges.push_back(explore::Range{sp.key, centre, centre, 0});
    plan.spread.push_back(sp.x);
  }
  for (const std::string& v : o.vary) {
    plan.ranges.push_back(explore::parse_range(v, "--vary", plan.samples == 0));
    if (plan.samples > 0 && plan.ranges.back().n != 0) {
      throw InputError(fmt::format(
          "--vary {}: with --samples the values come from a Latin hypercube; write KEY=A:B without a count",
          printable(v)));
    }
  }
  return plan;
}

void check_heatmap(const CLI::App& cmd, const SweepOptions& o, const explore::Plan& plan,
                   const LoadedInput& in) {
  if (given(cmd, "--heatmap")) {
#if WHATNEXT_FULL
    viz::check_heatmap_plan(plan, "--heatmap");
#endif
    check_png("--heatmap", o.heatmap, "heat map");
  }
  if (!given(cmd, "--heatmap") && !given(cmd, "--heatmap-value")) return;
  explore::check_value_name(o.heatmap_value, "--heatmap-value");
  bool radio_varied = false;
  for (const explore::Range& r : plan.ranges) radio_varied = radio_varied || r.key.rfind("radio.", 0) == 0;
  if (o.heatmap_value == "radio_on" && !in.scenario.machine.radio && !radio_varied) {
    throw InputError(
        "--heatmap-value radio_on: the radio is off in this machine, so the map would be all grey (add --set "
        "radio.enabled=true)");
  }
}

// The command's files: the CSV (the job's resumable file, or an AtomicFile for standard output
// and pipes) and the pictures, every one checked before any machine runs.
struct SweepOutputs {
  Outputs outputs;
  AtomicFile *csv = nullptr, *heat = nullptr, *hist = nullptr;
  int sync_fd = -1;  // the CSV's temporary, synced as rows are written
  ~SweepOutputs() {
    if (sync_fd >= 0) ::close(sync_fd);
  }
};

void open_outputs(const CLI::App& cmd, const SweepOptions& o, explore::SweepJob& job, SweepOutputs& out) {
  if (o.resume || (o.spread.empty() && regular_file_output(o.out))) {
    const std::string target = regular_output_target(o.out, "--out");
    check_unclaimed("--out", o.out);
    job.to_file(target, o.out, "--out", o.resume, "--resume");
  } else {
    out.csv = out.outputs.add(cmd, "--out", o.out);
  }
  out.heat = out.outputs.add(cmd, "--heatmap", o.heatmap);
  out.hist = out.outputs.add(cmd, "--histogram", o.histogram);
  out.outputs.check_distinct();
  for (const auto& [file, option, name] :
       {std::tuple{out.hist, "--histogram", &o.histogram}, std::tuple{out.heat, "--heatmap", &o.heatmap}}) {
    if (file && file->temp_path().empty())
      throw InputError(fmt::format("{} {}: must be a regular file", option, printable(*name, 96)));
  }
  if (!out.csv) return;
  // Rows are made durable as they go (about once a second), so that a kill or a power cut
  // leaves what was written.
  if (!out.csv->to_stdout() && !out.csv->temp_path().empty())
    out.sync_fd = ::open(out.csv->temp_path().c_str(), O_RDONLY | O_CLOEXEC);
  job.to_stream(out.csv->stream(), [&out] {
    out.csv->flush();
    if (out.sync_fd >= 0) (void)::fdatasync(out.sync_fd);
  });
}

// A Monte Carlo's summary: how often the machine works, and when; the histogram of that time.
std::string monte_carlo_report(const SweepOptions& o, const LoadedInput& in, const explore::Plan& plan,
                               const explore::SweepResult& result, AtomicFile* hist) {
  const bool radio = in.scenario.machine.radio;
  const std::string value = radio ? "radio_on" : "lid_open";
  std::vector<double> centre;
  for (const explore::Range& r : plan.ranges) centre.push_back(r.lo);
  const explore::Outcome own = explore::evaluate(in.config, plan.keys(), centre.data(), o.accuracy);
  const std::size_t keys = plan.ranges.size();
  std::string summary =
      fmt::format("monte carlo: {} machines around {}, {} key{} off by {} spreads (seed {})\n",
                  result.completed, in.source, keys, keys == 1 ? "" : "s", o.spread_dist, o.seed);
  summary += fmt::format("  the machine as given: {}\n",
                         own.valid ? fmt::format("{} at {:.4f} s", to_string(own.outcome), own.outcome_t)
                                   : fmt::format("{} ({})", own.failed ? "failed" : "invalid", own.error));
  explore::Distribution dist;
  const auto line = [&](const std::string& name, const char* what) {
    const explore::Distribution d = explore::distribution(result, name);
    const double n = static_cast<double>(std::max<std::int64_t>(1, result.completed));
    summary += fmt::format("  {} in {} of {} machines ({:.1f} %)", what, d.happened, result.completed,
                           100.0 * static_cast<double>(d.happened) / n);
    if (d.happened > 0) {
      summary += fmt::format(
          "; {} [s]: 5 % {:.4f}, 25 % {:.4f}, median {:.4f}, 75 % {:.4f}, 95 % {:.4f} (min {:.4f}, max "
          "{:.4f})",
          name, d.quantile(0.05), d.quantile(0.25), d.quantile(0.5), d.quantile(0.75), d.quantile(0.95),
          d.values.front(), d.values.back());
    }
    summary += "\n";
    dist = d;
  };
  line("lid_open", "the lid opens");
  if (radio) line("radio_on", "the radio turns on");
  if (result.invalid + result.failed > 0) {
    summary += fmt::format("  {} machines with invalid inputs, {} failed runs (counted as not working)\n",
                           result.invalid, result.failed);
  }
#if WHATNEXT_FULL
  if (hist) {
    viz::HistogramText t;
    t.title = fmt::format("{}: {} machines around {}", value, result.completed, printable(in.source, 60));
    t.x_label = value + " [s]";
    const std::int64_t never = result.completed - dist.happened;
    t.note =
        fmt::format("{} of {} machines{}; red line: the machine as given", dist.happened, result.completed,
                    never > 0 ? fmt::format(" ({} invalid or without {})", never, value) : std::string());
    viz::draw_histogram(hist->temp_path(), dist.values, explore::value_of(own, value), t);
  }
#else
  (void)hist;
#endif
  return summary;
}

// What the command says when the sweep ended: where its rows went.
std::string done_line(const SweepOptions& o, const explore::SweepJob& job, const explore::SweepResult& result,
                      std::int64_t machines, const SweepOutputs& out) {
  if (!o.spread.empty()) {
    if (!out.csv && !out.hist) return {};
    return fmt::format("written to {}\n", out.csv && out.hist ? fmt::format("{} and {}", printable(o.out, 96),
                                                                            printable(o.histogram, 96))
                                          : out.csv           ? printable(o.out, 96)
                                                              : printable(o.histogram, 96));
  }
  const explore::Resumable& kept = job.kept();
  return fmt::format("sweep: {} machines ({} with invalid inputs, {} failed runs) written to {}{}{}\n",
                     machines, result.invalid + kept.invalid, result.failed + kept.failed,
                     printable(o.out, 96),
                     out.heat ? fmt::format(", heat map {}", printable(o.heatmap, 96)) : "",
                     o.resume ? fmt::format(" ({} rows kept from the interrupted sweep)", kept.kept) : "");
}

int run_sweep(const CLI::App& cmd, const SweepOptions& o) {
  if (const int sig = early_interrupt.load()) return 128 + sig;  // before anything was read or written
  check_leftovers(cmd);
  explore::check_accuracy(o.accuracy, "--accuracy");
  // Everything about the input is checked before any machine runs or any file appears.
  check_option_mix(cmd, o);
  check_large(make_plan(o, nullptr).samples, o);  // a Latin hypercube's points are made up front
  const LoadedInput in = load_input(o.input);
  const explore::Plan plan = make_plan(o, &in);
  const explore::Machines machines(plan);
  check_large(machines.size(), o);
  check_heatmap(cmd, o, plan, in);
  explore::SweepJob job(in.config, machines, o.accuracy);
  SweepOutputs out;
  open_outputs(cmd, o, job, out);
  std::FILE* text_out = out.outputs.any_to_stdout() ? stderr : stdout;
  job.start();  // every output checked: only now is the .part file cut or made

  // An interrupt (Ctrl-C, SIGTERM, SIGHUP) stops the workers; the rows done so far are written.
  // It stays caught until the files are in place: a second one must not leave a .part file.
  std::atomic<int> signal{0};
  const InterruptStops guard([&job, &signal](int sig) {
    signal.store(sig);
    job.stop();
  });
  ProgressBar bar(isatty(STDERR_FILENO) != 0);
  explore::JobSettings settings;
  settings.threads = o.threads > 0 ? o.threads : explore::all_cores();
  settings.progress = [&bar](std::int64_t done, std::int64_t total) { bar.update(done, total); };
  settings.keep_rows = out.heat != nullptr || !o.spread.empty();  // the heat map and the summary read them
  const explore::SweepResult result = job.run(settings);
  bar.finish();
  const std::string summary = o.spread.empty() ? "" : monte_carlo_report(o, in, plan, result, out.hist);
#if WHATNEXT_FULL
  if (out.heat) viz::draw_heatmap(out.heat->temp_path(), machines, result, o.heatmap_value);
#endif
  job.sync();  // every file written before any is renamed: all appear, or none
  out.outputs.commit_all();
  job.commit();
  if (result.interrupted) {
    fmt::print(stderr, "whatnext: sweep interrupted: {} of {} machines written to {}\n", result.completed,
               machines.size(), printable(o.out, 96));
    return 128 + (signal.load() > 0 ? signal.load() : SIGINT);
  }
  fmt::print(text_out, "{}{}", summary, done_line(o, job, result, machines.size(), out));
  return 0;
}

}  // namespace

void hold_early_interrupts() {
  set_interrupt_handler([](int sig) { early_interrupt.store(sig); });
}

void register_sweep(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<SweepOptions>();
  CLI::App* cmd =
      app.add_subcommand("sweep", "run many machines over a grid of input values, one CSV row each");
  add_sweep_options(*cmd, *opts);
  cmd->callback([opts, cmd, &exit_code] {
#if !WHATNEXT_FULL
    if (given(*cmd, "--heatmap") || given(*cmd, "--histogram")) hand_over_to_full();
#endif
    exit_code = run_sweep(*cmd, *opts);
  });
}

}  // namespace whatnext::cli
