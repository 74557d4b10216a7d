#include "whatnext/simulate.hpp"

#include <cmath>
#include <cstdint>
#include <cstdio>

#include "ballistic.hpp"
#include "integrate.hpp"
#include "model.hpp"

namespace whatnext {

namespace {

// Adapts the automaton in one discrete state to the generic integrators' System concept.
struct MachineSystem {
  using state_type = State;
  using guard_type = GuardValues;
  const Model* model;
  Discrete d;
  Workspace* ws;                 // the run's (Runner::ws_)
  Observer* observer = nullptr;  // asked to keep going every 256 steps (guards() runs once a step)
  std::uint32_t* steps = nullptr;
  void operator()(const State& y, State& dy, double /*t*/) const { model->flow(d, y, dy, *ws); }
  void guards(const State& y, GuardValues& g, GuardValues* rates = nullptr) const {
    if (observer && (++*steps & 255u) == 0 && !observer->keep_going()) throw Cancelled("the run was stopped");
    model->guards(d, y, g, rates, -1, ws);
  }
  double guard(const State& y, int i) const {
    GuardValues g;
    model->guards(d, y, g, nullptr, i, ws);
    return g[i];
  }
  GuardStart guard_start(int i) const { return d.armed[i]; }
};

// [s] Keeps brief guard excursions visible (with the Hermite peak test of integrate_adaptive).
// 0.1 s instead of 0.05 halves example 3's steps at loose tolerances; the 10^4-machine sweep and
// ~1000 machines of an independent simulation give the same events with either.
constexpr double kMaxAdaptiveStep = 0.1;
// No accepted input may run for minutes without a word: a few seconds of steps at most.
constexpr std::int64_t kMaxAdaptiveSteps = 5'000'000;
// An event's time is promised to this many seconds per unit of run.tolerance (1e-9 s at the
// default 1e-12). A piece whose event is estimated less certain than kUncertainBeyond of that is
// integrated again as tightly as brings the estimate to kUncertaintyAim of it (the estimate can
// be a few times short of the real error, evaluate.cpp), down to kTightestTolerance (params.hpp).
constexpr double kEventSecondsPerTolerance = 1e3;
constexpr double kUncertainBeyond = 0.3;
constexpr double kUncertaintyAim = 0.1;

[[noreturn]] void fail(const char* what, double t, Mode mode) {
  char msg[240];
  std::snprintf(msg, sizeof msg, "%s at t = %.9g s in mode M%d", what, t, static_cast<int>(mode));
  throw SimulationError(msg);
}

}  // namespace

Snapshot SampleBatch::snapshot(std::size_t i) const {
  return model_->snapshot(times_[i], d_, states_[i], full_);  // no workspace: any thread
}

Positions SampleBatch::positions(std::size_t i) const { return model_->positions(times_[i], d_, states_[i]); }

namespace {

// One run, in the stages every smooth piece goes through: settle what the instant decides at once,
// integrate the piece (its samples handed over), check that it got somewhere, then the event that
// ends it with everything that follows at the same instant, published with one state.
class Runner {
 public:
  Runner(const Scenario& sc, Observer* observer)
      : sc_(sc),
        observer_(observer),
        model_(sc),
        batch_(model_, observer && observer->sample_detail() == Observer::Detail::full) {}

  Result run() {
    std::vector<Event> fresh;
    hs_ = model_.initial(fresh);
    const bool stopped = settle(fresh, false);
    publish(fresh);  // anything the start itself decides, at t = 0
    if (stopped) return std::move(res_);
    grid_ = OutputGrid{observer_ ? sc_.run.output_step : 0.0, 0};
    if (grid_.step > 0.0) batch_.reserve(kBatch);
    last_t_ = hs_.t;
    for (;;) {
      const Crossing c = integrate_piece_exactly();
      check_progress(c);
      fresh.clear();
      const bool stop = end_piece(c, fresh);
      for (double v : hs_.y)
        if (!std::isfinite(v)) fail("the state turned non-finite", hs_.t, hs_.d.mode());
      publish(fresh);
      if (stop || event_limit_reached()) break;
    }
    return std::move(res_);
  }

 private:
  // Samples are handed over in batches (a piece's, or kBatch of them): an observer may then make
  // their rows on several threads. 2048 states are 213 KB, allocated once per run.
  static constexpr std::size_t kBatch = 2048;
  // Pieces in a row that end where they began: the automaton going round at one instant (rk4 with
  // run.step = 1 s on example 4 did so for ever) is stopped instead of hanging.
  static constexpr int kMaxPiecesWithoutProgress = 10'000;

  // Where a smooth piece starts, a guard that already reads >= 0 is never seen to cross. A stop
  // threshold passed, or a stuck balloon the lid already leaves, happens at once; a contact guard
  // at zero that the contact decision did not arm is armed here, so it is looked for just after.
  bool start_piece(std::vector<Event>& out) {
    GuardValues g;
    model_.guards(hs_.d, hs_.y, g, nullptr, -1, &ws_);
    for (int i = 0; i < kGuardCount; ++i) {
      const Guard gi = static_cast<Guard>(i);
      if (!(g[i] >= 0.0)) continue;
      if (fires_at_once(gi) || (gi == kGuardBalloon && hs_.d.balloon_stuck))
        return model_.jump(gi, hs_, out, &ws_);
      if (hs_.d.armed[i].order == 0) hs_.d.armed[i] = {1, -1e-300, model_.guard_floor(gi, hs_.d)};
    }
    return false;
  }

  // What happens at once after a jump (or at the start), a few rounds at most; true: the run ends.
  bool settle(std::vector<Event>& out, bool stop) {
    for (int round = 0; round < 8 && !stop; ++round) {
      const std::size_t n = out.size();
      stop = start_piece(out);
      if (out.size() == n) break;
    }
    return stop;
  }

  // Every event of one instant carries the state the motion goes on with after all of them.
  void publish(std::vector<Event>& events) {
    if (!events.empty()) {
      const Snapshot final_state = model_.snapshot(hs_, &ws_);
      for (Event& e : events) {  // all of them at hs.t: the jumps' events carry no state of their own
        e.after = final_state;
        e.energy_after = final_state.energy();
        if (!e.impact) e.energy_before = e.energy_after;
      }
    }
    for (const Event& e : events) {
      res_.events.push_back(e);
      if (observer_) observer_->on_event(e);
    }
  }

  // One smooth piece, integrated again from its start where its event's time is less certain than
  // the run's event accuracy: a contact that closes grazing (a rope straight again at a few mm/s)
  // has a time as uncertain as the gap's error over its small rate, 4e-8 s at the default tolerance
  // on a rope that tightened again 6.7 ms after going slack (docs/model.md, section 9). Only the
  // piece is redone, so its events do not depend on where the run is cut; samples already handed
  // over stay (the grid goes on from the last one).
  Crossing integrate_piece_exactly() {
    const RunSettings& run = sc_.run;
    const State y0 = hs_.y;
    const double t0 = t_;
    const double accuracy = kEventSecondsPerTolerance * run.tolerance;
    double tolerance = run.tolerance;
    Crossing c = integrate_piece(tolerance);
    for (int again = 0;
         again < 2 && run.integrator == IntegratorKind::adaptive && c.kind == Crossing::event &&
         c.uncertainty > kUncertainBeyond * accuracy && tolerance > kTightestTolerance;
         ++again) {
      tolerance = std::fmax(kTightestTolerance, tolerance * kUncertaintyAim * accuracy / c.uncertainty);
      hs_.y = y0;
      t_ = t0;
      c = integrate_piece(tolerance);
    }
    return c;
  }

  // One smooth piece with the run's integrator, up to the first guard that fires or t_max; its
  // samples go to the observer before its events. hs_.y is left at the piece's end.
  Crossing integrate_piece(double tolerance) {
    namespace odeint = boost::numeric::odeint;
    const MachineSystem sys{&model_, hs_.d, &ws_, observer_, &steps_};
    if (observer_) batch_.start(hs_.d);
    auto sample = [&](double t, const State& y) {
      batch_.add(t, y);
      if (batch_.size() == kBatch) hand_over();
    };
    Crossing c;
    t_ = hs_.t;
    const RunSettings& run = sc_.run;
    switch (run.integrator) {
      case IntegratorKind::adaptive: {
        const DenseSettings dense{tolerance, kMaxAdaptiveStep, run.event_time_tolerance,
                                  kMaxAdaptiveSteps - res_.stats.steps};
        if (BallisticStepper::applies(model_, sc_, hs_.d, hs_.y,
                                      &ws_)) {  // the sandbag's parabola in closed form
          BallisticStepper stepper(model_, hs_.d, hs_.y, sc_.machine.gravity, dense, &ws_);
          c = integrate_dense(stepper, sys, hs_.y, t_, run.t_max, dense, grid_, sample, res_.stats);
        } else {
          c = integrate_adaptive(sys, hs_.y, t_, run.t_max, dense, grid_, sample, res_.stats);
        }
        break;
      }
      case IntegratorKind::euler:
        c = integrate_fixed<odeint::euler<State>>(sys, hs_.y, t_, run.t_max, run.step, grid_, sample,
                                                  res_.stats);
        break;
      case IntegratorKind::rk4:
        c = integrate_fixed<odeint::runge_kutta4<State>>(sys, hs_.y, t_, run.t_max, run.step, grid_, sample,
                                                         res_.stats);
        break;
    }
    if (observer_) hand_over();  // the piece's samples, before its events
    return c;
  }

  void hand_over() {
    if (batch_.size() > 0) observer_->on_samples(batch_);
    batch_.clear();
  }

  // The piece ended somewhere the run can go on from, or the run fails with one line.
  void check_progress(const Crossing& c) {
    if (c.kind == Crossing::non_finite) fail("the motion turned non-finite", c.t, hs_.d.mode());
    if (c.kind == Crossing::step_limit) {
      fail("the integrator used its budget of 5e6 steps (loosen run.tolerance or shorten run.t_max)", c.t,
           hs_.d.mode());
    }
    hs_.t = t_;
    no_progress_ = t_ > last_t_ ? 0 : no_progress_ + 1;
    last_t_ = t_;
    if (no_progress_ > kMaxPiecesWithoutProgress) {
      fail(
          "the run stopped advancing (the same instant's contacts decided again and again; a fixed step may "
          "be "
          "too long for this machine)",
          hs_.t, hs_.d.mode());
    }
  }

  // The event that ended the piece (or t_max), and what follows from it at once; true: the run ends.
  bool end_piece(const Crossing& c, std::vector<Event>& fresh) {
    if (c.kind == Crossing::end) {
      model_.timeout(hs_, fresh);
      return true;
    }
    const bool stop = settle(fresh, model_.jump(static_cast<Guard>(c.guard), hs_, fresh, &ws_));
    // The chart's switch and the rope's relaxing are no events; what they lead to at once is found on
    // no crossing.
    if (!reports_no_event(static_cast<Guard>(c.guard))) {
      for (Event& e : fresh) e.time_uncertainty = c.uncertainty;
    }
    return stop;
  }

  // A safety stop against endless event chains.
  bool event_limit_reached() {
    if (res_.events.size() < static_cast<std::size_t>(kMaxEvents)) return false;
    Event e = res_.events.back();
    e.type = EventType::event_limit;
    e.mode_before = e.mode_after;
    e.impact = false;
    e.energy_before = e.energy_after;
    std::vector<Event> last{e};
    publish(last);
    return true;
  }

  const Scenario& sc_;
  Observer* observer_;
  const Model model_;
  Workspace ws_;  // what this run's evaluations of model_ keep (workspace.hpp)
  SampleBatch batch_;
  Result res_;
  HybridState hs_;
  OutputGrid grid_;
  double t_ = 0.0;       // where the current piece has got to
  double last_t_ = 0.0;  // where the previous one ended
  int no_progress_ = 0;
  std::uint32_t steps_ = 0;  // for the observer's keep_going(), every 256 steps
};

}  // namespace

Result simulate(const Scenario& sc, Observer* observer) { return Runner(sc, observer).run(); }

}  // namespace whatnext
