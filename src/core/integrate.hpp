// Generic integrators with event location. They know nothing of seesaws: a System supplies
//   using state_type = std::array<double, N>;  using guard_type = std::array<double, G>;
//   void operator()(const state_type& y, state_type& dy, double t) const;   // the flow
//   void guards(const state_type& y, guard_type& g, guard_type* dg) const;  // event functions,
//                                       and their rates dg/dt if dg is given (NaN: not known)
//   double guard(const state_type& y, int i) const;  // event function i alone (root finding:
//                                       it may skip what only the others need)
//   S guard_start(int i) const;  // S has .order, .lead and .floor, see below
// A guard fires when its value goes from negative to >= 0. Each call integrates one smooth piece
// from t up to the first firing guard or t_end and hands samples on an output grid to a callback.
//
// A guard may start a piece at zero: a contact just released, whose gap is zero and opens. The
// System then says how it leaves zero, g(t) ~ lead (t - t0)^order with lead < 0, and the guard is
// searched as g(t) / (t - t0)^order in the first step: negative at the start by construction, so
// a contact that closes again however soon is found, at any tolerance, and never the start itself.
// Such a guard also has a floor: while |g| <= floor it is still "zero" (rounding, or a contact
// that neither opens nor closes), and it fires only when it rises above the floor. Right after
// the start, where lead (t - t0)^order is below a thousandth of the floor, the expansion is
// trusted over the computed value, which is rounding there.
//
// A guard that is negative at both ends of a step may still have touched zero in between (a lid
// that dips onto the box and rises again). Where the System knows a guard's rate, the cubic
// Hermite interpolant of its values and rates shows such an excursion, whichever way the guard
// slopes at the ends (a rope let go with hardly any pull drifts slack, comes back and tightens
// for a moment, all within one step: falling at both ends), and the guard is then looked at on
// the dense output where the interpolant peaks. Where the rate is not known (a closed contact's
// force), the parabola through the guard's values at the last three step ends stands in for it:
// an arm whose push dips below zero for 2 ms in the middle of a step (the sandbag hopping) shows
// there as a peak near zero.
#pragma once

#include <cstddef>
#include <type_traits>
#include <utility>

#include "dense_piece.hpp"
#include "whatnext/step_stats.hpp"

namespace whatnext {

// A piece with a dense-output stepper: Dormand-Prince on the whole state (integrate_adaptive), or
// one that knows part of the motion in closed form (simulate.cpp). The stepper has Boost.Odeint's
// dense-output interface: initialize(y, t, dt), do_step(system) -> (t_old, t_new) (throws where
// the step size cannot be controlled), calc_state(t, y), current_state(), current_time(). Guards
// are checked at every step end; a sign change is located on the dense output with TOMS 748 to
// set.time_tolerance, and the state is returned at the end of the bracket where the guard has fired.
template <class Stepper, class System, class Sample>
Crossing integrate_dense(Stepper& stepper, const System& sys, typename System::state_type& y, double& t,
                         double t_end, const DenseSettings& set, OutputGrid& grid, Sample&& sample,
                         StepStats& stats) {
  detail::DensePiece<Stepper, System, std::remove_reference_t<Sample>> piece(stepper, sys, set, grid, sample,
                                                                             stats);
  return piece.run(y, t, t_end);
}

// Dormand-Prince on the whole state; see integrate_dense.
template <class System, class Sample>
Crossing integrate_adaptive(const System& sys, typename System::state_type& y, double& t, double t_end,
                            const DenseSettings& set, OutputGrid& grid, Sample&& sample, StepStats& stats) {
  auto stepper = make_dopri5<typename System::state_type>(set);
  return integrate_dense(stepper, sys, y, t, t_end, set, grid, std::forward<Sample>(sample), stats);
}

// Fixed-step explicit Euler (the paper's method) or classical RK4. An event is found in the step
// in which its guard is first seen to have fired (of several, the one whose crossing comes first)
// and placed where the guard, interpolated linearly over the step, crosses zero: the state there is
// the step's linear interpolation, so a contact is not entered by a whole step's overshoot.
// Samples are the step-end states at or after each grid time, one per step, and the start.
template <class Stepper, class System, class Sample>
Crossing integrate_fixed(const System& sys, typename System::state_type& y, double& t, double t_end,
                         double dt, OutputGrid& grid, Sample&& sample, StepStats& stats) {
  using guard_type = typename System::guard_type;
  Stepper stepper;
  guard_type g0, g1;
  sys.guards(y, g0, nullptr);
  constexpr std::size_t kGuards = std::tuple_size<guard_type>::value;
  std::array<double, kGuards> floor{};
  std::array<int, kGuards> order{};
  std::array<bool, kGuards> armed{};
  for (std::size_t i = 0; i < g0.size(); ++i) {
    const auto s = sys.guard_start(static_cast<int>(i));
    armed[i] = s.order > 0;
    order[i] = s.order;
    floor[i] = s.floor;
    if (s.order > 0) g0[i] = s.lead;  // zero now, negative just after: see above
  }
  const double t0 = t;
  if (grid.step > 0.0 && grid.next == 0) {  // the run's start (the first row was the first step's end)
    sample(t, y);
    ++grid.next;
  }
  for (bool first = true;; first = false) {
    const double h = std::fmin(dt, t_end - t);
    const double t_before = t;
    const typename System::state_type y_before = y;
    stepper.do_step(std::cref(sys), y, t, h);
    t = (t_end - t <= dt) ? t_end : t + h;
    ++stats.steps;
    if (!detail::finite(y)) return {Crossing::non_finite, -1, t_before};
    sys.guards(y, g1, nullptr);
    for (std::size_t i = 0; i < g0.size(); ++i) {
      if (!armed[i]) continue;
      if (g1[i] < -floor[i]) {
        armed[i] = false;
      } else if (g1[i] <= floor[i]) {
        g1[i] = -std::numeric_limits<double>::min();
      }
    }
    int hit = -1;
    double best = 2.0;
    for (std::size_t i = 0; i < g0.size(); ++i) {
      if (!(g0[i] < 0.0 && g1[i] >= 0.0)) continue;
      // A guard that started at zero compares its lead with g / (t - t0)^order.
      const double g_end = first && order[i] > 0 ? g1[i] / detail::power(t - t0, order[i]) : g1[i];
      const double frac = g0[i] / (g0[i] - g_end);
      if (frac < best) best = frac, hit = static_cast<int>(i);
    }
    if (hit >= 0) {
      // The event's state: the step's linear interpolation where the guard crosses. The samples
      // of this step wait for the next piece, which starts from the event.
      for (std::size_t j = 0; j < y.size(); ++j) y[j] = y_before[j] + best * (y[j] - y_before[j]);
      t = t_before + best * h;
      return {Crossing::event, hit, t};
    }
    // One row per step for all the grid times it passed (a step longer than run.output_step wrote
    // the same row, with the same time, once for each), allowing for t's rounding.
    if (grid.step > 0.0 && grid.time() <= t + 1e-9 * dt) {
      sample(t, y);
      while (grid.time() <= t + 1e-9 * dt) ++grid.next;
    }
    if (t >= t_end) return {Crossing::end, -1, t_end};
    g0 = g1;
  }
}

}  // namespace whatnext
