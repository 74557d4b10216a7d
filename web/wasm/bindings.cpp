// The page's door into the library (embind): a machine is built from TOML text plus `--set`
// overrides exactly as the CLI builds it, then run; results come back as plain JS objects with the
// samples as Float64Array columns. Bad input gives the CLI's one-line message instead of a result.
// Nothing here computes physics or formats numbers: that is the library's (config, simulate, output).
#include <emscripten/bind.h>
#include <emscripten/emscripten.h>
#include <emscripten/val.h>

#include <cmath>
#include <exception>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/columns.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"
#include "whatnext/viz/recording.hpp"
#include "page_input.hpp"
#include "viz/scene.hpp"

namespace whatnext::web {

std::string_view radio_example_toml();  // generated from examples/example1-radio.toml

namespace {

using emscripten::val;

// What the page sends: {toml, source, label, sets: ["key=value", ...], format, maxRows}.
// `toml` is the machine's text (the paper's whatnext.inp when format is "inp"), `source` names it
// in messages (as a file name does for the CLI), `label` heads the timeline (the CLI's
// "example 1" or file name).
struct Input {
  Config config;
  Scenario scenario;
  std::string label;
};

Input load(const val& in) {
  Input out;
  out.config = config_of(in);
  const std::vector<std::string> sets = emscripten::vecFromJSArray<std::string>(in["sets"]);
  out.scenario = build_scenario(out.config);
  // As the CLI labels its runs, so that timeline and JSON read the same.
  out.label = input_label(in["label"].as<std::string>(), sets);
  return out;
}

val text_result(const std::string& text) {
  val r = val::object();
  r.set("ok", true);
  r.set("text", text);
  return r;
}

val xy(Vec2 p) {
  val v = val::object();
  v.set("x", p.x);
  v.set("h", p.h);
  return v;
}

// The columns of the samples and the fields of an event's state, by name: the state's columns of
// columns.hpp in SI units under their json_key (x, balloon_h, energy, lost_impacts, ...), then
// what the page needs beyond them: the angles and their rates in radians (the table reports them
// in degrees; the page converts at its edge, like the CLI's writers), the velocities, the
// balloon's sideways position, the contacts and the mode.
struct Column {
  std::string name;
  double (*get)(const Snapshot&);
};
#define WHATNEXT_COLUMN(f)                                         \
  Column {                                                         \
#f, [](const Snapshot& s) { return static_cast<double>(s.f); } \
  }
const std::vector<Column>& columns() {
  static const std::vector<Column> all = [] {
    std::vector<Column> out{WHATNEXT_COLUMN(t)};
    for (const StateColumn& c : state_columns()) {
      if (json_key(c) != c.name) out.push_back({std::string(json_key(c)), c.value});  // an SI column
    }
    for (Column c : {
             WHATNEXT_COLUMN(vx),
             WHATNEXT_COLUMN(vh),
             WHATNEXT_COLUMN(phi_s),
             WHATNEXT_COLUMN(dphi_s),
             WHATNEXT_COLUMN(phi_l),
             WHATNEXT_COLUMN(dphi_l),
             WHATNEXT_COLUMN(balloon_x),  // from the hinge sideways: a balloon smaller than the box moves
             WHATNEXT_COLUMN(normal_force),
             WHATNEXT_COLUMN(box_reaction),
             WHATNEXT_COLUMN(stop_reaction),
             WHATNEXT_COLUMN(floor_reaction),
             WHATNEXT_COLUMN(bag_floor_reaction),
             WHATNEXT_COLUMN(at_stop),  // the built machine's contacts (the mode's words)
             WHATNEXT_COLUMN(bag_on_floor),
             WHATNEXT_COLUMN(seesaw_on_floor),
             WHATNEXT_COLUMN(rope_let_go),
             WHATNEXT_COLUMN(rope_potential),  // a rope that stretches: its spring, its damper's heat
             WHATNEXT_COLUMN(dissipated_rope),
             WHATNEXT_COLUMN(initial_total),
             WHATNEXT_COLUMN(on_seesaw),
             WHATNEXT_COLUMN(rope_taut),
             WHATNEXT_COLUMN(lid_resting),
             WHATNEXT_COLUMN(balloon_stuck),
             Column{"mode", [](const Snapshot& s) { return static_cast<double>(static_cast<int>(s.mode)); }},
             Column{"total_energy", [](const Snapshot& s) { return s.total_energy(); }},
             Column{"dissipated", [](const Snapshot& s) { return s.dissipated(); }},
         }) {
      out.push_back(c);
    }
    return out;
  }();
  return all;
}
#undef WHATNEXT_COLUMN

val snapshot_object(const Snapshot& s) {
  val v = val::object();
  for (const Column& c : columns()) v.set(c.name, c.get(s));
  return v;
}

// Keeps the samples (every stride-th, so that a fine output step cannot fill the memory) and each
// event's state at its time, in time order: what the drawing and the plots need.
class Columns : public Observer {
 public:
  Columns(long stride, const Machine& m) : stride_(stride), machine_(m), geo_(m) {}
  void on_sample(const Snapshot& s) override {
    if (samples_++ % stride_ == 0) add(s, -1.0);
    watch_release(s);
    // The worker (web/src/worker.js) tells the page how far the run is, at most every few tenths
    // of a second; asking the clock costs next to nothing beside a sample.
    if (emscripten_get_now() - reported_ > 150.0) {
      reported_ = emscripten_get_now();
      const val progress = val::global("whatnextProgress");
      if (progress.typeOf().as<std::string>() == "function") progress(s.t);
    }
  }
  void on_event(const Event& e) override {
    add(e.after, static_cast<double>(events_++));
    if (machine_.radio && e.type == EventType::lid_open && !std::isfinite(release_.latch))
      release_.latch = e.t;
    watch_release(e.after);
  }
  // When the radio's latch let the rope go and when it came off the seesaw's end (scene.hpp's
  // Release), from every state of the run, not only the samples kept.
  const viz::scene::Release& release() const { return release_; }

  val to_js() const {
    val out = val::object();
    for (std::size_t c = 0; c < columns().size(); ++c) out.set(columns()[c].name, array(data_[c]));
    out.set("event", array(event_));
    out.set("stride", static_cast<double>(stride_));
    return out;
  }

 private:
  void add(const Snapshot& s, double event) {
    for (std::size_t c = 0; c < columns().size(); ++c) data_[c].push_back(columns()[c].get(s));
    event_.push_back(event);
  }
  void watch_release(const Snapshot& s) {
    if (s.t >= release_.latch && !std::isfinite(release_.off) && viz::scene::beyond_rope(geo_, s)) {
      release_.off = s.t;
    }
  }
  static val array(const std::vector<double>& v) {  // a copy, independent of the wasm memory
    return val::global("Float64Array").new_(emscripten::typed_memory_view(v.size(), v.data()));
  }
  long stride_;
  Machine machine_;
  RopeGeometry geo_;
  viz::scene::Release release_;
  long samples_ = 0, events_ = 0;
  double reported_ = emscripten_get_now();
  std::vector<std::vector<double>> data_ = std::vector<std::vector<double>>(columns().size());
  std::vector<double> event_;
};

val machine_object(const Scenario& sc) {
  const Machine& m = sc.machine;
  val v = val::object();
  v.set("seesaw_right_arm", m.seesaw_right_arm);
  v.set("seesaw_left_arm", m.seesaw_left_arm);  // Infinity: the paper's endless arm
  v.set("lid_half_length", m.lid_half_length);
  v.set("rope_knot", m.rope_knot());  // the rope's knot from the hinge along the lid [m]
  v.set("rope_length", m.rope_length);
  v.set("hinge", xy(m.hinge));
  v.set("balloon_radius", m.balloon_radius);
  v.set("radio", m.radio);
  v.set("radio_switch", xy(m.radio_switch));
  v.set("string_length", m.string_length);
  v.set("sandbag_mass", m.sandbag_mass);
  v.set("lid_mass", m.lid_mass);
  v.set("seesaw_mass", m.seesaw_mass);
  v.set("end_stop", m.end_stop);
  v.set("floor", m.floor);  // the built machine's floor through the box's bottom
  v.set("gravity", m.gravity);
  val start = val::object();
  start.set("sandbag_x", sc.start.sandbag_x);
  start.set("sandbag_h", sc.start.sandbag_h);
  start.set("seesaw_angle", sc.start.seesaw_angle);
  start.set("lid_angle", sc.start.lid_angle);
  v.set("start", start);
  val run = val::object();
  run.set("t_max", sc.run.t_max);
  run.set("output_step", sc.run.output_step);
  run.set("integrator", std::string(to_string(sc.run.integrator)));
  run.set("step", sc.run.step);
  run.set("impact_law", std::string(to_string(sc.run.impact_law)));
  run.set("vertical_margin", sc.run.vertical_margin);
  v.set("run", run);
  return v;
}

val config_value(const ConfigValue& c) {
  val v = val::object();
  switch (c.type) {
    case ConfigValue::Type::number: v.set("number", c.number); break;
    case ConfigValue::Type::text: v.set("text", c.text); break;
    case ConfigValue::Type::pair: {
      val p = val::array();
      p.call<void>("push", c.pair[0]);
      p.call<void>("push", c.pair[1]);
      v.set("pair", p);
      break;
    }
  }
  return v;
}

// The value every key has in this run, as written in an input: the given ones as given, the
// others as to_toml writes the built machine (so the panel can show what a blank field means).
val values_object(const Input& in) {
  const Config built = parse_toml(to_toml(in.scenario), "to_toml");
  val given = val::object(), effective = val::object();
  for (const auto& [key, value] : in.config.values) given.set(key, config_value(value));
  for (const auto& [key, value] : built.values) effective.set(key, config_value(value));
  val v = val::object();
  v.set("given", given);
  v.set("effective", effective);
  return v;
}

// impulses: how many contacts the machine has (columns.hpp impulse_columns).
val event_object(const Event& e, std::size_t impulses) {
  val v = val::object();
  v.set("type", std::string(to_string(e.type)));
  v.set("t", e.t);
  v.set("mode_before", std::string(to_string(e.mode_before)));
  v.set("mode_after", std::string(to_string(e.mode_after)));
  v.set("impact", e.impact);
  v.set("energy_before", e.energy_before);
  v.set("energy_after", e.energy_after);
  if (e.impact) {  // each contact's impulse [N s; the lid's N m s] and the law applied
    val p = val::object();
    for (std::size_t i = 0; i < impulses; ++i) p.set(std::string(impulse_key(i)), e.impulse[i]);
    v.set("impulses", p);
    v.set("law_applied", std::string(to_string(e.law)));
    v.set("law_note", std::string(e.law_note));
  }
  v.set("stop", is_stop(e.type));
  v.set("words", viz::event_words(e, true));
  v.set("state", snapshot_object(e.after));
  return v;
}

// --- what the page calls ---------------------------------------------------------------------

// Builds and runs the machine: {ok, label, machine, values, events, outcome, timeline, samples,
// stats}. input.maxRows bounds the samples kept (default 50000).
val run(val input) {
  return guarded([&] {
    const Input in = load(input);
    const double max_rows = input["maxRows"].isNumber() ? input["maxRows"].as<double>() : 5e4;
    const double rows = in.scenario.run.t_max / in.scenario.run.output_step;
    Columns columns(std::max(1L, static_cast<long>(std::ceil(rows / std::max(1.0, max_rows)))),
                    in.scenario.machine);
    const Result result = simulate(in.scenario, &columns);

    val r = val::object();
    r.set("ok", true);
    r.set("label", in.label);
    r.set("machine", machine_object(in.scenario));
    r.set("values", values_object(in));
    val events = val::array();
    for (const Event& e : result.events)
      events.call<void>("push", event_object(e, impulse_columns(in.scenario.machine)));
    r.set("events", events);
    val groups = val::array();  // events at one instant, as the animation holds them
    for (const viz::EventGroup& g : viz::group_events(result)) {
      val group = val::object(), members = val::array();
      group.set("t", g.t);
      for (int i : g.events) members.call<void>("push", i);
      group.set("events", members);
      group.set("label", g.label);
      groups.call<void>("push", group);
    }
    r.set("groups", groups);
    val outcome = val::object();
    outcome.set("type", std::string(to_string(result.outcome().type)));
    outcome.set("t", result.outcome().t);
    outcome.set("sentence", outcome_sentence(result));
    r.set("outcome", outcome);
    r.set("timeline", timeline_text(result, in.scenario, in.label));
    r.set("samples", columns.to_js());
    val release = val::object();
    release.set("latch", columns.release().latch);
    release.set("off", columns.release().off);
    r.set("release", release);
    val stats = val::object();
    stats.set("steps", static_cast<double>(result.stats.steps));
    stats.set("root_evaluations", static_cast<double>(result.stats.root_evaluations));
    r.set("stats", stats);
    return r;
  });
}

// What a run will cost before it is started: the machine's run settings, {ok, integrator, step,
// t_max, output_step}, or the input's message. The worker asks before a fixed-step run of
// millions of steps.
val plan(val input) {
  return guarded([&] {
    const Input in = load(input);
    val r = val::object();
    r.set("ok", true);
    r.set("integrator", std::string(to_string(in.scenario.run.integrator)));
    r.set("step", in.scenario.run.step);
    r.set("t_max", in.scenario.run.t_max);
    r.set("output_step", in.scenario.run.output_step);
    return r;
  });
}

val points(const std::vector<Vec2>& pts) {
  val a = val::array();
  for (Vec2 p : pts) a.call<void>("push", xy(p));
  return a;
}

// The machines the page draws, built once each from their input (a page draws a few at a time:
// the run and the ones it is compared with).
const Scenario& drawn_scenario(const val& input) {
  static std::map<std::string, Scenario> built;
  std::string key = input["toml"].as<std::string>() + '\n' + input["source"].as<std::string>() + '\n' +
                    (input["format"].isString() ? input["format"].as<std::string>() : "");
  for (const std::string& s : emscripten::vecFromJSArray<std::string>(input["sets"])) key += '\n' + s;
  auto it = built.find(key);
  if (it != built.end()) return it->second;
  if (built.size() >= 16) built.clear();
  return built.emplace(key, load(input).scenario).first->second;
}

// The scene as `whatnext animate` draws it (src/viz/scene.hpp): where each part of the machine is
// in state `state` of a run of `input` whose rope was let go as `release` says ({latch, off} of
// the run's result), with the left arm `arm` long and the end stop `stopHeight` high [m]. The
// page draws from this, so that its picture and the animation's have the same points:
// {landingDistance, endlessArm, ground, floor, floorPieces, stand, walls, radio {x0, x1, h0, h1}, dial,
// dialRadius, dialSquash,
//  radioPost, notes, hinge, lidEnd, armLeft, armRight, endStop, stopTop, rope, sandbag, balloon,
//  balloonRadius, string}, points as {x, h} in metres.
val scene(val input, val state, double arm, double stop_height, val release) {
  return guarded([&] {
    const Scenario& sc = drawn_scenario(input);
    const Machine& m = sc.machine;
    Snapshot s;  // what the scene reads of a state
    s.t = state["t"].as<double>();
    s.x = state["x"].as<double>();
    s.h = state["h"].as<double>();
    s.phi_s = state["phi_s"].as<double>();
    s.phi_l = state["phi_l"].as<double>();
    s.balloon_h = state["balloon_h"].as<double>();
    s.balloon_x = state["balloon_x"].as<double>();
    s.rope_taut = state["rope_taut"].as<double>() != 0.0;
    viz::scene::Release r;
    r.latch = release["latch"].as<double>();
    r.off = release["off"].as<double>();
    const viz::scene::StillParts still = viz::scene::still_parts(m);
    const viz::scene::MovingParts moving = viz::scene::moving_parts(m, s, r, arm, stop_height);
    val v = val::object();
    v.set("ok", true);
    v.set("landingDistance", viz::scene::landing_distance(sc));
    v.set("endlessArm", viz::scene::endless_arm(sc));
    v.set("ground", still.ground);
    v.set("floor", still.floor);
    val pieces = val::array();
    for (auto [a, b] : still.floor_pieces)
      pieces.call<void>("push", points({{a, still.ground}, {b, still.ground}}));
    v.set("floorPieces", pieces);
    v.set("stand", points({still.stand.begin(), still.stand.end()}));
    v.set("walls", points({still.walls.begin(), still.walls.end()}));
    val radio = val::object();
    radio.set("x0", still.radio.x0);
    radio.set("x1", still.radio.x1);
    radio.set("h0", still.radio.h0);
    radio.set("h1", still.radio.h1);
    v.set("radio", radio);
    v.set("dial", xy(still.dial));
    v.set("dialRadius", still.dial_radius);
    v.set("dialSquash", still.dial_squash);
    v.set("radioPost", points({still.radio_post.begin(), still.radio_post.end()}));
    v.set("notes", xy(still.notes));
    v.set("hinge", xy(moving.hinge));
    v.set("lidEnd", xy(moving.lid_end));
    v.set("armLeft", xy(moving.arm_left));
    v.set("armRight", xy(moving.arm_right));
    v.set("endStop", moving.end_stop);
    v.set("stopTop", xy(moving.stop_top));
    v.set("rope", points(moving.rope));
    v.set("sandbag", xy(moving.sandbag));
    v.set("balloon", xy(moving.balloon));
    v.set("balloonRadius", moving.balloon_radius);
    v.set("string", points(moving.string));
    return v;
  });
}

// The forces on the machine and the velocities in state `state` of a run of `input` (its
// fields as the run's samples name them), drawn on the scene as `scene` places it: each arrow
// {what, at {x, h}, vec {x, h}, unit}, where the force acts, in N (velocities in m/s). With
// `impulses` (an impact's, as its event holds them, N s) the impulses instead, along the same
// lines. The magnitudes are the library's snapshot (tension, the contact forces, the velocities);
// here they get only their directions, from the scene's points.
val forces(val input, val state, double arm, double stop_height, val release, val impulses) {
  return guarded([&] {
    const Scenario& sc = drawn_scenario(input);
    const Machine& m = sc.machine;
    auto get = [&](const char* k) { return state[k].isNumber() ? state[k].as<double>() : 0.0; };
    Snapshot s;
    s.t = get("t"), s.x = get("x"), s.h = get("h"), s.phi_s = get("phi_s"), s.phi_l = get("phi_l");
    s.balloon_h = get("balloon_h"), s.balloon_x = get("balloon_x");
    s.rope_taut = get("rope_taut") != 0.0;
    viz::scene::Release r;
    r.latch = release["latch"].as<double>();
    r.off = release["off"].as<double>();
    const viz::scene::MovingParts mp = viz::scene::moving_parts(m, s, r, arm, stop_height);
    const auto unit = [](Vec2 v) {
      const double n = std::hypot(v.x, v.h);
      return n > 0 ? Vec2{v.x / n, v.h / n} : Vec2{0, 0};
    };
    const auto scaled = [](Vec2 v, double k) { return Vec2{v.x * k, v.h * k}; };
    val arrows = val::array();
    const auto arrow = [&](const char* what, Vec2 at, Vec2 vec, const char* u) {
      if (!(std::hypot(vec.x, vec.h) > 0.0)) return;
      val a = val::object();
      a.set("what", std::string(what));
      a.set("at", xy(at));
      a.set("vec", xy(vec));
      a.set("unit", std::string(u));
      arrows.call<void>("push", a);
    };
    // Directions: the rope from each of its ends inwards, the arm's normal (up from the bar) and
    // its line towards the pivot (the stop pushes the sandbag inwards), up from the floor.
    Vec2 to_rope_bag{0, 0}, to_rope_lid{0, 0}, knot = mp.lid_end;
    if (mp.rope.size() >= 2) {
      const bool bag_first = std::hypot(mp.rope.front().x - mp.sandbag.x, mp.rope.front().h - mp.sandbag.h) <=
                             std::hypot(mp.rope.back().x - mp.sandbag.x, mp.rope.back().h - mp.sandbag.h);
      const Vec2 a = bag_first ? mp.rope.front() : mp.rope.back(),
                 a1 = bag_first ? mp.rope[1] : mp.rope[mp.rope.size() - 2];
      const Vec2 b = bag_first ? mp.rope.back() : mp.rope.front(),
                 b1 = bag_first ? mp.rope[mp.rope.size() - 2] : mp.rope[1];
      to_rope_bag = unit({a1.x - a.x, a1.h - a.h});
      to_rope_lid = unit({b1.x - b.x, b1.h - b.h});
      knot = b;
    }
    const Vec2 along = unit({mp.arm_right.x - mp.arm_left.x, mp.arm_right.h - mp.arm_left.h});
    const Vec2 normal{-along.h, along.x};
    const Vec2 up{0, 1};
    const Vec2 grounded_end = mp.arm_left.h < mp.arm_right.h ? mp.arm_left : mp.arm_right;
    // The lid's edge moves across the lid at dphi_l times this (m per rad): the derivative of the
    // scene's lid_end along phi_l.
    const double d = 1e-6;
    const Vec2 e1 = viz::scene::lid_end(m, s.phi_l + d), e0 = viz::scene::lid_end(m, s.phi_l - d);
    const Vec2 edge_per_rad{(e1.x - e0.x) / (2 * d), (e1.h - e0.h) / (2 * d)};
    if (!impulses.isUndefined() && !impulses.isNull()) {
      auto imp = [&](const char* k) { return impulses[k].isNumber() ? impulses[k].as<double>() : 0.0; };
      arrow("impulse_sandbag", mp.sandbag, scaled(normal, imp("sandbag_N_s")), "N s");
      arrow("impulse_rope_on_sandbag", mp.sandbag, scaled(to_rope_bag, imp("rope_N_s")), "N s");
      arrow("impulse_rope_on_lid", knot, scaled(to_rope_lid, imp("rope_N_s")), "N s");
      arrow("impulse_stop", mp.sandbag, scaled(along, imp("stop_N_s")), "N s");
      arrow("impulse_floor_seesaw", grounded_end, scaled(up, imp("floor_seesaw_N_s")), "N s");
      arrow("impulse_floor_sandbag", mp.sandbag, scaled(up, imp("floor_sandbag_N_s")), "N s");
      // The lid's angular impulse about its hinge (N m s) as the impulse at its edge that has the
      // same moment: the latch's against the opening (at the latch's instant), the box's along it.
      const double lever = std::hypot(mp.lid_end.x - mp.hinge.x, mp.lid_end.h - mp.hinge.h);
      const Vec2 opening = unit(edge_per_rad);
      const bool latch = s.t >= r.latch;
      if (lever > 0)
        arrow(latch ? "impulse_latch_on_lid" : "impulse_box_on_lid", mp.lid_end,
              scaled(opening, (latch ? -1.0 : 1.0) * imp("lid_N_m_s") / lever), "N s");
    } else {
      const double g = m.gravity;
      arrow("weight_sandbag", mp.sandbag, {0, -m.sandbag_mass * g}, "N");
      arrow("weight_lid", {0.5 * (mp.hinge.x + mp.lid_end.x), 0.5 * (mp.hinge.h + mp.lid_end.h)},
            {0, -m.lid_mass * g}, "N");
      const Vec2 right = unit(mp.arm_right);
      arrow("weight_seesaw", scaled(right, m.seesaw_com_offset), {0, -m.seesaw_mass * g}, "N");
      const double tension = get("tension");
      arrow("tension_on_sandbag", mp.sandbag, scaled(to_rope_bag, tension), "N");
      arrow("tension_on_lid", knot, scaled(to_rope_lid, tension), "N");
      if (get("on_seesaw") != 0.0)
        arrow("arm_on_sandbag", mp.sandbag, scaled(normal, get("normal_force")), "N");
      arrow("stop_on_sandbag", mp.sandbag, scaled(along, get("stop_reaction")), "N");
      arrow("floor_on_seesaw", grounded_end, scaled(up, get("floor_reaction")), "N");
      arrow("floor_on_sandbag", mp.sandbag, scaled(up, get("bag_floor_reaction")), "N");
      arrow("velocity_sandbag", mp.sandbag, {get("vx"), get("vh")}, "m/s");
      arrow("velocity_lid_edge", mp.lid_end, scaled(edge_per_rad, get("dphi_l")), "m/s");
    }
    val v = val::object();
    v.set("ok", true);
    v.set("arrows", arrows);
    return v;
  });
}

// The left arm's drawn length and the end stop's height, as the animation draws them
// (src/viz/scene.hpp drawn_arm, stop_height): leftArm is the machine's seesaw_left_arm (Infinity:
// endless), farthest how far out the sandbag has been on the arm so far.
double drawn_arm(double left_arm, double endless, double farthest) {
  return viz::scene::drawn_arm(left_arm, endless, farthest);
}
double stop_height(double scale) { return viz::scene::stop_height(scale); }

// The points of the scene that frame the picture, for many states at once (a call per state would
// cost the page more than the points): the seesaw's right end, the lid's free edge and the
// balloon's centre at each (phi_s, phi_l, balloon_x, balloon_h) given, as columns
// {seesawX, seesawH, lidX, lidH, balloonX, balloonH}.
val scene_trace(val input, val phi_s, val phi_l, val balloon_x, val balloon_h) {
  return guarded([&] {
    const Machine& m = drawn_scenario(input).machine;
    const auto ps = emscripten::vecFromJSArray<double>(phi_s), pl = emscripten::vecFromJSArray<double>(phi_l);
    const auto bx = emscripten::vecFromJSArray<double>(balloon_x),
               bh = emscripten::vecFromJSArray<double>(balloon_h);
    std::vector<double> cols[6];
    for (std::size_t i = 0; i < ps.size(); ++i) {
      Snapshot s;
      s.balloon_x = bx[i], s.balloon_h = bh[i];
      const Vec2 e = viz::scene::seesaw_end(m, ps[i]), l = viz::scene::lid_end(m, pl[i]);
      const Vec2 c = viz::scene::balloon_centre(m, s);
      const double row[6] = {e.x, e.h, l.x, l.h, c.x, c.h};
      for (int k = 0; k < 6; ++k) cols[k].push_back(row[k]);
    }
    val v = val::object();
    v.set("ok", true);
    const char* names[] = {"seesawX", "seesawH", "lidX", "lidH", "balloonX", "balloonH"};
    for (int k = 0; k < 6; ++k) {
      v.set(names[k],
            val::global("Float64Array").new_(emscripten::typed_memory_view(cols[k].size(), cols[k].data())));
    }
    return v;
  });
}

// The parts' colours as `whatnext animate` paints them (scene.hpp): {sandbag: "rgb(204,127,0)", ...}.
val colours() {
  val v = val::object();
  for (const viz::scene::NamedColour& c : viz::scene::kColourNames) {
    v.set(std::string(c.name), "rgb(" + std::to_string(c.rgb.r) + "," + std::to_string(c.rgb.g) + "," +
                                   std::to_string(c.rgb.b) + ")");
  }
  return v;
}

// The downloads, as `whatnext run` writes them: TOML (to_toml), --events JSON, --csv.
val toml(val input) {
  return guarded([&] { return text_result(to_toml(load(input).scenario)); });
}

val events(val input) {
  return guarded([&] {
    const Input in = load(input);
    return text_result(events_json(simulate(in.scenario), in.scenario, in.label));
  });
}

val csv(val input) {
  return guarded([&] {
    const Input in = load(input);
    std::ostringstream out;
    CsvWriter writer(out, Writing::at_once, impulse_columns(in.scenario.machine));
    simulate(in.scenario, &writer);
    return text_result(out.str());
  });
}

// Every input key, in documentation order: {key, kind, unit, help}.
val keys() {
  static const char* const kKinds[] = {"length",       "mass",     "density", "angle", "time",
                                       "acceleration", "positive", "text",    "pair",  "flag"};
  val out = val::array();
  for (const KeySpec& k : known_keys()) {
    val v = val::object();
    v.set("key", std::string(k.key));
    v.set("kind", std::string(kKinds[static_cast<int>(k.kind)]));
    v.set("unit", std::string(k.unit));
    v.set("help", std::string(k.help));
    v.set("default", std::string(k.default_text));  // what a blank field means (the panel)
    out.call<void>("push", v);
  }
  return out;
}

// The names an input may give for the text keys, and the modes in words.
val names() {
  val out = val::object();
  auto list = [](auto... items) {
    val a = val::array();
    (a.call<void>("push", std::string(to_string(items))), ...);
    return a;
  };
  out.set("run.impact_law", list(ImpactLaw::rope, ImpactLaw::angular_momentum_sum, ImpactLaw::kinetic_energy,
                                 ImpactLaw::linear_momentum));
  out.set("run.integrator", list(IntegratorKind::adaptive, IntegratorKind::euler, IntegratorKind::rk4));
  out.set("balloon.model", list(BalloonModel::program, BalloonModel::lagrangian, BalloonModel::added_mass));
  val modes = val::object();
  for (Mode m : {Mode::M1, Mode::M2, Mode::M3, Mode::M4, Mode::M5}) {
    modes.set(static_cast<int>(m), viz::mode_words(m));
  }
  out.set("modes", modes);
  // The words of every mode with the built machine's contacts (viz::mode_words), keyed
  // "mode,at_stop,bag_on_floor,seesaw_on_floor,rope_let_go" (0 or 1 each): the page's caption.
  val contacts = val::object();
  for (Mode m : {Mode::M1, Mode::M2, Mode::M3, Mode::M4, Mode::M5}) {
    for (int bits = 0; bits < 16; ++bits) {
      Snapshot s;
      s.mode = m;
      s.at_stop = bits & 1, s.bag_on_floor = bits & 2, s.seesaw_on_floor = bits & 4, s.rope_let_go = bits & 8;
      contacts.set(std::to_string(static_cast<int>(m)) + ',' + std::to_string(bits & 1) + ',' +
                       std::to_string((bits >> 1) & 1) + ',' + std::to_string((bits >> 2) & 1) + ',' +
                       std::to_string((bits >> 3) & 1),
                   viz::mode_words(s));
    }
  }
  out.set("modeWords", contacts);
  return out;
}

// The shipped machines: the paper's examples as `--example N` reads them, and the radio example.
val presets() {
  auto preset = [](const std::string& id, const std::string& title, std::string_view text,
                   const std::string& source, const std::string& label, const std::string& cli) {
    val v = val::object();
    v.set("id", id);
    v.set("title", title);
    v.set("toml", std::string(text));
    v.set("source", source);
    v.set("label", label);
    v.set("cli", cli);
    return v;
  };
  val out = val::array();
  for (int n = 1; n <= 4; ++n) {
    const std::string num = std::to_string(n);
    out.call<void>("push", preset("example" + num, "Example " + num, example_toml(n),
                                  "example" + num + ".toml", "example " + num, "--example " + num));
  }
  const std::string radio = "examples/example1-radio.toml";
  out.call<void>("push",
                 preset("radio", "Example 1 with the radio", radio_example_toml(), radio, radio, radio));
  out.call<void>("push", preset("konstanz", "The students' machine (Konstanz)", example_toml("konstanz"),
                                "konstanz.toml", "example konstanz", "--example konstanz"));
  return out;
}

}  // namespace

EMSCRIPTEN_BINDINGS(whatnext) {
  emscripten::function("run", &run);
  emscripten::function("plan", &plan);
  emscripten::function("toml", &toml);
  emscripten::function("events", &events);
  emscripten::function("csv", &csv);
  emscripten::function("keys", &keys);
  emscripten::function("presets", &presets);
  emscripten::function("names", &names);
  emscripten::function("scene", &scene);
  emscripten::function("sceneTrace", &scene_trace);
  emscripten::function("forces", &forces);
  emscripten::function("drawnArm", &drawn_arm);
  emscripten::function("stopHeight", &stop_height);
  emscripten::function("colours", &colours);
}

}  // namespace whatnext::web
