#include "whatnext/viz/recording.hpp"

#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "whatnext/events.hpp"

namespace whatnext::viz {

namespace {
class Collector : public Observer {
 public:
  explicit Collector(Recording& rec) : rec_(rec) {}
  void on_sample(const Snapshot& s) override {
    rec_.states.push_back(s);
    rec_.event_index.push_back(-1);
  }
  void on_event(const Event& e) override {
    rec_.states.push_back(e.after);
    rec_.event_index.push_back(events_++);
  }

 private:
  Recording& rec_;
  int events_ = 0;
};

double lerp(double a, double b, double w) { return a + (b - a) * w; }
}  // namespace

Recording record(const Scenario& scenario) {
  Recording rec;
  rec.scenario = scenario;
  Collector collector(rec);
  rec.result = simulate(scenario, &collector);
  return rec;
}

Snapshot Recording::at(double t) const {
  if (states.empty()) return {};
  // The last state at or before t (the later one of equal times: after the event).
  auto it =
      std::upper_bound(states.begin(), states.end(), t, [](double v, const Snapshot& s) { return v < s.t; });
  if (it == states.begin()) return states.front();
  const Snapshot& a = *(it - 1);
  if (it == states.end() || it->t <= a.t) {
    Snapshot s = a;
    s.t = t;
    return s;
  }
  const Snapshot& b = *it;
  const double w = (t - a.t) / (b.t - a.t);
  Snapshot s = a;
  s.t = t;
  for (double Snapshot::*f : {&Snapshot::x,
                              &Snapshot::h,
                              &Snapshot::vx,
                              &Snapshot::vh,
                              &Snapshot::r,
                              &Snapshot::dr,
                              &Snapshot::phi_s,
                              &Snapshot::dphi_s,
                              &Snapshot::phi_l,
                              &Snapshot::dphi_l,
                              &Snapshot::ddphi_l,
                              &Snapshot::balloon_h,
                              &Snapshot::balloon_v,
                              &Snapshot::balloon_x,
                              &Snapshot::balloon_vx,
                              &Snapshot::balloon_limit,
                              &Snapshot::balloon_limit_rate,
                              &Snapshot::tension,
                              &Snapshot::sandbag_kinetic,
                              &Snapshot::sandbag_potential,
                              &Snapshot::lid_kinetic,
                              &Snapshot::lid_potential}) {
    s.*f = lerp(a.*f, b.*f, w);
  }
  return s;
}

std::string event_words(const Event& e, bool with_energy) {
  std::string name(to_string(e.type));
  std::replace(name.begin(), name.end(), '_', ' ');
  if (e.impact) {
    if (with_energy) {
      return fmt::format("{} (impact, {:.2f} J -> {:.2f} J)", name, e.energy_before, e.energy_after);
    }
    return name + " (impact)";
  }
  return name;
}

std::vector<EventGroup> group_events(const Result& result) {
  std::vector<EventGroup> groups;
  for (std::size_t i = 0; i < result.events.size(); ++i) {
    const Event& e = result.events[i];
    if (groups.empty() || e.t > groups.back().t) {
      groups.push_back({e.t, {}, fmt::format("{:.3f} s", e.t)});
      groups.back().label += " ";
    } else {
      groups.back().label += " + ";
    }
    groups.back().events.push_back(static_cast<int>(i));
    groups.back().label += event_words(e, false);
  }
  return groups;
}

std::string mode_words(Mode mode) { return mode_words(Snapshot{0.0, mode}); }

// The paper's words for its modes (M1-M5), and where the built machine's contacts hold, the words
// that fit them instead: the page, the CLI's animation and the GIF all say these.
std::string mode_words(const Snapshot& s) {
  const bool falling = s.mode == Mode::M1 || s.mode == Mode::M2;
  const std::string bag = s.bag_on_floor ? "sandbag on the floor"
                          : falling      ? "sandbag falling"
                          : s.at_stop    ? "sandbag at the stop"
                                         : "sandbag on the seesaw";
  std::string rope;
  switch (s.mode) {
    case Mode::M1:
    case Mode::M3: rope = "rope slack"; break;
    case Mode::M2: rope = "rope taut"; break;
    case Mode::M4: rope = "rope pulls the lid"; break;
    case Mode::M5: rope = "rope taut, lid resting"; break;
  }
  if (s.rope_let_go) rope = "rope let go";
  const bool built = s.at_stop || s.bag_on_floor || s.seesaw_on_floor || s.rope_let_go;
  std::string words = std::string(to_string(s.mode)) + ": ";
  if (s.mode != Mode::M5 || built) words += bag + ", ";  // the paper's M5 names the rope and the lid only
  if (s.seesaw_on_floor) words += "seesaw on the floor, ";
  return words + rope;
}

}  // namespace whatnext::viz
