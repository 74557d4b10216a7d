// What integrate_dense (integrate.hpp) stands on: the result of a piece (Crossing), the output
// grid, the step control's helpers, the stepper and its settings (DenseSettings), and one piece
// of dense integration in its named stages (detail::DensePiece). The guards' conventions are
// those of integrate.hpp.
#pragma once

#include <array>
#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <tuple>
#include <type_traits>
#include <utility>

#include <boost/math/tools/toms748_solve.hpp>
#include <boost/numeric/odeint.hpp>

#include "whatnext/step_stats.hpp"

namespace whatnext {

struct Crossing {
  enum Kind { event, end, non_finite, step_limit };
  Kind kind = end;
  int guard = -1;  // the guard that fired (kind == event)
  double t = 0.0;  // where the piece ended (for non_finite and step_limit: the last good time)
  // How fast the guard passed zero (its secant over the step, per second; infinite where not
  // known). An event's time is as uncertain as the guard's value divided by this.
  double rate = std::numeric_limits<double>::infinity();
  // How far the event's time may be off for the integrator's error alone [s]: the change of the
  // guard when every state component moves by the error the tolerance allows per step, over the
  // rate (0 where the rate is not known). A slow crossing is an uncertain one.
  double uncertainty = 0.0;
};

namespace detail {
// x^n for the small orders of a guard's start (pow is far slower).
inline double power(double x, int n) {
  double r = 1.0;
  for (int i = 0; i < n; ++i) r *= x;
  return r;
}

template <class State>
bool finite(const State& y) {
  for (double v : y)
    if (!std::isfinite(v)) return false;
  return true;
}
}  // namespace detail

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
// See Crossing::uncertainty. Two directions of the allowed error (all components one way; every
// other one the other way) so that no guard's dependence cancels in both.
// g: the guard's value at y where the root finder has it already (NaN: evaluated here).
template <class System>
double time_uncertainty(const System& sys, const typename System::state_type& y, int guard, double tolerance,
                        double rate, double g) {
  if (!(std::fabs(rate) < std::numeric_limits<double>::infinity()) || rate == 0.0) return 0.0;
  if (std::isnan(g)) g = sys.guard(y, guard);
  double change = 0.0;
  for (int pattern = 0; pattern < 2; ++pattern) {
    typename System::state_type yp = y;
    for (std::size_t i = 0; i < yp.size(); ++i) {
      const double sign = pattern == 1 && (i % 2) ? -1.0 : 1.0;
      yp[i] += sign * tolerance * (1.0 + std::fabs(y[i]));
    }
    change = std::fmax(change, std::fabs(sys.guard(yp, guard) - g));
  }
  return change / std::fabs(rate);
}

// The last values a root finder was given (see fired_end).
struct RecentValues {
  static constexpr int kSize = 16;
  std::array<double, kSize> t, value;  // the first count are set
  int count = 0, next = 0;
  void add(double tt, double v) {
    t[next] = tt, value[next] = v;
    next = (next + 1) % kSize;
    if (count < kSize) ++count;
  }
  bool find(double tt, double& v) const {
    for (int k = 0; k < count; ++k) {
      if (t[k] == tt) {
        v = value[k];
        return true;
      }
    }
    return false;
  }
};

// Where a guard f fires on [a, b] (f(a) = fa < 0 <= fb = f(b)): TOMS 748's bracket, to
// time_tolerance, and its end where f >= 0, with f's value there (NaN where f was not evaluated
// there). The values TOMS 748 was given are kept: it returns only the bracket's ends, and picking
// the end, or the event's time uncertainty, would otherwise evaluate the guard there again.
template <class F>
std::pair<double, double> fired_end(const F& f, double a, double b, double fa, double fb,
                                    double time_tolerance) {
  RecentValues seen;
  auto kept = [&seen, &f](double t) {
    const double v = f(t);
    seen.add(t, v);
    return v;
  };
  std::uintmax_t iterations = 200;
  auto stop = [&](double x, double y) { return std::fabs(y - x) <= time_tolerance; };
  const auto bracket = boost::math::tools::toms748_solve(kept, a, b, fa, fb, stop, iterations);
  double value = 0.0;
  if (!seen.find(bracket.first, value)) value = kept(bracket.first);
  if (value >= 0.0) return {bracket.first, value};
  if (!seen.find(bracket.second, value)) value = std::numeric_limits<double>::quiet_NaN();
  return {bracket.second, value};
}

// The step a piece starts with: Hairer, Norsett and Wanner's estimate (Solving Ordinary
// Differential Equations I, II.4), in the step control's norm (|v_i| / (tolerance (1 + |x_i|)),
// the largest). From the flow at the start and after a small Euler step it guesses the step whose
// fifth-order error is a hundredth of the tolerance, so that a piece starts near its own step
// size instead of climbing to it tenfold per step (a third of a sweep's steps were such climbs
// after the events). Never longer than that Euler step (they allow 100 times it: that saved
// 0.8 % more of a sweep's instructions, and a fast oscillator's first step at a tight tolerance
// was then rejected). Two evaluations of the flow.
template <class State, class Flow>
double starting_step(const Flow& flow, const State& x, double t, double tolerance, double max_dt) {
  auto norm = [&](const State& v) {
    double n = 0.0;
    for (std::size_t i = 0; i < v.size(); ++i)
      n = std::fmax(n, std::fabs(v[i]) / (tolerance * (1.0 + std::fabs(x[i]))));
    return n;
  };
  State f0, x1, f1;
  flow(x, f0, t);
  const double d0 = norm(x), d1 = norm(f0);
  double h0 = std::fmin(max_dt, d0 < 1e-5 || d1 < 1e-5 ? 1e-6 : 0.01 * d0 / d1);
  double d2 = std::numeric_limits<double>::quiet_NaN();
  // (An Euler step too long for the motion's charts gives no number: a shorter one is tried.)
  for (int tries = 0; tries < 4; ++tries) {
    for (std::size_t i = 0; i < x.size(); ++i) x1[i] = x[i] + h0 * f0[i];
    flow(x1, f1, t + h0);
    for (std::size_t i = 0; i < x.size(); ++i) f1[i] -= f0[i];
    d2 = norm(f1) / h0;
    if (std::isfinite(d2)) break;
    h0 *= 0.01;
  }
  if (!std::isfinite(d2)) return h0;
  const double d = std::fmax(d1, d2);
  if (d == 0.0) return max_dt;  // a motion that does not change: any step is exact
  return std::fmin(max_dt, std::fmin(h0, std::pow(0.01 / d, 0.2)));
}

// Boost.Odeint's step control, but a step may grow tenfold after an easy one (Hairer and
// Wanner's DOPRI5 default) instead of fivefold: where a contact was just released the motion
// restarts with a 1 us step, and climbing back from it is a large share of a short run.
class StepGrowth : public boost::numeric::odeint::default_step_adjuster<double, double> {
 public:
  explicit StepGrowth(double max_dt = 0.0)
      : boost::numeric::odeint::default_step_adjuster<double, double>(max_dt), max_dt_(max_dt) {}
  double increase_step(double dt, double error, int order) const {
    if (error < 0.5) {
      // The factor below stays <= 10. Dormand-Prince's order is 5: its floor is computed once
      // (a pow per step was 1 % of a sweep), the same number.
      static const double floor5 = std::pow(10.0 / 0.9, -5);
      error = std::fmax(order == 5 ? floor5 : std::pow(10.0 / 0.9, -order), error);
      dt *= 0.9 * std::pow(error, -1.0 / order);
      if (max_dt_ > 0.0) dt = std::fmin(dt, max_dt_);
    }
    return dt;
  }

 private:
  double max_dt_;
};

// A contact released on its acceleration (order 2: gap ~ L tau^2, L < 0 as a guard) whose gap
// closes again while it is still within rounding of zero: its value cannot say where, but its rate
// can (the rate's terms are velocities, resolved far better than the gap's positions), and so can
// a value that has already come out clearly positive. With g = L tau^2 + C tau^3 through the guard
// g or its rate r at tau: C = (g - L tau^2) / tau^3 or (r - 2 L tau) / (3 tau^2), and the gap
// closes at tau* = -L / C. Returns tau* when it is within tau, else -1 (not closing yet, or not
// such a guard). Without this a rope that tightened again within microseconds of going slack was
// found only where the step after next ended (11 us after, docs/model.md §4).
inline double closes_again(int order, double lead, double tau, double g, double floor, double rate) {
  if (order != 2 || !(lead < -1e-200) || !(tau > 0.0)) return -1.0;
  double c;
  if (g > floor) {
    c = (g - lead * tau * tau) / (tau * tau * tau);
  } else if (std::isfinite(rate) && rate > 0.0) {
    c = (rate - 2.0 * lead * tau) / (3.0 * tau * tau);
  } else {
    return -1.0;
  }
  if (!(c > 0.0)) return -1.0;
  const double closing = -lead / c;
  if (closing <= tau) return closing;
  return g > floor ? tau : -1.0;
}
}  // namespace detail

// The adaptive integrator's stepper: embedded Dormand-Prince 5(4) with error control (tolerance
// absolute and relative, per component) and dense output (Boost.Odeint).
template <class State>
using Dopri5Dense =
    boost::numeric::odeint::dense_output_runge_kutta<boost::numeric::odeint::controlled_runge_kutta<
        boost::numeric::odeint::runge_kutta_dopri5<State>,
        boost::numeric::odeint::default_error_checker<double, boost::numeric::odeint::array_algebra,
                                                      boost::numeric::odeint::default_operations>,
        detail::StepGrowth, boost::numeric::odeint::initially_resizer,
        boost::numeric::odeint::explicit_error_stepper_fsal_tag>>;

// How a dense piece is integrated: one set, given to the stepper's factory and to integrate_dense
// (as Odeint's steppers keep theirs).
struct DenseSettings {
  double tolerance = 0.0;       // the step control's, absolute and relative per component
  double max_dt = 0.0;          // the longest step (keeps brief guard excursions visible)
  double time_tolerance = 0.0;  // an event's time is located to this [s]
  std::int64_t max_steps = 0;   // steps after which the piece gives up (Crossing::step_limit)
};

template <class State>
Dopri5Dense<State> make_dopri5(const DenseSettings& set) {
  using controlled = typename Dopri5Dense<State>::controlled_stepper_type;
  return Dopri5Dense<State>(controlled(typename controlled::error_checker_type(set.tolerance, set.tolerance),
                                       detail::StepGrowth(set.max_dt)));
}

namespace detail {
// The earliest guard found to fire in a step so far: where, how fast it passed zero, and its value
// there (NaN where not known).
struct Hit {
  int guard = -1;
  double t = 0.0, rate = std::numeric_limits<double>::infinity();
  double g = std::numeric_limits<double>::quiet_NaN();
  void offer(int i, double ti, double rate_i, double g_i) {
    if (guard < 0 || ti < t) guard = i, t = ti, rate = rate_i, g = g_i;
  }
};

// One piece of integrate_dense, in its stages: start (the guards' starts and the first step),
// then per step take_step, look_at_guards (released_guard, touch, crossing for each guard),
// and either stop at the earliest event, or emit the samples and go on. The state the stages
// share is the stepper's dense output and the guards' values at the step's ends.
template <class Stepper, class System, class Sample>
class DensePiece {
  using state_type = typename System::state_type;
  using guard_type = typename System::guard_type;
  static constexpr std::size_t kGuards = std::tuple_size<guard_type>::value;
  // Where a contact was just released, the first step is this short (see start).
  static constexpr double kReleasedStep = 1e-6;

 public:
  DensePiece(Stepper& stepper, const System& sys, const DenseSettings& set, OutputGrid& grid, Sample& sample,
             StepStats& stats)
      : stepper_(stepper), sys_(sys), set_(set), grid_(grid), sample_(sample), stats_(stats) {}

  Crossing run(state_type& y, double& t, double t_end) {
    start(y, t);
    for (bool first = true;; first = false) {
      in_first_ = first;
      if (!take_step(y, t)) return stop_;
      const Hit hit = look_at_guards();
      if (hit.guard >= 0 && hit.t <= t_end) return stop_at_event(hit, y, t);
      emit_samples(std::fmin(tb_, t_end));
      g_prev_ = g0_;
      t_prev_ = ta_;
      g0_ = g1_;
      d0_ = d1_;
      if (tb_ >= t_end) return stop_at_end(y, t, t_end);
      if (released_) {
        released_ = any_armed();
        if (!released_ && natural_ > 10.0 * (tb_ - ta_)) stepper_.initialize(y1_, tb_, natural_);
      }
    }
  }

 private:
  // The guards' starts (a guard at zero is searched as g / (t - t0)^order, see the top) and the
  // stepper's first step.
  void start(const state_type& y, double t) {
    t0_ = t_prev_ = t;
    sys_.guards(y, g0_, &d0_);
    for (std::size_t i = 0; i < kGuards; ++i) {
      const auto s = sys_.guard_start(static_cast<int>(i));
      order_[i] = s.order;
      floor_[i] = s.floor;
      lead_[i] = s.lead;
      armed_[i] = s.order > 0;
      if (s.order > 0) {
        g0_[i] = s.lead;  // the limit of g / (t - t0)^order at t0
        noise_time_[i] = std::pow(1e-3 * s.floor / std::fabs(s.lead), 1.0 / s.order);
      }
    }
    // The whole state's, unless the stepper has its own (ballistic.hpp).
    if constexpr (requires { stepper_.starting_step(sys_, y, t, set_.tolerance, set_.max_dt); }) {
      natural_ = stepper_.starting_step(sys_, y, t, set_.tolerance, set_.max_dt);
    } else {
      natural_ = starting_step(sys_, y, t, set_.tolerance, set_.max_dt);
    }
    // Where a contact was just released, the first step is short: its gap may close again within
    // what would be the first step, by less than the dense output's error over so long a step.
    // The steps grow from there while it is still within rounding of zero (what tells a gap that
    // closes again holds for such short times only), and once every released contact is clearly
    // open the stepper starts again there with the motion's own step (run).
    released_ = any_armed();
    stepper_.initialize(y, t, released_ ? std::fmin(natural_, kReleasedStep) : natural_);
  }

  bool any_armed() const {
    for (bool a : armed_)
      if (a) return true;
    return false;
  }

  // One step and the guards at its end; false (with the piece's end in stop_) where the motion is
  // not finite or the steps are used up.
  bool take_step(state_type& y, double& t) {
    std::pair<double, double> interval;
    try {
      interval = stepper_.do_step(std::cref(sys_));
    } catch (const std::exception&) {  // the step size could not be controlled: a non-finite flow
      stop_ = {Crossing::non_finite, -1, stepper_.current_time()};
      return false;
    }
    ++stats_.steps;
    // The guards are looked at over the whole step, wherever t_end cuts it: an event's time is the
    // motion's, not the run's length's (one after t_end is no event of this run).
    ta_ = interval.first, tb_ = interval.second;
    y1_ = stepper_.current_state();
    if (!finite(y1_)) {
      stop_ = {Crossing::non_finite, -1, ta_};
      return false;
    }
    if (++steps_ > set_.max_steps) {
      stepper_.calc_state(ta_, y);
      t = ta_;
      stop_ = {Crossing::step_limit, -1, ta_};
      return false;
    }
    sys_.guards(y1_, g1_, &d1_);
    return true;
  }

  // The earliest guard that fired over [ta, tb]: a released contact closing again, a touch of zero
  // between two negative ends, or a sign change.
  Hit look_at_guards() {
    Hit hit;
    hit.t = tb_;
    for (std::size_t i = 0; i < kGuards; ++i) {
      if (armed_[i]) {
        released_guard(i, hit);
      } else {
        touch(i, hit);
      }
    }
    if (tb_ > ta_) {
      for (std::size_t i = 0; i < kGuards; ++i) crossing(i, hit);
    }
    return hit;
  }

  double guard_at(std::size_t i, double tt) {
    state_type yy;
    stepper_.calc_state(tt, yy);
    ++stats_.root_evaluations;
    return sys_.guard(yy, static_cast<int>(i));
  }

  // A guard that started the piece at zero and has not yet clearly opened: it is disarmed once it
  // has, or its closing again is located (g1 is then set so that it is no ordinary crossing).
  void released_guard(std::size_t i, Hit& hit) {
    const double ta = ta_, tb = tb_;  // (held here: the guard calls below could change members)
    const bool first = in_first_;
    own_from_[i] = steps_;
    // Within rounding of the start only the guard's rate can tell (its value is as expanded).
    const bool noise = first && order_[i] > 0 && tb - t0_ < noise_time_[i];
    if (!noise && g1_[i] < -floor_[i]) {
      armed_[i] = false;  // clearly open: an ordinary guard from here on
      return;
    }
    // Still zero within rounding, or closed again before it ever opened beyond it.
    const double g_seen = noise ? 0.0 : g1_[i];
    const double closes = closes_again(order_[i], lead_[i], tb - t0_, g_seen, floor_[i], d1_[i]);
    if (closes > 0.0) {
      double t_close = std::fmax(ta, t0_ + closes), rate_close = std::numeric_limits<double>::infinity();
      double g_close = std::numeric_limits<double>::quiet_NaN();
      // The expansion only points at the closing (its cubic is off by the next term, microseconds
      // a hundred microseconds out): where the guard's own values bracket it, it is located on
      // the dense output like any crossing, from the gap's deepest point (2/3 of the way for the
      // cubic) to the step's end, so its time does not depend on where the step happened to end.
      const double lo = std::fmax(ta, t0_ + (2.0 / 3.0) * closes);
      if (!noise && g1_[i] >= 0.0 && lo < tb) {
        const double g_lo = guard_at(i, lo);
        if (g_lo < 0.0) {
          const auto end = fired_end([&](double t2) { return guard_at(i, t2); }, lo, tb, g_lo, g1_[i],
                                     set_.time_tolerance);
          if (std::fabs(end.first - t_close) <= 0.5 * closes) {
            t_close = end.first, rate_close = (g1_[i] - g_lo) / (tb - lo), g_close = end.second;
          }
        }
      }
      hit.offer(static_cast<int>(i), t_close, rate_close, g_close);
      g1_[i] = -std::numeric_limits<double>::min();  // found: not an ordinary crossing
    } else if (noise || g1_[i] <= floor_[i]) {
      g1_[i] = -std::numeric_limits<double>::min();  // still zero: not a crossing
    }
  }

  // Negative at both ends: a touch in between? Peak of the Hermite cubic on [ta, tb] (not in the
  // first step of a guard that started at zero: its g0 is the scaled lead, not a value).
  void touch(std::size_t i, Hit& hit) {
    const double ta = ta_, tb = tb_;  // (held here: the guard calls below could change members)
    const bool first = in_first_;
    if (!(g0_[i] < 0.0 && g1_[i] < 0.0) || !(tb > ta) || (first && order_[i] > 0)) return;
    const double h = tb - ta;
    double r0 = d0_[i], r1 = d1_[i];
    if ((std::isnan(r0) || std::isnan(r1)) && !rates_from_values(i, r0, r1)) return;
    const double s_peak = hermite_peak(g0_[i], g1_[i], h, r0, r1);
    if (!(s_peak > 0.0 && s_peak < 1.0)) return;
    // Look at the real guard around the predicted peak; if it is >= 0 there, the touch is
    // located between ta and that point like any crossing.
    for (double frac : {s_peak, 0.5 * s_peak, 0.5 * (1.0 + s_peak)}) {
      const double tt = ta + frac * h;
      const double gv = guard_at(i, tt);
      if (gv >= 0.0) {
        const auto end =
            fired_end([&](double t2) { return guard_at(i, t2); }, ta, tt, g0_[i], gv, set_.time_tolerance);
        hit.offer(static_cast<int>(i), end.first, (gv - g0_[i]) / (tt - ta), end.second);
        return;
      }
    }
  }

  // No rate: the slopes at ta and tb of the parabola through the last three values, p(t) = g_prev
  // + s1 (t - t_prev) + k (t - t_prev)(t - ta); false where none is needed or none can be had.
  bool rates_from_values(std::size_t i, double& r0, double& r1) const {
    const double h = tb_ - ta_, h1 = ta_ - t_prev_;
    if (steps_ - own_from_[i] < 3 || g1_[i] == g0_[i] || !(h1 > 0.0))
      return false;  // (equal: not in use, or still)
    const double hi = g0_[i] > g1_[i] ? g0_[i] : g1_[i], lo = g0_[i] > g1_[i] ? g1_[i] : g0_[i];
    // Over [ta, tb] the parabola exceeds the chord by at most |k| h^2 / 4, and |k| (h1 + h) is at
    // most |g1 - g0| / h + |g0 - g_prev| / h1: where even that stays below half the guard's way to
    // zero (the test below), no peak can come near it (NaN: a value that is not finite).
    const double room =
        4.0 * h1 * (hi - 0.5 * lo) + h1 * std::fabs(g1_[i] - g0_[i]) + h * std::fabs(g0_[i] - g_prev_[i]);
    if (!(room >= 0.0)) return false;
    const double s1 = (g0_[i] - g_prev_[i]) / h1, k = ((g1_[i] - g0_[i]) / h - s1) / (h1 + h);
    r0 = s1 + k * h1;
    r1 = s1 + k * (h1 + 2.0 * h);
    return true;
  }

  // Where the cubic Hermite interpolant of values g0, g1 and rates r0, r1 over a step h peaks, as a
  // fraction of the step, if it comes near zero there (else -1).
  static double hermite_peak(double g0, double g1, double h, double r0, double r1) {
    const double hi = g0 > g1 ? g0 : g1, lo = g0 > g1 ? g1 : g0;
    // The cubic is at most the larger end value plus (4/27) h (|r0| + |r1|) (the largest the
    // slopes' basis functions get): where that stays below half of both ends, so does any peak,
    // and the test below would pass it by without its square root and divisions (0.16 for 4/27
    // and the factor on the right leave room for rounding).
    if (hi + 0.16 * h * (std::fabs(r0) + std::fabs(r1)) < 0.5 * (1.0 + 1e-9) * lo) return -1.0;
    const double a = 6.0 * (g0 - g1) + 3.0 * h * (r0 + r1);  // p'(s) = a s^2 + b s + c
    const double b = 6.0 * (g1 - g0) - 2.0 * h * (2.0 * r0 + r1);
    const double c = h * r0;
    double s_peak = -1.0;
    if (std::fabs(a) < 1e-300) {
      if (b < 0.0) s_peak = -c / b;
    } else {
      const double disc = b * b - 4.0 * a * c;
      if (disc >= 0.0) {
        const double q = -0.5 * (b + std::copysign(std::sqrt(disc), b));
        for (double root : {q / a, q != 0.0 ? c / q : -1.0}) {
          if (root > 0.0 && root < 1.0 && 2.0 * a * root + b < 0.0) s_peak = root;  // a maximum
        }
      }
    }
    if (!(s_peak > 0.0 && s_peak < 1.0)) return -1.0;
    const double s2 = s_peak * s_peak, s3 = s2 * s_peak;
    const double peak = (2 * s3 - 3 * s2 + 1) * g0 + (s3 - 2 * s2 + s_peak) * h * r0 +
                        (-2 * s3 + 3 * s2) * g1 + (s3 - s2) * h * r1;
    if (peak < 0.5 * g0 && peak < 0.5 * g1) return -1.0;  // not even close to zero
    return s_peak;
  }

  // A sign change over [ta, tb], located on the dense output (in the first step, a guard that
  // started at zero as g / (t - t0)^order).
  void crossing(std::size_t i, Hit& hit) {
    const double ta = ta_, tb = tb_;  // (held here: the guard calls below could change members)
    const bool first = in_first_;
    if (!(g0_[i] < 0.0 && g1_[i] >= 0.0)) return;
    const int p = first ? order_[i] : 0;
    const double scale_b = p > 0 ? power(tb - t0_, p) : 1.0;
    auto f = [&](double tt) {
      if (p > 0 && tt - t0_ < noise_time_[i]) return g0_[i];
      const double gi = guard_at(i, tt);
      return p > 0 ? gi / power(tt - t0_, p) : gi;
    };
    const auto end = fired_end(f, ta, tb, g0_[i], g1_[i] / scale_b, set_.time_tolerance);
    // (g scaled where p > 0, where the rate and so the uncertainty are not known)
    hit.offer(static_cast<int>(i), end.first,
              p > 0 ? std::numeric_limits<double>::infinity() : (g1_[i] - g0_[i]) / (tb - ta), end.second);
  }

  void emit_samples(double t_hi) {
    sample_until<System>(
        grid_, t_hi, [this](double tt, state_type& out) { stepper_.calc_state(tt, out); }, sample_);
  }

  Crossing stop_at_event(const Hit& hit, state_type& y, double& t) {
    emit_samples(hit.t);
    stepper_.calc_state(hit.t, y);
    t = hit.t;
    return {Crossing::event, hit.guard, hit.t, hit.rate,
            time_uncertainty(sys_, y, hit.guard, set_.tolerance, hit.rate, hit.g)};
  }

  Crossing stop_at_end(state_type& y, double& t, double t_end) {
    if (tb_ > t_end) {
      stepper_.calc_state(t_end, y);
    } else {
      y = y1_;
    }
    t = t_end;
    return {Crossing::end, -1, t_end};
  }

  Stepper& stepper_;
  const System& sys_;
  const DenseSettings& set_;
  OutputGrid& grid_;
  Sample& sample_;
  StepStats& stats_;
  Crossing stop_;  // where take_step ended the piece
  double t0_ = 0.0, natural_ = 0.0;
  bool released_ = false, in_first_ = true;
  std::int64_t steps_ = 0;
  // The step [ta, tb] just taken, its end state, and the start of the one before.
  double ta_ = 0.0, tb_ = 0.0, t_prev_ = 0.0;
  // (Not cleared: every piece writes them before it reads them, and a piece is often short.)
  state_type y1_;
  // The guards and their rates at ta and tb, and at t_prev for those whose rates are not known.
  guard_type g0_, g1_, d0_, d1_;
  guard_type g_prev_{};
  std::array<int, kGuards> order_{};
  std::array<double, kGuards> floor_{}, noise_time_{}, lead_{};
  std::array<bool, kGuards> armed_{};
  // The step from whose end on the guard's values are its own (not an armed guard's lead, nor its
  // rounding written as zero): the parabola in rates_from_values needs three of them.
  std::array<std::int64_t, kGuards> own_from_{};
};
}  // namespace detail

}  // namespace whatnext
