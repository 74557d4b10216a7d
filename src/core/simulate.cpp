#include "whatnext/simulate.hpp"

#include <cstdint>
#include <cstdio>

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
  Observer* observer = nullptr;  // asked to keep going every 256 steps (guards() runs once a step)
  std::uint32_t* steps = nullptr;
  void operator()(const State& y, State& dy, double /*t*/) const { model->flow(d, y, dy); }
  void guards(const State& y, GuardValues& g, GuardValues* rates = nullptr) const {
    if (observer && (++*steps & 255u) == 0 && !observer->keep_going()) throw Cancelled("the run was stopped");
    model->guards(d, y, g, rates);
  }
  double guard(const State& y, int i) const {
    GuardValues g;
    model->guards(d, y, g, nullptr, i);
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

[[noreturn]] void fail(const char* what, double t, Mode mode) {
  char msg[240];
  std::snprintf(msg, sizeof msg, "%s at t = %.9g s in mode M%d", what, t, static_cast<int>(mode));
  throw SimulationError(msg);
}

}  // namespace

Snapshot SampleBatch::snapshot(std::size_t i) const {
  return model_->snapshot(times_[i], d_, states_[i], full_, /*memo=*/false);
}

Result simulate(const Scenario& sc, Observer* observer) {
  namespace odeint = boost::numeric::odeint;
  const Model model(sc);
  Result res;
  std::vector<Event> fresh;
  HybridState hs = model.initial(fresh);
  // Where a smooth piece starts, a guard that already reads >= 0 is never seen to cross. A stop
  // threshold passed, or a stuck balloon the lid already leaves, happens at once; a contact guard
  // at zero that the contact decision did not arm is armed here, so it is looked for just after.
  auto start_piece = [&](std::vector<Event>& out) {
    GuardValues g;
    model.guards(hs.d, hs.y, g);
    for (int i = 0; i < kGuardCount; ++i) {
      const Guard gi = static_cast<Guard>(i);
      if (!(g[i] >= 0.0)) continue;
      if (fires_at_once(gi) || (gi == kGuardBalloon && hs.d.balloon_stuck)) return model.jump(gi, hs, out);
      if (hs.d.armed[i].order == 0) hs.d.armed[i] = {1, -1e-300, model.guard_floor(gi, hs.d)};
    }
    return false;
  };
  // Every event of one instant carries the state the motion goes on with after all of them.
  auto publish = [&](std::vector<Event>& events) {
    if (!events.empty()) {
      const Snapshot final_state = model.snapshot(hs);
      for (Event& e : events) {  // all of them at hs.t: the jumps' events carry no state of their own
        e.after = final_state;
        e.energy_after = final_state.energy();
        if (!e.impact) e.energy_before = e.energy_after;
      }
    }
    for (const Event& e : events) {
      res.events.push_back(e);
      if (observer) observer->on_event(e);
    }
  };
  bool stopped = false;
  for (int settle = 0; settle < 8 && !stopped; ++settle) {
    const std::size_t n = fresh.size();
    stopped = start_piece(fresh);
    if (fresh.size() == n) break;
  }
  publish(fresh);  // anything the start itself decides, at t = 0
  if (stopped) return res;
  OutputGrid grid{observer ? sc.run.output_step : 0.0, 0};
  const bool full_samples = observer && observer->sample_detail() == Observer::Detail::full;
  // Samples are handed over in batches (a piece's, or kBatch of them): an observer may then make
  // their rows on several threads. 2048 states are 213 KB, allocated once per run.
  constexpr std::size_t kBatch = 2048;
  SampleBatch batch(model, full_samples);
  if (grid.step > 0.0) batch.reserve(kBatch);
  auto hand_over = [&] {
    if (batch.size() > 0) observer->on_samples(batch);
    batch.clear();
  };
  const double t_end = sc.run.t_max;
  // Pieces in a row that end where they began: the automaton going round at one instant (rk4 with
  // run.step = 1 s on example 4 did so for ever) is stopped instead of hanging.
  constexpr int kMaxPiecesWithoutProgress = 10'000;
  double last_t = hs.t;
  int no_progress = 0;
  std::uint32_t steps = 0;
  for (;;) {
    const MachineSystem sys{&model, hs.d, observer, &steps};
    if (observer) batch.start(hs.d);
    auto sample = [&](double t, const State& y) {
      batch.add(t, y);
      if (batch.size() == kBatch) hand_over();
    };
    Crossing c;
    double t = hs.t;
    switch (sc.run.integrator) {
      case IntegratorKind::adaptive:
        c = integrate_adaptive(sys, hs.y, t, t_end, sc.run.tolerance, kMaxAdaptiveStep,
                               sc.run.event_time_tolerance, kMaxAdaptiveSteps - res.stats.steps, grid, sample,
                               res.stats);
        break;
      case IntegratorKind::euler:
        c = integrate_fixed<odeint::euler<State>>(sys, hs.y, t, t_end, sc.run.step, grid, sample, res.stats);
        break;
      case IntegratorKind::rk4:
        c = integrate_fixed<odeint::runge_kutta4<State>>(sys, hs.y, t, t_end, sc.run.step, grid, sample,
                                                         res.stats);
        break;
    }
    if (observer) hand_over();  // the piece's samples, before its events
    if (c.kind == Crossing::non_finite) fail("the motion turned non-finite", c.t, hs.d.mode());
    if (c.kind == Crossing::step_limit) {
      fail("the integrator used its budget of 5e6 steps (loosen run.tolerance or shorten run.t_max)", c.t,
           hs.d.mode());
    }
    hs.t = t;
    no_progress = t > last_t ? 0 : no_progress + 1;
    last_t = t;
    if (no_progress > kMaxPiecesWithoutProgress) {
      fail(
          "the run stopped advancing (the same instant's contacts decided again and again; a fixed step may "
          "be "
          "too long for this machine)",
          hs.t, hs.d.mode());
    }
    fresh.clear();
    bool stop = false;
    if (c.kind == Crossing::end) {
      model.timeout(hs, fresh);
      stop = true;
    } else {
      stop = model.jump(static_cast<Guard>(c.guard), hs, fresh);
      for (int settle = 0; settle < 8 && !stop; ++settle) {
        const std::size_t n = fresh.size();
        stop = start_piece(fresh);
        if (fresh.size() == n) break;
      }
      // The chart's switch is no event; what it leads to at once is found on no crossing.
      if (c.guard != kGuardChart) {
        for (Event& e : fresh) e.time_uncertainty = c.uncertainty;
      }
    }
    for (double v : hs.y)
      if (!std::isfinite(v)) fail("the state turned non-finite", hs.t, hs.d.mode());
    publish(fresh);
    if (stop) break;
    if (res.events.size() >= static_cast<std::size_t>(kMaxEvents)) {
      Event e = res.events.back();
      e.type = EventType::event_limit;
      e.mode_before = e.mode_after;
      e.impact = false;
      e.energy_before = e.energy_after;
      std::vector<Event> last{e};
      publish(last);
      break;
    }
  }
  return res;
}

}  // namespace whatnext
