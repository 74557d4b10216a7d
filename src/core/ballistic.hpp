// Pieces in which the sandbag flies freely: falling before it lands, or on a massless seesaw with
// the rope slack (docs/model.md, "Free fall in closed form"). Its motion is then a parabola, known
// exactly, and so is the balloon's while it rises freely without drag; the lid, swinging freely
// about its hinge, is a pendulum, taken by its Taylor series (pendulum.hpp, docs/model.md "The
// lid's free swing in series"). Only a small balloon sliding along the lid is left to integrate,
// by the adaptive integrator's own Dormand-Prince on the four numbers that move.
#pragma once

#include <array>
#include <cmath>
#include <stdexcept>
#include <utility>

#include "integrate.hpp"
#include "model.hpp"
#include "pendulum.hpp"

namespace whatnext {

// A dense-output stepper (integrate_dense's interface) for such a piece. Where every part is known
// in closed form or in series the steps are as long as the series reaches and the lid's turn
// allows (kLidArc; at most max_dt, the guards' bound), growing tenfold from a short start as
// Dormand-Prince's would where it meets no error; the state anywhere inside a step is exact to
// rounding. Otherwise the lid and the balloon
// take Dormand-Prince's steps on their four numbers (the sandbag's error estimate was rounding,
// below the step growth's limit, so these are the whole state's steps and values, bit for bit).
class BallisticStepper {
 public:
  // The lid's angle and rate, the balloon's height and rate: what moves besides the sandbag.
  using Moving = std::array<double, 4>;
  static constexpr std::array<int, 4> kMoving = {slot::phi_l, slot::dphi_l, slot::balloon_h, slot::balloon_v};

  // Whether the piece that starts in (d, y) is such a piece: the sandbag in Cartesian free fall on
  // a massless seesaw, no damper, drag or friction (whose losses follow the lid and the seesaw, and
  // vanish where a slip starts from rest: the check below cannot see them), and the model's flow
  // there the free fall's (checked, so that a contact added to the model later, say a floor the
  // sandbag rests on, is never taken for one).
  static bool applies(const Model& model, const Scenario& sc, const Discrete& d, const State& y,
                      Workspace* ws = nullptr) {
    const Machine& m = sc.machine;
    if (d.polar() || d.heavy || d.stretched || m.heavy_seesaw() || m.pivot_damping > 0.0 ||
        m.lid_hinge_damping > 0.0 || m.balloon_drag_rate() > 0.0 || m.has_friction()) {
      return false;
    }
    State dy;
    ws ? model.flow(d, y, dy, *ws) : model.flow(d, y, dy);
    if (!(dy[slot::x] == y[slot::vx] && dy[slot::h] == y[slot::vh] && dy[slot::vx] == 0.0 &&
          dy[slot::vh] == -m.gravity)) {
      return false;
    }
    for (int i = 0; i < static_cast<int>(dy.size()); ++i) {
      const bool own = i == slot::x || i == slot::h || i == slot::vx || i == slot::vh;
      bool moving = false;
      for (int k : kMoving) moving = moving || i == k;
      if (!own && !moving && dy[i] != 0.0) return false;
    }
    return true;
  }

  // y: the piece's start, where the model's flow tells which parts move and how (closed_forms).
  // ws: the run's workspace (workspace.hpp), or null.
  BallisticStepper(const Model& model, const Discrete& d, const State& y, double gravity,
                   const DenseSettings& set, Workspace* ws = nullptr)
      : model_(&model),
        ws_(ws),
        d_(&d),
        g_(gravity),
        // The series' own error, far below the integrator's (the other pieces'), and not below rounding.
        series_error_(std::fmax(1e-3 * set.tolerance, 1e-16)),
        lid_arc_(kLidArc * std::fmin(1.0, std::pow(set.tolerance / kLidArcTolerance, 0.2))),
        growth_(set.max_dt),
        inner_(make_dopri5<Moving>(set)) {
    exact_ = closed_forms(y);
  }
  BallisticStepper(const BallisticStepper&) = delete;  // flow_ points at this one
  BallisticStepper& operator=(const BallisticStepper&) = delete;

  void initialize(const State& y, double t, double dt) {
    y0_ = y;
    t0_ = t;
    current_ = y;
    if (exact_) {
      t_ = t, dt_ = dt;
      return;
    }
    inner_.initialize(moving_of(y), t, dt);
  }
  // In closed form the longest step (the series and max_dt bound it); else the whole state's
  // starting step, so that the steps stay Dormand-Prince's.
  template <class System>
  double starting_step(const System& sys, const State& y, double t, double tolerance, double max_dt) const {
    return exact_ ? max_dt : detail::starting_step(sys, y, t, tolerance, max_dt);
  }
  template <class System>
  std::pair<double, double> do_step(System /*whole state's: the flow below is its restriction*/) {
    if (exact_) {
      // As long a step as the lid's series reaches (any, if it rests), growing as Dormand-Prince's
      // steps grow where their error estimate is nil.
      const double t_old = t_;
      double h = dt_;
      if (lid_swings_) {
        const double phi = current_[slot::phi_l], rate = current_[slot::dphi_l];
        series_.expand(w_, phi, rate);
        // The guards are looked at every step end: a touch in between is seen by their cubic
        // through the ends, which follows the lid's circle only over a short arc.
        for (double turn = std::fabs(series_.angle(h) - phi); turn > lid_arc_;
             turn = std::fabs(series_.angle(h) - phi))
          h *= 0.9 * lid_arc_ / turn;
        const double angle_error = series_error_ * (1.0 + std::fabs(phi)),
                     rate_error = series_error_ * (1.0 + std::fabs(rate));
        while (h > 0.0 && !series_.reaches(h, angle_error, rate_error)) h *= 0.5;
        // A series that is not finite (overflow) reaches nowhere: integrate_dense takes the throw
        // for a motion that turned non-finite, rather than the halving going on for ever.
        if (!(h > 0.0)) throw std::runtime_error("the lid's series is not finite");
      }
      series_t_ = t_old;
      t_ += h;
      dt_ = growth_.increase_step(h, 0.0, 5);
      current_ = exact_at(t_);
      return {t_old, t_};
    }
    const std::pair<double, double> interval = inner_.do_step(std::cref(flow_));
    current_ = at(interval.second, inner_.current_state());
    return interval;
  }
  void calc_state(double t, State& out) const {
    if (exact_) {
      out = exact_at(t);
      return;
    }
    Moving r;
    inner_.calc_state(t, r);
    out = at(t, r);
  }
  const State& current_state() const { return current_; }
  double current_time() const { return exact_ ? t_ : inner_.current_time(); }

 private:
  // The model's flow at y, with the run's memos where there are any (the same bits either way).
  void flow(const State& y, State& dy) const {
    ws_ ? model_->flow(*d_, y, dy, *ws_) : model_->flow(*d_, y, dy);
  }

  // Which parts move in this piece, and whether each is known without integrating, read off the
  // model's flow at the start: the lid swinging free, undamped and unforced (its acceleration the
  // free lid's at rest at that angle: a pendulum, w = m g r / I from the same function at phiL =
  // 0), and the balloon rising without drag (its acceleration the one at rest: a constant). A
  // small balloon sliding along the lid is integrated.
  bool closed_forms(const State& y) {
    State dy;
    flow(y, dy);
    lid_swings_ = !(dy[slot::phi_l] == 0.0 && dy[slot::dphi_l] == 0.0);
    balloon_rises_ = !(dy[slot::balloon_h] == 0.0 && dy[slot::balloon_v] == 0.0);
    if (lid_swings_ && !(dy[slot::phi_l] == y[slot::dphi_l] &&
                         dy[slot::dphi_l] == model_->lid_free_acceleration(y[slot::phi_l], 0.0))) {
      return false;
    }
    if (balloon_rises_ && (model_->small_balloon() || dy[slot::balloon_h] != y[slot::balloon_v] ||
                           dy[slot::balloon_v] != model_->balloon_acceleration(0.0))) {
      return false;
    }
    w_ = -model_->lid_free_acceleration(0.0, 0.0);
    balloon_a_ = dy[slot::balloon_v];
    return true;
  }
  static Moving moving_of(const State& y) {
    Moving r;
    for (std::size_t k = 0; k < kMoving.size(); ++k) r[k] = y[kMoving[k]];
    return r;
  }
  // The sandbag's parabola from the piece's start.
  void fly(double t, State& y) const {
    const double tau = t - t0_;
    y[slot::x] = y0_[slot::x] + y0_[slot::vx] * tau;
    y[slot::h] = y0_[slot::h] + (y0_[slot::vh] - 0.5 * g_ * tau) * tau;
    y[slot::vh] = y0_[slot::vh] - g_ * tau;
  }
  // The whole state at time t: the sandbag's parabola from the piece's start, the moving part r,
  // the rest as it was.
  State at(double t, const Moving& r) const {
    State y = y0_;
    fly(t, y);
    for (std::size_t k = 0; k < kMoving.size(); ++k) y[kMoving[k]] = r[k];
    return y;
  }
  // The whole state at time t (within the last step) where every part is known.
  State exact_at(double t) const {
    State y = y0_;
    fly(t, y);
    if (balloon_rises_) {
      const double tau = t - t0_;
      y[slot::balloon_h] = y0_[slot::balloon_h] + (y0_[slot::balloon_v] + 0.5 * balloon_a_ * tau) * tau;
      y[slot::balloon_v] = y0_[slot::balloon_v] + balloon_a_ * tau;
    }
    if (lid_swings_) {
      y[slot::phi_l] = series_.angle(t - series_t_);
      y[slot::dphi_l] = series_.rate(t - series_t_);
    }
    return y;
  }
  // The model's flow restricted to the moving part, with the sandbag where it is at time t.
  struct Flow {
    const BallisticStepper* self;
    void operator()(const Moving& r, Moving& dr, double t) const {
      State dy;
      self->flow(self->at(t, r), dy);
      for (std::size_t k = 0; k < kMoving.size(); ++k) dr[k] = dy[kMoving[k]];
    }
  };

  // [rad] The longest arc the lid turns through in one step at tolerance kLidArcTolerance (where it
  // was measured: a sweep's default, its accuracy 1e-8 s / 15), shorter with the fifth root of a
  // tighter one, as Dormand-Prince's steps are (which turned it through about 0.05 rad there). 0.2 finds
  // every event a tight Dormand-Prince run finds on 40,000 random machines around example 2, and steps beyond
  // about 1 rad start to miss a rope that tightens again for an instant.
  static constexpr double kLidArc = 0.2, kLidArcTolerance = 1e-8 / 15.0;
  const Model* model_;
  Workspace* ws_;  // the run's (workspace.hpp)
  const Discrete* d_;
  double g_;
  double series_error_;
  double lid_arc_;  // [rad] (kLidArc)
  detail::StepGrowth growth_;
  bool exact_ = false, lid_swings_ = false, balloon_rises_ = false;
  double w_ = 0.0, balloon_a_ = 0.0;
  PendulumSeries series_;  // the lid's, about series_t_: the last step's
  double series_t_ = 0.0;
  double t_ = 0.0, dt_ = 0.0;  // while exact_
  Dopri5Dense<Moving> inner_;
  Flow flow_{this};
  State y0_{}, current_{};
  double t0_ = 0.0;
};

}  // namespace whatnext
