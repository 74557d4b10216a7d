// `whatnext sweep`: many machines over a grid or a Latin hypercube, one CSV row each.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "cli_common.hpp"
#if WHATNEXT_FULL
#include "whatnext/explore/heatmap.hpp"
#endif
#include "whatnext/explore/sweep.hpp"
#include "whatnext/output.hpp"

namespace whatnext::cli {

namespace {

struct SweepOptions {
  InputOptions input;
  std::vector<std::string> vary;
  std::int64_t samples = 0;
  std::uint64_t seed = 1;
  int threads = 0;
  double accuracy = explore::kDefaultAccuracy;
  std::string out, heatmap, heatmap_value = "lid_open";
  bool force_large = false;
};

// Sweeps bigger than this need --force-large: every row is kept in memory until the CSV is
// written (a few hundred bytes each), and the CSV takes about as much again.
constexpr std::int64_t kLargeSweep = 1'000'000;
constexpr double kSweepRowBytes = 600.0;

// Interrupts stop the sweep instead of ending the process while this lives.
struct InterruptStops {
  explicit InterruptStops(std::function<void(int)> stop) { set_interrupt_handler(std::move(stop)); }
  ~InterruptStops() { set_interrupt_handler({}); }
  InterruptStops(const InterruptStops&) = delete;
  InterruptStops& operator=(const InterruptStops&) = delete;
};

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
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
    if (done > 0) left = fmt::format("{:.0f} s", elapsed / static_cast<double>(done) * static_cast<double>(total - done));
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

}  // namespace

void register_sweep(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<SweepOptions>();
  CLI::App* cmd = app.add_subcommand("sweep", "run many machines over a grid of input values, one CSV row each");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--vary", opts->vary,
                  "KEY=A:B:N: N values of KEY from A to B (KEY=A:B with --samples); repeat for more keys")
      ->required()
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--samples", opts->samples, "a Latin hypercube of this many machines instead of the grid")
      ->check(CLI::Range(std::int64_t{1}, explore::kMaxMachines));
  cmd->add_option("--seed", opts->seed, "seed of the Latin hypercube (same seed, same machines)");
  cmd->add_option("--threads", opts->threads, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--accuracy", opts->accuracy,
                  fmt::format("event times to this many seconds (default {:g}); sets the integrator's "
                              "tolerance unless run.tolerance is given",
                              explore::kDefaultAccuracy));
  cmd->add_option("--out", opts->out, "CSV file to write, one row per machine ('-': standard output)")->required();
  cmd->add_option("--heatmap", opts->heatmap, "also draw a PNG heat map (needs exactly two --vary keys)");
  cmd->add_option("--heatmap-value", opts->heatmap_value,
                  "value drawn: an event name (its first time, e.g. lid_open), outcome_t, final_r or "
                  "final_phi_l_deg");
  cmd->add_flag("--force-large", opts->force_large,
                fmt::format("run sweeps of more than {} machines", kLargeSweep));
  cmd->callback([opts, cmd, &exit_code] {
#if !WHATNEXT_FULL
    if (given(*cmd, "--heatmap")) hand_over_to_full();
#endif
    check_leftovers(*cmd);
    explore::check_accuracy(opts->accuracy, "--accuracy");
    // Everything about the input is checked before any machine runs or any file appears.
    explore::Plan plan;
    plan.samples = opts->samples;
    plan.seed = opts->seed;
    for (const std::string& v : opts->vary) {
      plan.ranges.push_back(explore::parse_range(v, "--vary", plan.samples == 0));
      if (plan.samples > 0 && plan.ranges.back().n != 0) {
        throw InputError(fmt::format("--vary {}: with --samples the values come from a Latin hypercube; write "
                                     "KEY=A:B without a count", printable(v)));
      }
    }
    // A Latin hypercube's points are made up front: its size is checked before.
    const auto check_large = [&](std::int64_t n) {
      if (n > kLargeSweep && !opts->force_large) {
        throw InputError(fmt::format("sweep: {} machines would hold about {:.1f} GB in memory and write as much; "
                                     "use fewer, or give --force-large", n,
                                     static_cast<double>(n) * kSweepRowBytes / 1e9));
      }
    };
    check_large(plan.samples);
    const explore::Machines machines(plan);
    check_large(machines.size());
    const LoadedInput in = load_input(opts->input);
    if (given(*cmd, "--heatmap")) {
#if WHATNEXT_FULL
      explore::check_heatmap_plan(plan, "--heatmap");
#endif
      if (!ends_with(opts->heatmap, ".png") && !ends_with(opts->heatmap, ".PNG")) {
        throw InputError(fmt::format("--heatmap {}: the heat map is a PNG; give a name ending in .png",
                                     printable(opts->heatmap, 96)));
      }
    }
    if (given(*cmd, "--heatmap") || given(*cmd, "--heatmap-value")) {
      explore::check_value_name(opts->heatmap_value, "--heatmap-value");
      bool radio_varied = false;
      for (const explore::Range& r : plan.ranges) radio_varied = radio_varied || r.key.rfind("radio.", 0) == 0;
      if (opts->heatmap_value == "radio_on" && !in.scenario.machine.radio && !radio_varied) {
        throw InputError("--heatmap-value radio_on: the radio is off in this machine, so the map would be all "
                         "grey (add --set radio.enabled=true)");
      }
    }
    Outputs outputs;
    AtomicFile* csv = outputs.add(*cmd, "--out", opts->out);
    AtomicFile* heat = outputs.add(*cmd, "--heatmap", opts->heatmap);
    outputs.check_distinct();
    if (heat && heat->temp_path().empty()) {
      throw InputError(fmt::format("--heatmap {}: must be a regular file", printable(opts->heatmap, 96)));
    }
    std::FILE* text = outputs.any_to_stdout() ? stderr : stdout;

    explore::RunOptions ro;
    ro.threads = opts->threads > 0 ? opts->threads
                                   : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    std::atomic<bool> stop{false};
    std::atomic<int> signal{0};
    ro.stop = &stop;
    ro.accuracy = opts->accuracy;
    ProgressBar bar(isatty(STDERR_FILENO) != 0);
    ro.progress = [&bar](std::int64_t done, std::int64_t total) { bar.update(done, total); };
    // An interrupt (Ctrl-C, SIGTERM, SIGHUP) stops the workers; the rows done so far are written.
    // It stays caught until the files are in place: a second one must not leave a .part file.
    const InterruptStops guard([&stop, &signal](int sig) {
      signal.store(sig);
      stop.store(true);
    });
    ro.csv = &csv->stream();  // written while the machines run
    ro.keep_rows = heat != nullptr;  // the heat map reads the outcomes; the CSV alone does not
    const explore::SweepResult result = explore::run(in.config, machines, ro);
    bar.finish();
#if WHATNEXT_FULL
    if (heat) explore::draw_heatmap(heat->temp_path(), machines, result, opts->heatmap_value);
#endif
    outputs.commit_all();
    if (result.interrupted) {
      fmt::print(stderr, "whatnext: sweep interrupted: {} of {} machines written to {}\n", result.completed,
                 machines.size(), printable(opts->out, 96));
      exit_code = 128 + (signal.load() > 0 ? signal.load() : SIGINT);
      return;
    }
    fmt::print(text, "sweep: {} machines ({} with invalid inputs, {} failed runs) written to {}{}\n",
               machines.size(), result.invalid, result.failed, printable(opts->out, 96),
               heat ? fmt::format(", heat map {}", printable(opts->heatmap, 96)) : "");
    exit_code = 0;
  });
}

}  // namespace whatnext::cli
