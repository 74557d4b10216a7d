// libFuzzer harness: any bytes as a TOML machine that, once accepted, is run. A run either ends
// with an outcome or stops with SimulationError; it never crashes, and every state it reports
// is finite and within its physical range.
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_common.hpp"
#include "whatnext/simulate.hpp"

namespace {

using namespace whatnext;

void check_state(const Snapshot& s, const Scenario& sc, const char* where) {
  const double values[] = {s.t, s.x, s.h, s.r, s.phi_s, s.phi_l, s.dphi_s, s.dphi_l, s.balloon_h, s.energy()};
  for (const double v : values) {
    if (!std::isfinite(v)) fuzz::broken("finite states", where);
  }
  constexpr double kHalfPi = 1.57079632679489661923;
  if (s.phi_l < sc.start.lid_angle - 1e-9 || s.phi_l > kHalfPi + 1e-9)
    fuzz::broken("lid angle in [phiL0, 90 deg]", where);
  if (std::fabs(s.phi_s) > kHalfPi + 1e-9) fuzz::broken("seesaw angle in [-90, 90] deg", where);
  if (s.t < -1e-12 || s.t > sc.run.t_max + 1e-9) fuzz::broken("times within [0, t_max]", where);
}

struct Checker : Observer {
  const Scenario* sc;
  void on_sample(const Snapshot& s) override { check_state(s, *sc, "sample"); }
  void on_event(const Event& e) override { check_state(e.after, *sc, to_string(e.type).data()); }
};

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  Scenario sc;
  try {
    sc = build_scenario(parse_toml(text, "fuzz.toml"));
  } catch (const InputError& e) {
    fuzz::check_message(e);
    return 0;
  }
  // Keep each run short: a few simulated seconds, a sane tolerance and step, few samples.
  sc.run.t_max = std::min(sc.run.t_max, 3.0);
  sc.run.tolerance = std::max(sc.run.tolerance, 1e-10);
  sc.run.step = std::max(sc.run.step, 1e-4);
  sc.run.output_step = std::max(sc.run.output_step, 0.01);
  Checker checker;
  checker.sc = &sc;
  try {
    const Result r = simulate(sc, &checker);
    if (r.events.empty() || !is_stop(r.outcome().type))
      fuzz::broken("a run ends with an outcome", std::string(text));
  } catch (const SimulationError&) {
    // A run that cannot go on says so; that is allowed.
  }
  return 0;
}
