// `whatnext sweep`: many machines over a grid or a Latin hypercube, one CSV row each.
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <fstream>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/explore/heatmap.hpp"
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
  std::string out, heatmap, heatmap_value = "lid_open";
};

// Set by SIGINT; the workers stop taking machines and the rows done so far are written.
std::atomic<bool> g_interrupted{false};
extern "C" void on_sigint(int) { g_interrupted.store(true); }

// Fails early (before any work) when a file cannot be written; nothing is left behind.
void check_writable(const std::string& path) {
  const std::string probe = path + ".part";
  {
    std::ofstream f(probe, std::ios::binary | std::ios::trunc);
    if (!f) throw std::runtime_error(fmt::format("{}: cannot write this file", path));
  }
  std::remove(probe.c_str());
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
  cmd->add_option("--out", opts->out, "CSV file to write, one row per machine")->required();
  cmd->add_option("--heatmap", opts->heatmap, "also draw a PNG heat map (needs exactly two --vary keys)");
  cmd->add_option("--heatmap-value", opts->heatmap_value,
                  "value drawn: an event name (its first time, e.g. lid_open), outcome_t, final_r or "
                  "final_phi_l_deg");
  cmd->callback([opts, &exit_code] {
    // Everything about the input is checked before any machine runs or any file appears.
    explore::Plan plan;
    plan.samples = opts->samples;
    plan.seed = opts->seed;
    for (const std::string& v : opts->vary) {
      plan.ranges.push_back(explore::parse_range(v, "--vary", plan.samples == 0));
    }
    const explore::Machines machines(plan);
    if (!opts->heatmap.empty()) {
      explore::check_heatmap_plan(plan, "--heatmap");
      explore::check_value_name(opts->heatmap_value, "--heatmap-value");
    }
    const LoadedInput in = load_input(opts->input);
    AtomicFile csv(opts->out);
    if (!opts->heatmap.empty()) check_writable(opts->heatmap);

    explore::RunOptions ro;
    ro.threads = opts->threads > 0 ? opts->threads
                                   : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
    ro.stop = &g_interrupted;
    ProgressBar bar(isatty(STDERR_FILENO) != 0);
    ro.progress = [&bar](std::int64_t done, std::int64_t total) { bar.update(done, total); };
    g_interrupted.store(false);
    const auto old_handler = std::signal(SIGINT, on_sigint);
    const explore::SweepResult result = explore::run(in.config, machines, ro);
    bar.finish();

    // The handler stays until the files are in place: a second Ctrl-C must not leave a .part file.
    explore::write_csv(csv.stream(), machines, result);
    csv.commit();
    if (!opts->heatmap.empty()) explore::draw_heatmap(opts->heatmap, machines, result, opts->heatmap_value);
    std::signal(SIGINT, old_handler);
    std::int64_t invalid = 0;
    for (std::int64_t i = 0; i < machines.size(); ++i) {
      if (result.done[static_cast<std::size_t>(i)] && !result.rows[static_cast<std::size_t>(i)].valid) ++invalid;
    }
    if (result.interrupted) {
      fmt::print(stderr, "whatnext: sweep interrupted: {} of {} machines written to {}\n", result.completed,
                 machines.size(), opts->out);
      exit_code = 130;
      return;
    }
    fmt::print("sweep: {} machines ({} with invalid inputs) written to {}{}\n", machines.size(), invalid,
               opts->out, opts->heatmap.empty() ? "" : fmt::format(", heat map {}", opts->heatmap));
    exit_code = 0;
  });
}

}  // namespace whatnext::cli
