// The page's map and phase plots (web/src/map.js, phase.js), through the library's own sweep
// (include/whatnext/explore/sweep.hpp): a map is `whatnext sweep` over two --vary keys, its
// machines run a block at a time in the map's Web Workers, and every block comes back as one
// typed array of numbers and the CSV rows the command's own writer makes for those machines, so
// that the map's download is the command's file (its numbers as WebAssembly's maths library gives
// them: web/tests/map.js says how close). The phase plots get a run's samples in the
// columns of `whatnext run --csv` (columns.hpp), in the CSV's units.
#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <exception>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "whatnext/columns.hpp"
#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/simulate.hpp"
#include "page_input.hpp"

namespace whatnext::web {

namespace {

using emscripten::val;

val f64(const std::vector<double>& v) {  // a copy, independent of the wasm memory
  return val::global("Float64Array").new_(emscripten::typed_memory_view(v.size(), v.data()));
}

val words(const std::vector<std::string>& v) {
  val a = val::array();
  for (const std::string& s : v) a.call<void>("push", s);
  return a;
}

// The map a worker is running: the machine and the plan, kept between its blocks.
struct Map {
  Config base;
  std::unique_ptr<explore::Machines> machines;
  std::vector<std::string> keys;
};
Map& current() {
  static Map map;
  return map;
}

// Sets up the map of `input` over `vary` (["KEY=A:B:N", ...], as `whatnext sweep --vary` takes
// them, the last varying fastest): {ok, size, header, axes: [Float64Array per key], events:
// [event names], stride} or the command's message. The axes are the values the machines get.
// Every machine's numbers come back from mapBlock in rows of `stride`: the outcome (its index in
// events, -1 invalid, -2 failed), outcome_t, final_r, final_phi_l_deg, then the first time of
// each event (NaN: it did not happen), as the CSV's columns.
val map_start(val input, val vary) {
  return guarded([&] {
    Map& m = current();
    m.machines.reset();
    m.base = config_of(input);
    build_scenario(m.base);  // the machine itself must be one (as the command refuses a bad file)
    explore::Plan plan;
    for (const std::string& spec : emscripten::vecFromJSArray<std::string>(vary))
      plan.ranges.push_back(explore::parse_range(spec, "--vary", true));
    m.machines = std::make_unique<explore::Machines>(plan);
    m.keys = plan.keys();
    val r = val::object();
    r.set("ok", true);
    r.set("size", static_cast<double>(m.machines->size()));
    r.set("header", explore::csv_header(plan));
    val axes = val::array();
    std::int64_t step = m.machines->size();
    std::vector<double> point(m.keys.size());
    for (std::size_t d = 0; d < plan.ranges.size(); ++d) {
      step /= plan.ranges[d].n;  // machine j * step has value j of this key, the others first
      std::vector<double> axis;
      for (int j = 0; j < plan.ranges[d].n; ++j) {
        m.machines->point(j * step, point.data());
        axis.push_back(point[d]);
      }
      axes.call<void>("push", f64(axis));
    }
    r.set("axes", axes);
    std::vector<std::string> names;
    for (EventType t : explore::event_types()) names.emplace_back(to_string(t));
    r.set("events", words(names));
    r.set("stride", static_cast<double>(4 + names.size()));
    return r;
  });
}

// Runs machines start..end-1 of the map: {ok, numbers: Float64Array (end - start rows of stride),
// rows: their CSV lines as `whatnext sweep` writes them, errors: [[index, message], ...] for the
// machines that did not run (invalid inputs and failed runs)}.
val map_block(double start, double end) {
  return guarded([&] {
    Map& m = current();
    if (!m.machines) throw std::runtime_error("no map started");
    const auto& types = explore::event_types();
    std::vector<double> numbers, values(m.keys.size());
    std::string rows;
    val errors = val::array();
    for (auto i = static_cast<std::int64_t>(start); i < static_cast<std::int64_t>(end); ++i) {
      m.machines->point(i, values.data());
      const explore::Outcome o = explore::evaluate(m.base, m.keys, values.data());
      rows += explore::csv_row(i, values, o);
      double code = o.failed ? -2.0 : -1.0;
      for (std::size_t k = 0; o.valid && k < types.size(); ++k) {
        if (types[k] == o.outcome) code = static_cast<double>(k);
      }
      numbers.push_back(code);
      numbers.push_back(o.valid ? o.outcome_t : NAN);
      numbers.push_back(o.valid ? o.final_r : NAN);
      numbers.push_back(o.valid ? o.final_phi_l_deg : NAN);
      numbers.insert(numbers.end(), o.first.begin(), o.first.end());
      if (!o.valid) {
        val e = val::array();
        e.call<void>("push", static_cast<double>(i));
        e.call<void>("push", o.error);
        errors.call<void>("push", e);
      }
    }
    val r = val::object();
    r.set("ok", true);
    r.set("numbers", f64(numbers));
    r.set("rows", rows);
    r.set("errors", errors);
    return r;
  });
}

// A run's samples and event states in the CSV's numeric columns (t_s, then columns.hpp's state
// columns, in their units), every stride-th sample kept so that at most about maxRows come back.
class Table : public Observer {
 public:
  explicit Table(long stride) : stride_(stride), data_(1 + state_columns().size()) {}
  void on_sample(const Snapshot& s) override {
    if (samples_++ % stride_ == 0) add(s, "");
  }
  void on_event(const Event& e) override { add(e.after, std::string(to_string(e.type))); }
  val to_js() const {
    val data = val::array();
    for (const std::vector<double>& c : data_) data.call<void>("push", f64(c));
    val r = val::object();
    r.set("data", data);
    r.set("event", words(event_));
    return r;
  }

 private:
  void add(const Snapshot& s, std::string event) {
    data_[0].push_back(s.t);
    for (std::size_t c = 0; c < state_columns().size(); ++c)
      data_[c + 1].push_back(state_columns()[c].value(s));
    event_.push_back(std::move(event));
  }
  long stride_, samples_ = 0;
  std::vector<std::vector<double>> data_;
  std::vector<std::string> event_;
};

// The columns a phase plot may use: [{name, unit, meaning}], t_s first.
val phase_columns() {
  val out = val::array();
  auto column = [&out](std::string_view name, std::string_view unit, std::string_view meaning) {
    val c = val::object();
    c.set("name", std::string(name));
    c.set("unit", std::string(unit));
    c.set("meaning", std::string(meaning));
    out.call<void>("push", c);
  };
  column(kLeadingColumns[0], "s", "time");
  for (const StateColumn& c : state_columns()) column(c.name, c.unit, c.meaning);
  return out;
}

// The run of `input` in those columns: {ok, data: [Float64Array per column], event: ["" or the
// event's name per row]}.
val phase_table(val input, double max_rows) {
  return guarded([&] {
    const Scenario sc = build_scenario(config_of(input));
    const double rows = sc.run.t_max / sc.run.output_step;
    Table table(std::max(1L, static_cast<long>(std::ceil(rows / std::max(1.0, max_rows)))));
    simulate(sc, &table);
    val r = table.to_js();
    r.set("ok", true);
    return r;
  });
}

}  // namespace

EMSCRIPTEN_BINDINGS(whatnext_map) {
  emscripten::function("mapStart", &map_start);
  emscripten::function("mapBlock", &map_block);
  emscripten::function("phaseColumns", &phase_columns);
  emscripten::function("phaseTable", &phase_table);
}

}  // namespace whatnext::web
