#include "whatnext/simulate.hpp"

#include "whatnext/model.hpp"

namespace whatnext {

namespace {

// Adapts the automaton in one discrete state to the generic integrators' System concept.
struct MachineSystem {
  using state_type = State;
  using guard_type = GuardValues;
  const Model* model;
  Discrete d;
  void operator()(const State& y, State& dy, double /*t*/) const { model->flow(d, y, dy); }
  void guards(const State& y, GuardValues& g) const { model->guards(d, y, g); }
};

constexpr double kEventTimeTolerance = 1e-12;  // [s]
constexpr double kMaxAdaptiveStep = 0.05;     // [s]; keeps brief guard excursions visible

}  // namespace

Result simulate(const Scenario& sc, Observer* observer) {
  namespace odeint = boost::numeric::odeint;
  const Model model(sc);
  Result res;
  std::vector<Event> fresh;
  HybridState hs = model.initial(fresh);
  // A guard that already reads >= 0 when a smooth piece starts is never seen to cross: a stop
  // threshold passed at the start or by a jump, or a stuck balloon whose lid now accelerates away
  // faster than it can follow. Such events happen at once.
  auto fire_at_once = [&](std::vector<Event>& out) {
    GuardValues g;
    model.guards(hs.d, hs.y, g);
    for (int i = 0; i < kGuardCount; ++i) {
      const Guard gi = static_cast<Guard>(i);
      if (g[i] >= 0.0 && (gi == kGuardBalloonFree || is_stop(event_of(gi)))) return model.jump(gi, hs, out);
    }
    return false;
  };
  auto publish = [&](const Event& e) {
    res.events.push_back(e);
    if (observer) observer->on_event(e);
  };
  const bool stopped = fire_at_once(fresh);
  for (const Event& e : fresh) publish(e);  // anything the start itself decides, at t = 0
  if (stopped) return res;
  OutputGrid grid{observer ? sc.run.output_step : 0.0, 0};
  const double t_end = sc.run.t_max;
  for (;;) {
    const MachineSystem sys{&model, hs.d};
    auto sample = [&](double t, const State& y) {
      observer->on_sample(model.snapshot(HybridState{t, sys.d, y}));
    };
    Crossing c;
    double t = hs.t;
    switch (sc.run.integrator) {
      case IntegratorKind::adaptive:
        c = integrate_adaptive(sys, hs.y, t, t_end, sc.run.tolerance, kMaxAdaptiveStep,
                               kEventTimeTolerance, grid, sample, res.stats);
        break;
      case IntegratorKind::euler:
        c = integrate_fixed<odeint::euler<State>>(sys, hs.y, t, t_end, sc.run.step, grid, sample,
                                                  res.stats);
        break;
      case IntegratorKind::rk4:
        c = integrate_fixed<odeint::runge_kutta4<State>>(sys, hs.y, t, t_end, sc.run.step, grid,
                                                         sample, res.stats);
        break;
    }
    hs.t = t;
    fresh.clear();
    bool stop = false;
    if (c.guard < 0) {
      model.timeout(hs, fresh);
      stop = true;
    } else {
      stop = model.jump(static_cast<Guard>(c.guard), hs, fresh);
      if (!stop) stop = fire_at_once(fresh);
    }
    for (const Event& e : fresh) publish(e);
    if (stop) break;
    if (res.events.size() >= static_cast<std::size_t>(kMaxEvents)) {
      Event e = res.events.back();
      e.type = EventType::event_limit;
      e.mode_before = e.mode_after;
      e.impact = false;
      e.energy_before = e.energy_after;
      publish(e);
      break;
    }
  }
  return res;
}

}  // namespace whatnext
