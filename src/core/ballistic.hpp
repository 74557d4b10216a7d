// Pieces in which the sandbag flies freely: falling before it lands, or on a massless seesaw with
// the rope slack (docs/model.md, "Free fall in closed form"). Its motion is then a parabola, known
// exactly; only what else moves (the lid's free swing, the balloon) is integrated, by the adaptive
// integrator's own Dormand-Prince on those four numbers instead of all thirteen.
#pragma once

#include <array>
#include <utility>

#include "integrate.hpp"
#include "model.hpp"

namespace whatnext {

// A dense-output stepper (integrate_dense's interface) for such a piece. Dormand-Prince integrates
// a parabola exactly, so the whole state's steps were already those of the lid and the balloon
// alone (the sandbag's error estimate is rounding, below the step growth's limit): this stepper
// takes the same steps and gives the lid and the balloon the same values, bit for bit, while the
// sandbag's comes from the closed form instead of the dense output (the same up to rounding).
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
  static bool applies(const Model& model, const Scenario& sc, const Discrete& d, const State& y) {
    const Machine& m = sc.machine;
    if (d.polar() || d.heavy || d.stretched || m.heavy_seesaw() || m.pivot_damping > 0.0 ||
        m.lid_hinge_damping > 0.0 || m.balloon_drag_rate() > 0.0 || m.has_friction()) {
      return false;
    }
    State dy;
    model.flow(d, y, dy);
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

  BallisticStepper(const Model& model, const Discrete& d, double gravity, double tolerance, double max_dt)
      : model_(&model),
        d_(&d),
        g_(gravity),
        growth_(max_dt),
        // Nothing else moves while the lid rests (or is latched open) and the balloon is stuck under it
        // (a smaller one held in its corner, not sliding along the lid: docs/extensions.md).
        still_((d.lid_resting || d.latched) && d.balloon_stuck && d.balloon_held),
        inner_(make_dopri5<Moving>(tolerance, max_dt)) {}
  BallisticStepper(const BallisticStepper&) = delete;  // flow_ points at this one
  BallisticStepper& operator=(const BallisticStepper&) = delete;

  void initialize(const State& y, double t, double dt) {
    y0_ = y;
    t0_ = t;
    current_ = y;
    const Moving r = moving_of(y);
    if (still_) {
      t_ = t, dt_ = dt;
      return;
    }
    inner_.initialize(r, t, dt);
  }
  // The whole state's starting step, so that the steps stay Dormand-Prince's; while still, the
  // longest: every step is exact.
  template <class System>
  double starting_step(const System& sys, const State& y, double t, double tolerance, double max_dt) const {
    return still_ ? max_dt : detail::starting_step(sys, y, t, tolerance, max_dt);
  }
  template <class System>
  std::pair<double, double> do_step(System /*whole state's: the flow below is its restriction*/) {
    if (still_) {
      // Only the sandbag moves: the steps Dormand-Prince takes where its error estimate is nil,
      // each the step growth's largest, with nothing to integrate.
      const double t_old = t_;
      t_ += dt_;
      dt_ = growth_.increase_step(dt_, 0.0, 5);
      current_ = at(t_, moving_of(y0_));
      return {t_old, t_};
    }
    const std::pair<double, double> interval = inner_.do_step(std::cref(flow_));
    current_ = at(interval.second, inner_.current_state());
    return interval;
  }
  void calc_state(double t, State& out) const {
    if (still_) {
      out = at(t, moving_of(y0_));
      return;
    }
    Moving r;
    inner_.calc_state(t, r);
    out = at(t, r);
  }
  const State& current_state() const { return current_; }
  double current_time() const { return still_ ? t_ : inner_.current_time(); }

 private:
  static Moving moving_of(const State& y) {
    Moving r;
    for (std::size_t k = 0; k < kMoving.size(); ++k) r[k] = y[kMoving[k]];
    return r;
  }
  // The whole state at time t: the sandbag's parabola from the piece's start, the moving part r,
  // the rest as it was.
  State at(double t, const Moving& r) const {
    State y = y0_;
    const double tau = t - t0_;
    y[slot::x] = y0_[slot::x] + y0_[slot::vx] * tau;
    y[slot::h] = y0_[slot::h] + (y0_[slot::vh] - 0.5 * g_ * tau) * tau;
    y[slot::vh] = y0_[slot::vh] - g_ * tau;
    for (std::size_t k = 0; k < kMoving.size(); ++k) y[kMoving[k]] = r[k];
    return y;
  }
  // The model's flow restricted to the moving part, with the sandbag where it is at time t.
  struct Flow {
    const BallisticStepper* self;
    void operator()(const Moving& r, Moving& dr, double t) const {
      State dy;
      self->model_->flow(*self->d_, self->at(t, r), dy);
      for (std::size_t k = 0; k < kMoving.size(); ++k) dr[k] = dy[kMoving[k]];
    }
  };

  const Model* model_;
  const Discrete* d_;
  double g_;
  detail::StepGrowth growth_;
  bool still_;
  double t_ = 0.0, dt_ = 0.0;  // while still_
  Dopri5Dense<Moving> inner_;
  Flow flow_{this};
  State y0_{}, current_{};
  double t0_ = 0.0;
};

}  // namespace whatnext
