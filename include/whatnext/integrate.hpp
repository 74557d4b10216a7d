// Generic integrators with event location. They know nothing of seesaws: a System supplies
//   using state_type = std::array<double, N>;  using guard_type = std::array<double, G>;
//   void operator()(const state_type& y, state_type& dy, double t) const;   // the flow
//   void guards(const state_type& y, guard_type& g) const;                   // event functions
// A guard fires when its value goes from negative to >= 0. Each call integrates one smooth piece
// from t up to the first firing guard or t_end and hands samples on an output grid to a callback.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>

#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>

namespace whatnext {

struct Crossing {
  int guard = -1;  // -1: t_end reached without an event
  double t = 0.0;
};

struct StepStats {
  std::int64_t steps = 0;
  std::int64_t root_evaluations = 0;
};

// Output times n * step; next is the index of the next sample still to be written.
struct OutputGrid {
  double step = 0.0;  // <= 0: no samples
  std::int64_t next = 0;
  double time() const { return static_cast<double>(next) * step; }
};

namespace detail {
template <class System, class Eval, class Sample>
void sample_until(OutputGrid& grid, double t_hi, Eval&& eval, Sample&& sample) {
  if (grid.step <= 0.0) return;
  typename System::state_type y;
  while (grid.time() <= t_hi) {
    const double t = grid.time();
    eval(t, y);
    sample(t, y);
    ++grid.next;
  }
}
}  // namespace detail

// Embedded Dormand-Prince 5(4) with error control and dense output (Boost.Odeint). Guards are
// checked at every step end; a sign change is located on the dense output with TOMS 748 to
// time_tolerance, and the state is returned at the end of the bracket where the guard has fired.
template <class System, class Sample>
Crossing integrate_adaptive(const System& sys, typename System::state_type& y, double& t,
                            double t_end, double tolerance, double max_dt, double time_tolerance,
                            OutputGrid& grid, Sample&& sample, StepStats& stats) {
  namespace odeint = boost::numeric::odeint;
  using state_type = typename System::state_type;
  using guard_type = typename System::guard_type;
  auto stepper = odeint::make_dense_output(tolerance, tolerance, max_dt,
                                           odeint::runge_kutta_dopri5<state_type>());
  const double dt0 = std::fmin(max_dt, std::fmax(1e-6, 0.05 * std::pow(tolerance, 0.2)));
  stepper.initialize(y, t, dt0);
  auto eval = [&](double tt, state_type& out) { stepper.calc_state(tt, out); };

  guard_type g0, g1;
  sys.guards(y, g0);
  state_type y1;
  for (;;) {
    const auto interval = stepper.do_step(std::cref(sys));
    ++stats.steps;
    const double ta = interval.first;
    const double tb = std::fmin(interval.second, t_end);
    if (tb < interval.second) {
      stepper.calc_state(tb, y1);
    } else {
      y1 = stepper.current_state();
    }
    sys.guards(y1, g1);
    int hit = -1;
    double t_hit = tb;
    for (std::size_t i = 0; i < g0.size(); ++i) {
      if (!(g0[i] < 0.0 && g1[i] >= 0.0)) continue;
      auto f = [&](double tt) {
        state_type yy;
        guard_type gg;
        stepper.calc_state(tt, yy);
        sys.guards(yy, gg);
        ++stats.root_evaluations;
        return gg[i];
      };
      std::uintmax_t iterations = 200;
      auto stop = [&](double a, double b) { return std::fabs(b - a) <= time_tolerance; };
      const auto bracket = boost::math::tools::toms748_solve(f, ta, tb, g0[i], g1[i], stop, iterations);
      // The end of the bracket where the guard has fired (f >= 0).
      const double root = f(bracket.first) >= 0.0 ? bracket.first : bracket.second;
      if (hit < 0 || root < t_hit) hit = static_cast<int>(i), t_hit = root;
    }
    if (hit >= 0) {
      detail::sample_until<System>(grid, t_hit, eval, sample);
      stepper.calc_state(t_hit, y);
      t = t_hit;
      return {hit, t_hit};
    }
    detail::sample_until<System>(grid, tb, eval, sample);
    g0 = g1;
    if (tb >= t_end) {
      y = y1;
      t = t_end;
      return {-1, t_end};
    }
  }
}

// Fixed-step explicit Euler (the paper's method) or classical RK4. An event is taken at the end of
// the step in which its guard is first seen to have fired; of several, the one whose linear
// estimate of the crossing is earliest. Samples are the step-end states at or after each grid time.
template <class Stepper, class System, class Sample>
Crossing integrate_fixed(const System& sys, typename System::state_type& y, double& t,
                         double t_end, double dt, OutputGrid& grid, Sample&& sample,
                         StepStats& stats) {
  using guard_type = typename System::guard_type;
  Stepper stepper;
  guard_type g0, g1;
  sys.guards(y, g0);
  for (;;) {
    const double h = std::fmin(dt, t_end - t);
    stepper.do_step(std::cref(sys), y, t, h);
    t = (t_end - t <= dt) ? t_end : t + h;
    ++stats.steps;
    sys.guards(y, g1);
    int hit = -1;
    double best = 2.0;
    for (std::size_t i = 0; i < g0.size(); ++i) {
      if (!(g0[i] < 0.0 && g1[i] >= 0.0)) continue;
      const double frac = g0[i] / (g0[i] - g1[i]);
      if (frac < best) best = frac, hit = static_cast<int>(i);
    }
    if (grid.step > 0.0) {
      while (grid.time() <= t) {
        sample(t, y);
        ++grid.next;
      }
    }
    if (hit >= 0) return {hit, t};
    if (t >= t_end) return {-1, t_end};
    g0 = g1;
  }
}

}  // namespace whatnext
