// `whatnext sweep`: many machines over a grid or a Latin hypercube, one CSV row each.
#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <exception>
#include <memory>
#include <thread>

#include <fmt/format.h>

#include "cli_common.hpp"
#if WHATNEXT_FULL
#include "whatnext/viz/heatmap.hpp"
#endif
#include "whatnext/explore/sweep.hpp"
#include "whatnext/explore/sweep_file.hpp"
#include "whatnext/output.hpp"
#if WHATNEXT_FULL
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

}  // namespace

void register_sweep(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<SweepOptions>();
  CLI::App* cmd =
      app.add_subcommand("sweep", "run many machines over a grid of input values, one CSV row each");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--vary", opts->vary,
                  "KEY=A:B:N: N values of KEY from A to B (KEY=A:B with --samples); repeat for more keys")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option(
         "--spread", opts->spread,
         "KEY=±X (or KEY=+-X): a Monte Carlo around the machine, KEY off by a random amount of spread X "
         "in its unit; repeat for more keys")
      ->take_all()
      ->allow_extra_args(false);
  cmd->add_option("--spread-dist", opts->spread_dist,
                  "normal (X is the standard deviation, the default) or uniform (X is the half-width)");
  cmd->add_option("--histogram", opts->histogram,
                  "with --spread: a PNG histogram of the lid's opening time (the radio's, if it is on)");
  cmd->add_option(
         "--samples", opts->samples,
         "a Latin hypercube of this many machines instead of the grid; with --spread, the machines drawn "
         "(default 1000)")
      ->check(CLI::Range(std::int64_t{1}, explore::kMaxMachines));
  cmd->add_option("--seed", opts->seed,
                  "seed of the Latin hypercube or the --spread draws (same seed, same machines)");
  cmd->add_option("--threads", opts->threads, "worker threads (default: all cores)")
      ->check(CLI::Range(1, 1024));
  cmd->add_option("--accuracy", opts->accuracy,
                  fmt::format("event times to this many seconds (default {:g}); sets the integrator's "
                              "tolerance unless run.tolerance is given",
                              explore::kDefaultAccuracy));
  cmd->add_option("--out", opts->out, "CSV file to write, one row per machine ('-': standard output)");
  cmd->add_option("--heatmap", opts->heatmap, "also draw a PNG heat map (needs exactly two --vary keys)");
  cmd->add_option("--heatmap-value", opts->heatmap_value,
                  "value drawn: an event name (its first time, e.g. lid_open), outcome_t, final_r or "
                  "final_phi_l_deg");
  cmd->add_flag("--resume", opts->resume,
                "continue the sweep an interrupted run left in --out (its .part file or the CSV itself); "
                "the file ends the same as an uninterrupted run's");
  cmd->add_flag("--force-large", opts->force_large,
                fmt::format("run sweeps of more than {} machines", kLargeSweep));
  cmd->callback([opts, cmd, &exit_code] {
#if !WHATNEXT_FULL
    if (given(*cmd, "--heatmap") || given(*cmd, "--histogram")) hand_over_to_full();
#endif
    check_leftovers(*cmd);
    explore::check_accuracy(opts->accuracy, "--accuracy");
    // Everything about the input is checked before any machine runs or any file appears.
    const bool monte_carlo = !opts->spread.empty();
    if (opts->vary.empty() && !monte_carlo) {
      throw InputError("sweep: give --vary KEY=A:B:N for a grid (or --spread KEY=±X for a Monte Carlo)");
    }
    if (!opts->vary.empty() && monte_carlo) {
      throw InputError("sweep: --vary and --spread do not mix: a grid, or a Monte Carlo around one machine");
    }
    if (!monte_carlo) {
      for (const char* o : {"--spread-dist", "--histogram"}) {
        if (given(*cmd, o)) throw InputError(fmt::format("{}: goes with --spread KEY=±X (a Monte Carlo)", o));
      }
      if (!given(*cmd, "--out")) throw InputError("--out: give the CSV file to write ('-': standard output)");
    } else {
      for (const char* o : {"--heatmap", "--heatmap-value", "--resume"}) {
        if (given(*cmd, o)) {
          throw InputError(
              fmt::format("{}: goes with a grid (--vary), not with a Monte Carlo (--spread)", o));
        }
      }
      if (given(*cmd, "--histogram") && !ends_with(opts->histogram, ".png") &&
          !ends_with(opts->histogram, ".PNG")) {
        throw InputError(fmt::format("--histogram {}: the histogram is a PNG; give a name ending in .png",
                                     printable(opts->histogram, 96)));
      }
    }
    explore::Plan plan;
    plan.samples = opts->samples;
    plan.seed = opts->seed;
    std::vector<explore::Spread> spreads;
    if (monte_carlo) {
      plan.spread_kind = explore::parse_spread_kind(opts->spread_dist, "--spread-dist");
      for (const std::string& v : opts->spread) spreads.push_back(explore::parse_spread(v, "--spread"));
      if (plan.samples == 0) plan.samples = 1000;
    }
    for (const std::string& v : opts->vary) {
      plan.ranges.push_back(explore::parse_range(v, "--vary", plan.samples == 0));
      if (plan.samples > 0 && plan.ranges.back().n != 0) {
        throw InputError(
            fmt::format("--vary {}: with --samples the values come from a Latin hypercube; write "
                        "KEY=A:B without a count",
                        printable(v)));
      }
    }
    // A Latin hypercube's points are made up front: its size is checked before.
    const auto check_large = [&](std::int64_t n) {
      if (n > kLargeSweep && !opts->force_large) {
        throw InputError(
            fmt::format("sweep: {} machines would hold about {:.1f} GB in memory and write as much; "
                        "use fewer, or give --force-large",
                        n, static_cast<double>(n) * kSweepRowBytes / 1e9));
      }
    };
    check_large(plan.samples);
    const LoadedInput in = load_input(opts->input);
    for (const explore::Spread& sp : spreads) {  // around the machine's own values
      explore::Range r;
      r.key = sp.key;
      r.lo = r.hi = explore::base_value(in.config, sp.key, "--spread");
      plan.ranges.push_back(r);
      plan.spread.push_back(sp.x);
    }
    const explore::Machines machines(plan);
    check_large(machines.size());
    if (given(*cmd, "--heatmap")) {
#if WHATNEXT_FULL
      viz::check_heatmap_plan(plan, "--heatmap");
#endif
      if (!ends_with(opts->heatmap, ".png") && !ends_with(opts->heatmap, ".PNG")) {
        throw InputError(fmt::format("--heatmap {}: the heat map is a PNG; give a name ending in .png",
                                     printable(opts->heatmap, 96)));
      }
    }
    if (given(*cmd, "--heatmap") || given(*cmd, "--heatmap-value")) {
      explore::check_value_name(opts->heatmap_value, "--heatmap-value");
      bool radio_varied = false;
      for (const explore::Range& r : plan.ranges)
        radio_varied = radio_varied || r.key.rfind("radio.", 0) == 0;
      if (opts->heatmap_value == "radio_on" && !in.scenario.machine.radio && !radio_varied) {
        throw InputError(
            "--heatmap-value radio_on: the radio is off in this machine, so the map would be all "
            "grey (add --set radio.enabled=true)");
      }
    }
    if (opts->resume && given(*cmd, "--heatmap")) {
      throw InputError(
          "--resume: draw the heat map from the finished CSV with a sweep of its own; --resume does "
          "not take --heatmap");
    }
    // The CSV of a grid or Latin hypercube in a regular file is written resumably (docs/explore.md,
    // "Resuming a sweep"); a resumed sweep reads what the interrupted one left (and checks that it
    // is this sweep's) before anything is written.
    std::unique_ptr<explore::SweepFile> file;
    explore::Resumable kept;
    std::string text;
    std::string_view kept_text;
    if (opts->resume || (!monte_carlo && regular_file_output(opts->out))) {
      const std::string target = regular_output_target(opts->out, "--out");
      check_unclaimed("--out", opts->out);
      file = std::make_unique<explore::SweepFile>(target, opts->out, "--out");
      if (opts->resume) {
        text = file->previous();
        kept = explore::read_resumable(text, machines, in.config, opts->accuracy,
                                       fmt::format("--resume {}", printable(file->source(), 96)));
      }
      kept_text = std::string_view(text).substr(0, kept.prefix_bytes);
    }
    Outputs outputs;
    AtomicFile* csv = file ? nullptr : outputs.add(*cmd, "--out", opts->out);
    AtomicFile* heat = outputs.add(*cmd, "--heatmap", opts->heatmap);
    AtomicFile* hist = outputs.add(*cmd, "--histogram", opts->histogram);
    outputs.check_distinct();
    if (hist && hist->temp_path().empty()) {
      throw InputError(fmt::format("--histogram {}: must be a regular file", printable(opts->histogram, 96)));
    }
    if (heat && heat->temp_path().empty()) {
      throw InputError(fmt::format("--heatmap {}: must be a regular file", printable(opts->heatmap, 96)));
    }
    std::FILE* text_out = outputs.any_to_stdout() ? stderr : stdout;
    // Every output checked: only now is the .part file cut or made (a refused sweep touches nothing).
    if (file) file->start(kept_text);

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
    // Rows are made durable as they go (about once a second), so that a kill or a power cut
    // leaves a .part file that --resume continues.
    std::exception_ptr write_failure;
    int sync_fd = -1;
    if (csv && !csv->to_stdout() && !csv->temp_path().empty())
      sync_fd = ::open(csv->temp_path().c_str(), O_RDONLY | O_CLOEXEC);
    ro.checkpoint = [&] {
      try {
        if (file) {
          file->sync();
        } else if (csv) {
          csv->flush();
          if (sync_fd >= 0) (void)::fdatasync(sync_fd);
        }
      } catch (...) {  // thrown here it would end the workers' threads: they stop, it is thrown after
        if (!write_failure) write_failure = std::current_exception();
        stop.store(true);
      }
    };
    if (opts->resume) {
      ro.header_written = kept.header;
      ro.rows_written = kept.prefix_rows;
      ro.known = std::move(kept.later);
    }
    ro.csv = file ? &file->stream() : csv ? &csv->stream() : nullptr;  // written while the machines run
    ro.keep_rows = heat != nullptr || monte_carlo;  // the heat map and the summary read the outcomes
    const explore::SweepResult result = explore::run(in.config, machines, ro);
    bar.finish();
    // A Monte Carlo's summary: how often the machine works, and when.
    std::string summary;
    std::string value = "lid_open";
    explore::Distribution dist;
    double designed = 0.0;
    if (monte_carlo) {
      const bool radio = in.scenario.machine.radio;
      value = radio ? "radio_on" : "lid_open";
      std::vector<double> centre;
      for (const explore::Range& r : plan.ranges) centre.push_back(r.lo);
      const explore::Outcome own = explore::evaluate(in.config, plan.keys(), centre.data(), opts->accuracy);
      designed = explore::value_of(own, value);
      summary = fmt::format("monte carlo: {} machines around {}, {} key{} off by {} spreads (seed {})\n",
                            result.completed, in.source, spreads.size(), spreads.size() == 1 ? "" : "s",
                            opts->spread_dist, opts->seed);
      summary +=
          fmt::format("  the machine as given: {}\n",
                      own.valid ? fmt::format("{} at {:.4f} s", to_string(own.outcome), own.outcome_t)
                                : fmt::format("{} ({})", own.failed ? "failed" : "invalid", own.error));
      const auto line = [&](const std::string& name, const char* what) {
        const explore::Distribution d = explore::distribution(result, name);
        const double n = static_cast<double>(std::max<std::int64_t>(1, result.completed));
        std::string out = fmt::format("  {} in {} of {} machines ({:.1f} %)", what, d.happened,
                                      result.completed, 100.0 * static_cast<double>(d.happened) / n);
        if (d.happened > 0) {
          out += fmt::format(
              "; {} [s]: 5 % {:.4f}, 25 % {:.4f}, median {:.4f}, 75 % {:.4f}, 95 % {:.4f} "
              "(min {:.4f}, max {:.4f})",
              name, d.quantile(0.05), d.quantile(0.25), d.quantile(0.5), d.quantile(0.75), d.quantile(0.95),
              d.values.front(), d.values.back());
        }
        summary += out + "\n";
        return d;
      };
      dist = line("lid_open", "the lid opens");
      if (radio) dist = line("radio_on", "the radio turns on");
      if (result.invalid + result.failed > 0) {
        summary += fmt::format("  {} machines with invalid inputs, {} failed runs (counted as not working)\n",
                               result.invalid, result.failed);
      }
    }
#if WHATNEXT_FULL
    if (heat) viz::draw_heatmap(heat->temp_path(), machines, result, opts->heatmap_value);
    if (hist) {
      viz::HistogramText t;
      t.title = fmt::format("{}: {} machines around {}", value, result.completed, printable(in.source, 60));
      t.x_label = value + " [s]";
      const std::int64_t never = result.completed - dist.happened;
      t.note =
          fmt::format("{} of {} machines{}; red line: the machine as given", dist.happened, result.completed,
                      never > 0 ? fmt::format(" ({} invalid or without {})", never, value) : std::string());
      viz::draw_histogram(hist->temp_path(), dist.values, designed, t);
    }
#else
    (void)designed;
#endif
    if (sync_fd >= 0) ::close(sync_fd);
    if (write_failure) std::rethrow_exception(write_failure);
    if (file) file->sync();  // every file written before any is renamed: all appear, or none
    outputs.commit_all();
    if (file) file->commit();
    if (result.interrupted) {
      fmt::print(stderr, "whatnext: sweep interrupted: {} of {} machines written to {}\n", result.completed,
                 machines.size(), printable(opts->out, 96));
      exit_code = 128 + (signal.load() > 0 ? signal.load() : SIGINT);
      return;
    }
    if (monte_carlo) {
      fmt::print(text_out, "{}", summary);
      if (!csv && !hist) {
        exit_code = 0;
        return;
      }
      fmt::print(text_out, "written to {}\n",
                 csv && hist
                     ? fmt::format("{} and {}", printable(opts->out, 96), printable(opts->histogram, 96))
                 : csv ? printable(opts->out, 96)
                       : printable(opts->histogram, 96));
      exit_code = 0;
      return;
    }
    fmt::print(text_out, "sweep: {} machines ({} with invalid inputs, {} failed runs) written to {}{}{}\n",
               machines.size(), result.invalid + kept.invalid, result.failed + kept.failed,
               printable(opts->out, 96),
               heat ? fmt::format(", heat map {}", printable(opts->heatmap, 96)) : "",
               opts->resume && file ? fmt::format(" ({} rows kept from the interrupted sweep)", kept.kept) : "");
    exit_code = 0;
  });
}

}  // namespace whatnext::cli
