// The integrators against each other: the adaptive default against a much tighter run, and the
// paper's Euler method converging at first order.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/simulate.hpp"

namespace wn = whatnext;

namespace {

wn::Result run(int n, const std::vector<std::string>& sets) {
  wn::Config cfg = wn::example_config(n);
  for (const auto& s : sets) wn::apply_set(cfg, s);
  return wn::simulate(wn::build_scenario(cfg));
}

class AdaptiveAccuracy : public ::testing::TestWithParam<int> {};

TEST_P(AdaptiveAccuracy, EveryEventWithinOneNanosecondOfATightReference) {
  const wn::Result dflt = run(GetParam(), {});
  const wn::Result tight = run(GetParam(), {"run.tolerance=1e-15"});
  ASSERT_EQ(dflt.events.size(), tight.events.size());
  for (std::size_t i = 0; i < dflt.events.size(); ++i) {
    EXPECT_EQ(dflt.events[i].type, tight.events[i].type) << i;
    EXPECT_NEAR(dflt.events[i].t, tight.events[i].t, 1e-9) << wn::to_string(dflt.events[i].type);
  }
}

INSTANTIATE_TEST_SUITE_P(PaperExamples, AdaptiveAccuracy, ::testing::Values(1, 2, 3, 4));

double lid_open_time(const wn::Result& r) {  // for the fixed-step check below
  EXPECT_EQ(r.outcome().type, wn::EventType::lid_open);
  return r.outcome().t;
}

// Mechanical event times (balloon events left out).
std::vector<double> mechanical_times(const wn::Result& r) {
  std::vector<double> t;
  for (const auto& e : r.events) {
    if (e.type != wn::EventType::balloon_caught && e.type != wn::EventType::balloon_free) t.push_back(e.t);
  }
  return t;
}

TEST(EulerConvergence, ErrorShrinksAboutLinearlyWithTheStep) {
  // Example 2's event times under the paper's method. An event is taken at the end of the step in
  // which it is seen, so each time carries a quantisation error anywhere in [0, dt); averaging over
  // all events and five nearby steps per level leaves the trend, fitted in log-log over a factor 32.
  const std::vector<double> ref = mechanical_times(run(2, {}));
  std::vector<double> xs, ys;
  for (double level = 1e-3; level > 2e-5; level /= 2.0) {
    double sum = 0.0;
    int count = 0;
    for (double m : {1.0, 1.07, 1.13, 1.19, 1.27}) {
      const std::vector<double> t =
          mechanical_times(run(2, {"run.integrator=\"euler\"", "run.step=" + std::to_string(level * m)}));
      EXPECT_EQ(t.size(), ref.size());
      for (std::size_t i = 0; i < std::min(t.size(), ref.size()); ++i)
        sum += std::fabs(t[i] - ref[i]), ++count;
    }
    xs.push_back(std::log(level));
    ys.push_back(std::log(sum / count));
  }
  const double n = static_cast<double>(xs.size());
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  for (std::size_t i = 0; i < xs.size(); ++i) {
    sx += xs[i], sy += ys[i], sxx += xs[i] * xs[i], sxy += xs[i] * ys[i];
  }
  const double slope = (n * sxy - sx * sy) / (n * sxx - sx * sx);
  EXPECT_NEAR(slope, 1.0, 0.3);
  EXPECT_LT(std::exp(ys.back()), 1e-4);  // and it does converge to the adaptive solution
}

TEST(FixedStep, Rk4AndEulerAgreeWithTheAdaptiveSolutionWithinAFewSteps) {
  const double ref = lid_open_time(run(1, {}));
  for (const char* integ : {"euler", "rk4"}) {
    const double t = lid_open_time(run(1, {std::string("run.integrator=") + integ, "run.step=1e-4"}));
    EXPECT_NEAR(t, ref, 3e-3) << integ;
  }
}

}  // namespace
