// whatnext benchmarks (docs/performance.md): the four examples with the adaptive integrator and the
// paper's Euler steps, a work-precision table, sweep throughput, and heap allocations per run.
// Every timed configuration also reports its event-time error against a very tight reference run
// (adaptive, tolerance 1e-15): err_s is the largest difference of the first time of each event
// type; inf when the run's set of event types differs from the reference's.
#include <benchmark/benchmark.h>

#include <atomic>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <map>
#include <new>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "number_text.hpp"  // src/io/: the output files' number writers
#include "whatnext/config.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

// --- counting global operator new: shows that a run allocates per event, never per step ---------
namespace {
std::atomic<long> g_allocations{0};
}
// GCC takes the free() in the replaced operator delete below for a mismatch with new; every new
// here comes from malloc, so it is not one.
#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic ignored "-Wmismatched-new-delete"
#endif
void* operator new(std::size_t n) {
  g_allocations.fetch_add(1, std::memory_order_relaxed);
  if (void* p = std::malloc(n ? n : 1)) return p;
  throw std::bad_alloc();
}
void* operator new[](std::size_t n) { return ::operator new(n); }
void operator delete(void* p) noexcept { std::free(p); }
void operator delete[](void* p) noexcept { std::free(p); }
void operator delete(void* p, std::size_t) noexcept { std::free(p); }
void operator delete[](void* p, std::size_t) noexcept { std::free(p); }

namespace {

using namespace whatnext;
constexpr double kInf = std::numeric_limits<double>::infinity();

struct Method {
  IntegratorKind kind;
  double param;  // tolerance (adaptive) or step (euler, rk4)
  std::string name() const {
    return kind == IntegratorKind::adaptive ? fmt::format("adaptive_tol{:g}", param)
                                            : fmt::format("{}_dt{:g}", to_string(kind), param);
  }
};

Config with_method(Config c, const Method& m) {
  c.values.erase("run.integrator");
  apply_set(c, fmt::format("run.integrator={}", to_string(m.kind)));
  set_number(c, m.kind == IntegratorKind::adaptive ? "run.tolerance" : "run.step", m.param);
  return c;
}

std::map<EventType, double> first_times(const Result& r) {
  std::map<EventType, double> out;
  for (const Event& e : r.events) out.emplace(e.type, e.t);  // emplace keeps the first
  return out;
}

double event_error(const Result& run, const Result& ref) {
  const auto a = first_times(run), b = first_times(ref);
  if (a.size() != b.size()) return kInf;
  double err = 0.0;
  for (const auto& [type, t] : b) {
    const auto it = a.find(type);
    if (it == a.end()) return kInf;
    err = std::fmax(err, std::fabs(it->second - t));
  }
  return err;
}

const Result& reference(int example) {
  static std::map<int, Result> cache;
  auto it = cache.find(example);
  if (it == cache.end()) {
    Config c = example_config(example);
    set_number(c, "run.tolerance", 1e-15);
    it = cache.emplace(example, simulate(build_scenario(c))).first;
  }
  return it->second;
}

// One example, one method: time per run, event-time error, steps.
void run_example(benchmark::State& state, int example, Method m) {
  const Scenario sc = build_scenario(with_method(example_config(example), m));
  const Result once = simulate(sc);
  for (auto _ : state) {
    Result r = simulate(sc);
    benchmark::DoNotOptimize(r.events.data());
  }
  state.counters["err_s"] = event_error(once, reference(example));
  state.counters["steps"] = static_cast<double>(once.stats.steps);
  state.counters["t_end_s"] = once.outcome().t;
}

// The grid of docs/performance.md: 10^4 example-2-class machines, rope length and drop height varied around
// example 2, as `whatnext sweep` runs them (the tolerance chosen from the accuracy asked, rows
// formatted as CSV lines in the workers, the CSV written).
explore::Plan sweep_plan() {
  explore::Plan p;
  p.ranges.push_back(explore::parse_range("geometry.rope_length=0.64:0.80:100", "--vary", true));
  p.ranges.push_back(explore::parse_range("start.sandbag_height=0.3:1.2:100", "--vary", true));
  return p;
}

std::int64_t write_sweep_csv(const explore::Machines& machines, const explore::SweepResult& r);

void sweep_throughput(benchmark::State& state, double accuracy) {
  const int threads = static_cast<int>(state.range(0));
  const explore::Machines machines(sweep_plan());
  const Config base = example_config(2);
  explore::RunOptions ro;
  ro.threads = threads;
  ro.accuracy = accuracy;
  std::int64_t invalid = 0;
  for (auto _ : state) {
    const explore::SweepResult r = explore::run(base, machines, ro);
    invalid = 0;
    for (const auto& o : r.rows) invalid += o.valid ? 0 : 1;
    benchmark::DoNotOptimize(write_sweep_csv(machines, r));
  }
  state.SetItemsProcessed(state.iterations() * machines.size());
  // Accuracy of these very machines, every one of them, against tolerance 1e-14 (event times to
  // 1e-14 s): the first time of each event type, as the sweep reports it. err_over_accuracy must
  // stay below 1; seq_diff counts machines whose events (or validity) differ in kind, which no
  // accuracy can excuse; beyond_half those whose worst event is off by more than half the accuracy.
  const explore::SweepResult run = explore::run(base, machines, ro);
  static const explore::SweepResult ref = [&] {  // the same for every accuracy: computed once
    Config tight = base;
    set_number(tight, "run.tolerance", 1e-14);
    explore::RunOptions tight_ro = ro;
    tight_ro.threads = 2;
    tight_ro.accuracy = 1e-12;  // the events located to 1e-14 s; the tolerance is the one given
    return explore::run(tight, machines, tight_ro);
  }();
  double err = 0.0;
  std::int64_t seq_diff = 0, beyond_half = 0;
  for (std::size_t i = 0; i < run.rows.size(); ++i) {
    const auto& a = run.rows[i];
    const auto& b = ref.rows[i];
    if (a.valid != b.valid || a.outcome != b.outcome) {
      ++seq_diff;
      continue;
    }
    if (!a.valid) continue;
    bool differs = false;
    double e = 0.0;
    for (std::size_t k = 0; k < a.first.size(); ++k) {
      if (std::isnan(a.first[k]) != std::isnan(b.first[k]))
        differs = true;
      else if (!std::isnan(a.first[k]))
        e = std::fmax(e, std::fabs(a.first[k] - b.first[k]));
    }
    if (differs)
      ++seq_diff;
    else
      err = std::fmax(err, e);
    if (!differs && e > 0.5 * accuracy) ++beyond_half;
  }
  state.counters["err_s"] = err;
  state.counters["err_over_accuracy"] = err / accuracy;
  state.counters["seq_diff"] = static_cast<double>(seq_diff);
  state.counters["beyond_half"] = static_cast<double>(beyond_half);
  state.counters["invalid"] = static_cast<double>(invalid);
}

// --- output files: `whatnext run --example 3 --set run.output_step=0.00025 --dat/--csv` ---------

// A stream that counts what it is given and keeps nothing, as fast as a stream can be: what is
// left is the writers' own cost.
class CountingBuf : public std::streambuf {
 public:
  std::int64_t bytes = 0;

 protected:
  int_type overflow(int_type ch) override {
    ++bytes;
    return traits_type::not_eof(ch);
  }
  std::streamsize xsputn(const char*, std::streamsize n) override {
    bytes += n;
    return n;
  }
};

std::int64_t write_sweep_csv(const explore::Machines& machines, const explore::SweepResult& r) {
  CountingBuf buf;
  std::ostream out(&buf);
  explore::write_csv(out, machines, r);
  return buf.bytes;
}

Scenario example3_fine() {
  Config c = example_config(3);
  set_number(c, "run.output_step", 0.00025);  // the paper's step for example 3: 79,777 rows
  return build_scenario(c);
}

// Samples taken and thrown away: the cost of the rows before any text (dense output, kinematics
// and, for full samples, forces and energies).
class Discard : public Observer {
 public:
  explicit Discard(Detail d) : detail_(d) {}
  Detail sample_detail() const override { return detail_; }
  void on_sample(const Snapshot& s) override { benchmark::DoNotOptimize(s.x); }

 private:
  Detail detail_;
};

void samples_only(benchmark::State& state, Observer::Detail detail) {
  const Scenario sc = example3_fine();
  Discard sink(detail);
  for (auto _ : state) {
    Result r = simulate(sc, &sink);
    benchmark::DoNotOptimize(r.events.data());
  }
}

// The run with its writer, as the command does it (the file itself excluded: see CountingBuf):
// its rows made on one thread, or on two (Writing::parallel, the command's; real time).
template <class Writer>
void run_with_writer(benchmark::State& state, Writing writing) {
  const Scenario sc = example3_fine();
  std::int64_t bytes = 0;
  for (auto _ : state) {
    CountingBuf buf;
    std::ostream out(&buf);
    Writer w(out, writing);
    Result r = simulate(sc, &w);
    benchmark::DoNotOptimize(r.events.data());
    bytes = buf.bytes;
  }
  state.SetBytesProcessed(state.iterations() * bytes);
  state.counters["file_bytes"] = static_cast<double>(bytes);
}

// Formatting alone, over the run's recorded samples: the library's number writers against fmt's
// compiled formats for the same text ("{:8.3f}" for the .dat, "{:.9g}" for the CSV). This is the
// benchmark that justifies numtext (docs/performance.md).
const std::vector<Snapshot>& example3_fine_samples() {
  static const std::vector<Snapshot> samples = [] {
    Recorder rec;
    simulate(example3_fine(), &rec);
    return rec.samples;
  }();
  return samples;
}

std::vector<double> dat_values(const Snapshot& s) {
  return {s.t, s.x, s.h, s.phi_s, s.phi_l, s.balloon_limit, s.balloon_h, 0.0, s.rope_taut ? 1.0 : 0.0};
}
std::vector<double> csv_values(const Snapshot& s) {
  return {s.t,
          s.x,
          s.h,
          s.r,
          s.dr,
          s.phi_s,
          s.dphi_s,
          s.phi_l,
          s.dphi_l,
          s.balloon_h,
          s.balloon_v,
          s.balloon_limit,
          s.tension,
          s.energy(),
          s.sandbag_kinetic,
          s.sandbag_potential,
          s.lid_kinetic,
          s.lid_potential,
          s.seesaw_kinetic,
          s.seesaw_potential,
          s.balloon_kinetic,
          s.balloon_potential,
          s.lost_impacts,
          s.lost_balloon_catch,
          s.dissipated_pivot,
          s.dissipated_hinge,
          s.dissipated_drag,
          s.lid_push_work,
          s.ledger_residual()};
}

template <class Put>
void format_numbers(benchmark::State& state, std::vector<double> (*values)(const Snapshot&), Put put) {
  std::vector<double> all;
  for (const Snapshot& s : example3_fine_samples()) {
    for (double v : values(s)) all.push_back(v);
  }
  std::vector<char> text(all.size() * 24);
  std::int64_t bytes = 0;
  for (auto _ : state) {
    char* p = text.data();
    for (double v : all) p = put(p, v);
    bytes = p - text.data();
    benchmark::DoNotOptimize(text.data());
  }
  state.SetItemsProcessed(state.iterations() * static_cast<std::int64_t>(all.size()));
  state.counters["s_per_number"] =
      benchmark::Counter(static_cast<double>(all.size()),
                         benchmark::Counter::kIsIterationInvariantRate | benchmark::Counter::kInvert);
  state.counters["text_bytes"] = static_cast<double>(bytes);
}

// Heap allocations per run: constant in the number of steps means none per step.
void allocations(benchmark::State& state, int example, Method m) {
  const Scenario sc = build_scenario(with_method(example_config(example), m));
  long per_run = 0;
  std::int64_t steps = 0;
  for (auto _ : state) {
    const long before = g_allocations.load();
    Result r = simulate(sc);
    per_run = g_allocations.load() - before;
    steps = r.stats.steps;
    benchmark::DoNotOptimize(r.events.data());
  }
  state.counters["allocs_per_run"] = static_cast<double>(per_run);
  state.counters["steps"] = static_cast<double>(steps);
  state.counters["allocs_per_step"] = static_cast<double>(per_run) / static_cast<double>(steps);
}

}  // namespace

int main(int argc, char** argv) {
  const Method adaptive_default{IntegratorKind::adaptive, 1e-12};
  const Method adaptive_1e9{IntegratorKind::adaptive, 1e-11};
  const Method euler_paper{IntegratorKind::euler, 1e-3};
  const Method euler_fine{IntegratorKind::euler, 2.5e-4};
  for (int ex = 1; ex <= 4; ++ex) {
    for (const Method& m : {adaptive_default, adaptive_1e9, euler_paper, euler_fine}) {
      benchmark::RegisterBenchmark(fmt::format("example{}/{}", ex, m.name()).c_str(), run_example, ex, m)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  std::vector<Method> table;
  for (double dt : {1e-3, 2.5e-4, 1e-4, 2.5e-5}) table.push_back({IntegratorKind::euler, dt});
  for (double dt : {1e-2, 2.5e-3, 1e-3, 2.5e-4, 1e-4}) table.push_back({IntegratorKind::rk4, dt});
  for (double tol : {1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12, 1e-13})
    table.push_back({IntegratorKind::adaptive, tol});
  for (int ex : {2, 3}) {
    for (const Method& m : table) {
      benchmark::RegisterBenchmark(fmt::format("precision/example{}/{}", ex, m.name()).c_str(), run_example,
                                   ex, m)
          ->Unit(benchmark::kMicrosecond);
    }
  }
  for (double accuracy : {1e-6, 1e-8, 1e-10}) {
    benchmark::RegisterBenchmark(
        fmt::format("sweep/example2_grid_10000/accuracy{:g}/threads", accuracy).c_str(), sweep_throughput,
        accuracy)
        ->Arg(1)
        ->Arg(2)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("output/example3_step0.00025/samples_positions", samples_only,
                               Observer::Detail::positions)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("output/example3_step0.00025/samples_full", samples_only,
                               Observer::Detail::full)
      ->Unit(benchmark::kMillisecond);
  for (const auto& [name, writing] :
       {std::pair{"at_once", Writing::at_once}, std::pair{"parallel", Writing::parallel}}) {
    benchmark::RegisterBenchmark((std::string("output/example3_step0.00025/dat/") + name).c_str(),
                                 run_with_writer<DatWriter>, writing)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
    benchmark::RegisterBenchmark((std::string("output/example3_step0.00025/csv/") + name).c_str(),
                                 run_with_writer<CsvWriter>, writing)
        ->UseRealTime()
        ->Unit(benchmark::kMillisecond);
  }
  benchmark::RegisterBenchmark("format/dat_numbers/numtext", format_numbers<char* (*)(char*, double)>,
                               dat_values, numtext::put_f8_3)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("format/dat_numbers/fmt_compiled", format_numbers<char* (*)(char*, double)>,
                               dat_values,
                               [](char* p, double v) { return fmt::format_to(p, FMT_COMPILE("{:8.3f}"), v); })
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("format/csv_numbers/numtext", format_numbers<char* (*)(char*, double)>,
                               csv_values, numtext::put_g9)
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("format/csv_numbers/fmt_compiled", format_numbers<char* (*)(char*, double)>,
                               csv_values,
                               [](char* p, double v) { return fmt::format_to(p, FMT_COMPILE("{:.9g}"), v); })
      ->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("allocations/example2/adaptive_tol1e-12", allocations, 2, adaptive_default);
  benchmark::RegisterBenchmark("allocations/example3/adaptive_tol1e-12", allocations, 3, adaptive_default);
  benchmark::RegisterBenchmark("allocations/example3/euler_dt0.00025", allocations, 3, euler_fine);
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
