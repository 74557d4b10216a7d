// The compiled half of the Python module (whatnext._core): validated machines, one run with its
// samples filled into numpy buffers here, and sweeps on all cores with the GIL released. The public
// API, its docstrings and the plots are Python (python/whatnext/); this file only moves data.
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdint>
#include <functional>
#include <iterator>
#include <limits>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace py = pybind11;

namespace whatnext::python {

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;
constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

// A validated machine: the input as given (so that further overrides are checked, and named in
// messages, exactly as the CLI's --set), the overrides applied to it so far and the scenario built
// from it.
struct MachineHandle {
  Config config;
  Scenario scenario;
  std::string origin;             // "example 1", a path, "whatnext.machine()"
  std::vector<std::string> sets;  // the "KEY=VALUE" overrides, in order, as --set takes them
  std::string source;             // the timeline's and the events JSON's "input", as the CLI names it
};

MachineHandle make_machine(Config config, std::string origin, std::vector<std::string> sets = {}) {
  MachineHandle m{std::move(config), Scenario{}, std::move(origin), std::move(sets), {}};
  m.scenario = build_scenario(m.config);
  m.source = input_label(m.origin, m.sets);  // "example 2 with --set geometry.rope_length=0.7"
  return m;
}

// Applies "KEY=VALUE" overrides (VALUE as TOML, bare words as text) to a copy: the CLI's --set.
MachineHandle with_set(const MachineHandle& base, const std::vector<std::string>& assignments) {
  Config config = base.config;
  for (const std::string& a : assignments) apply_set(config, a);
  std::vector<std::string> sets = base.sets;
  sets.insert(sets.end(), assignments.begin(), assignments.end());
  return make_machine(std::move(config), base.origin, std::move(sets));
}

// The keys the input gives, in inputs.md's units (degrees for angles), as Python values.
py::dict inputs_of(const MachineHandle& m) {
  py::dict out;
  for (const auto& [key, v] : m.config.values) {
    const KeySpec* spec = find_key(key);
    if (v.type == ConfigValue::Type::text) {
      out[py::str(key)] = py::str(v.text);
    } else if (v.type == ConfigValue::Type::pair) {
      out[py::str(key)] = py::make_tuple(v.pair[0], v.pair[1]);
    } else if (spec && spec->kind == KeyKind::flag) {
      out[py::str(key)] = py::bool_(v.number != 0.0);
    } else {
      out[py::str(key)] = py::float_(v.number);
    }
  }
  return out;
}

// --- samples ------------------------------------------------------------------------------------

// The CSV's numeric columns after t_s, event, mode and rope_taut, computed as CsvWriter computes
// them; their names are read from CsvWriter::header() so that the two cannot drift apart silently
// (module import fails if the counts differ, the tests compare the values with the CLI's CSV).
using Getter = double (*)(const Snapshot&);
constexpr Getter kNumeric[] = {
    [](const Snapshot& s) { return s.x; },
    [](const Snapshot& s) { return s.h; },
    [](const Snapshot& s) { return s.r; },
    [](const Snapshot& s) { return s.dr; },
    [](const Snapshot& s) { return s.phi_s * kDeg; },
    [](const Snapshot& s) { return s.dphi_s * kDeg; },
    [](const Snapshot& s) { return s.phi_l * kDeg; },
    [](const Snapshot& s) { return s.dphi_l * kDeg; },
    [](const Snapshot& s) { return s.balloon_h; },
    [](const Snapshot& s) { return s.balloon_v; },
    [](const Snapshot& s) { return s.balloon_limit; },
    [](const Snapshot& s) { return s.tension; },
    [](const Snapshot& s) { return s.energy(); },
    [](const Snapshot& s) { return s.sandbag_kinetic; },
    [](const Snapshot& s) { return s.sandbag_potential; },
    [](const Snapshot& s) { return s.lid_kinetic; },
    [](const Snapshot& s) { return s.lid_potential; },
    [](const Snapshot& s) { return s.seesaw_kinetic; },
    [](const Snapshot& s) { return s.seesaw_potential; },
    [](const Snapshot& s) { return s.balloon_kinetic; },
    [](const Snapshot& s) { return s.balloon_potential; },
    [](const Snapshot& s) { return s.lost_impacts; },
    [](const Snapshot& s) { return s.lost_balloon_catch; },
    [](const Snapshot& s) { return s.dissipated_pivot; },
    [](const Snapshot& s) { return s.dissipated_hinge; },
    [](const Snapshot& s) { return s.dissipated_drag; },
    [](const Snapshot& s) { return s.lid_push_work; },
    [](const Snapshot& s) { return s.ledger_residual(); },
};
constexpr std::size_t kNumericCount = std::size(kNumeric);
constexpr const char* kLeading[] = {"t_s", "event", "mode", "rope_taut"};

const std::vector<std::string>& column_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    std::string_view header = CsvWriter::header();
    for (;;) {
      const auto comma = header.find(',');
      out.emplace_back(header.substr(0, comma));
      if (comma == std::string_view::npos) break;
      header = header.substr(comma + 1);
    }
    return out;
  }();
  return names;
}

void check_columns() {
  const auto& names = column_names();
  bool ok = names.size() == std::size(kLeading) + kNumericCount;
  for (std::size_t i = 0; ok && i < std::size(kLeading); ++i) ok = names[i] == kLeading[i];
  if (!ok) {
    throw std::runtime_error(fmt::format(
        "whatnext._core: the CSV has {} columns ({}), the module knows {}; update kNumeric in bindings.cpp",
        names.size(), CsvWriter::header(), std::size(kLeading) + kNumericCount));
  }
}

// A numpy array that owns the vector's buffer: no copy, freed with the array.
template <class T>
py::array adopt(std::vector<T>&& v, py::dtype dtype) {
  auto* owned = new std::vector<T>(std::move(v));
  py::capsule owner(owned, [](void* p) { delete static_cast<std::vector<T>*>(p); });
  return py::array(std::move(dtype), {owned->size()}, {sizeof(T)}, owned->data(), owner);
}

// A numpy array of fixed-width strings (dtype <U width) from ASCII names, written here.
py::array name_array(const std::vector<std::string_view>& names) {
  std::size_t width = 1;
  for (std::string_view s : names) width = std::max(width, s.size());
  py::array a(py::dtype(fmt::format("<U{}", width)), std::vector<py::ssize_t>{static_cast<py::ssize_t>(names.size())});
  auto* p = static_cast<std::uint32_t*>(a.mutable_data());
  std::fill(p, p + names.size() * width, 0u);
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < names[i].size(); ++j) p[i * width + j] = static_cast<unsigned char>(names[i][j]);
  }
  return a;
}

// The same for any UTF-8 text (error messages may quote paths); empty entries stay empty.
py::array text_array(const std::vector<std::string>& texts) {
  std::vector<py::str> decoded(texts.size());
  std::size_t width = 1;
  for (std::size_t i = 0; i < texts.size(); ++i) {
    if (texts[i].empty()) continue;
    // "replace": a path with bytes that are not UTF-8 must not turn a whole sweep into an exception.
    decoded[i] = py::reinterpret_steal<py::str>(
        PyUnicode_DecodeUTF8(texts[i].data(), static_cast<Py_ssize_t>(texts[i].size()), "replace"));
    if (!decoded[i]) throw py::error_already_set();
    width = std::max(width, static_cast<std::size_t>(PyUnicode_GetLength(decoded[i].ptr())));
  }
  py::array a(py::dtype(fmt::format("<U{}", width)), std::vector<py::ssize_t>{static_cast<py::ssize_t>(texts.size())});
  auto* p = static_cast<Py_UCS4*>(a.mutable_data());
  std::fill(p, p + texts.size() * width, Py_UCS4{0});
  for (std::size_t i = 0; i < texts.size(); ++i) {
    if (texts[i].empty()) continue;
    if (!PyUnicode_AsUCS4(decoded[i].ptr(), p + i * width, static_cast<Py_ssize_t>(width), 0)) {
      throw py::error_already_set();
    }
  }
  return a;
}

// Keeps the run's CSV rows as columns: a row per output sample and one right after each event.
class ColumnRecorder : public Observer {
 public:
  ColumnRecorder() : numeric_(kNumericCount) {}
  void reserve(std::size_t rows) {
    t_.reserve(rows), event_.reserve(rows), mode_.reserve(rows), taut_.reserve(rows);
    for (auto& c : numeric_) c.reserve(rows);
  }
  void on_sample(const Snapshot& s) override { row(s, ""); }
  void on_event(const Event& e) override { row(e.after, to_string(e.type)); }

  py::dict take() {
    py::dict out;
    const auto& names = column_names();
    std::vector<std::string_view> modes(mode_.size());
    for (std::size_t i = 0; i < mode_.size(); ++i) modes[i] = to_string(mode_[i]);
    out[py::str(names[0])] = adopt(std::move(t_), py::dtype::of<double>());
    out[py::str(names[1])] = name_array(event_);
    out[py::str(names[2])] = name_array(modes);
    out[py::str(names[3])] = adopt(std::move(taut_), py::dtype::of<bool>());
    for (std::size_t c = 0; c < kNumericCount; ++c) {
      out[py::str(names[std::size(kLeading) + c])] = adopt(std::move(numeric_[c]), py::dtype::of<double>());
    }
    return out;
  }

 private:
  void row(const Snapshot& s, std::string_view event) {
    t_.push_back(s.t);
    event_.push_back(event);
    mode_.push_back(s.mode);
    taut_.push_back(s.rope_taut ? 1 : 0);
    for (std::size_t c = 0; c < kNumericCount; ++c) numeric_[c].push_back(kNumeric[c](s));
  }
  std::vector<double> t_;
  std::vector<std::string_view> event_;  // names live in the static names table
  std::vector<Mode> mode_;
  std::vector<std::uint8_t> taut_;  // numpy bool is one byte
  std::vector<std::vector<double>> numeric_;
};

// An event's state with the CSV's column names.
py::dict state_of(const Snapshot& s) {
  py::dict d;
  const auto& names = column_names();
  d["t_s"] = s.t;
  d["mode"] = py::str(std::string(to_string(s.mode)));
  d["rope_taut"] = s.rope_taut;
  for (std::size_t c = 0; c < kNumericCount; ++c) d[py::str(names[std::size(kLeading) + c])] = kNumeric[c](s);
  return d;
}

py::dict run_machine(const MachineHandle& m, bool samples) {
  Result result;
  ColumnRecorder rec;
  {
    py::gil_scoped_release nogil;
    if (samples) {  // the rows up to t_max, but not gigabytes for a run that may stop early
      const RunSettings& r = m.scenario.run;
      rec.reserve(static_cast<std::size_t>(std::min(1e5, r.t_max / r.output_step)) + 64);
    }
    result = simulate(m.scenario, samples ? &rec : nullptr);
  }
  py::list events;
  for (const Event& e : result.events) {
    py::dict d;
    d["type"] = py::str(std::string(to_string(e.type)));
    d["time"] = e.t;
    d["mode_before"] = py::str(std::string(to_string(e.mode_before)));
    d["mode_after"] = py::str(std::string(to_string(e.mode_after)));
    d["impact"] = e.impact;
    d["energy_before"] = e.energy_before;
    d["energy_after"] = e.energy_after;
    d["state"] = state_of(e.after);
    events.append(std::move(d));
  }
  const Event& last = result.outcome();
  py::dict out;
  out["outcome"] = py::make_tuple(std::string(to_string(last.type)), last.t, outcome_sentence(result));
  out["events"] = events;
  out["samples"] = samples ? py::object(rec.take()) : py::object(py::none());
  out["timeline"] = timeline_text(result, m.scenario, m.source);
  out["events_json"] = events_json(result, m.scenario, m.source);
  return out;
}

// --- sweeps -------------------------------------------------------------------------------------

// The values of machine i, one per key, written to out.
using PointFn = std::function<void(std::int64_t, double*)>;

// Every key must be one the inputs hold as a single number (set_number's rule, as the CLI's
// --vary): one line naming the key otherwise.
void check_sweep_keys(const std::vector<std::string>& keys) {
  if (keys.empty()) throw InputError("sweep: give at least one key to vary");
  Config probe;
  for (const std::string& k : keys) set_number(probe, k, 0.0);
}

// Runs machines 0..n-1 on `threads` threads with explore::evaluate, the GIL released; Ctrl-C
// (checked ten times a second on the calling thread) stops the workers and raises KeyboardInterrupt.
// Rows land in their own slots, so they do not depend on the thread count.
// Each machine runs to the event-time accuracy given (explore::apply_accuracy; none: the machine's
// own run settings).
std::vector<explore::Outcome> run_points(const MachineHandle& m, const std::vector<std::string>& keys,
                                         std::int64_t n, const PointFn& point, int threads,
                                         std::optional<double> accuracy_given) {
  if (accuracy_given) explore::check_accuracy(*accuracy_given, "sweep: accuracy");
  const double accuracy = accuracy_given.value_or(0.0);
  std::vector<explore::Outcome> rows(static_cast<std::size_t>(n));
  if (threads <= 0) threads = static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  threads = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(threads, n)));
  std::atomic<std::int64_t> next{0};
  std::atomic<bool> stop{false};
  bool interrupted = false;
  {
    py::gil_scoped_release nogil;
    std::mutex mu;
    std::condition_variable cv;
    int running = threads;
    auto worker = [&] {
      std::vector<double> values(keys.size());
      for (std::int64_t i = next.fetch_add(1); i < n && !stop.load(std::memory_order_relaxed);
           i = next.fetch_add(1)) {
        point(i, values.data());
        rows[static_cast<std::size_t>(i)] = explore::evaluate(m.config, keys, values.data(), accuracy);
      }
      std::lock_guard<std::mutex> lock(mu);
      --running;
      cv.notify_all();
    };
    std::vector<std::thread> pool;
    for (int i = 0; i < threads; ++i) pool.emplace_back(worker);
    std::unique_lock<std::mutex> lock(mu);
    while (running > 0) {
      if (cv.wait_for(lock, std::chrono::milliseconds(100), [&] { return running == 0; })) break;
      if (!interrupted) {
        lock.unlock();
        {
          py::gil_scoped_acquire gil;
          interrupted = PyErr_CheckSignals() != 0;  // keeps the exception set for below
        }
        if (interrupted) stop.store(true);
        lock.lock();
      }
    }
    lock.unlock();
    for (std::thread& t : pool) t.join();
  }
  if (interrupted) throw py::error_already_set();
  return rows;
}

// The sweep CSV's columns (explore::write_csv) as numpy arrays: index, the varied keys, outcome,
// outcome_t, final_r, final_phi_l_deg, an event column per event type (first time, NaN if none)
// and error. An invalid machine has outcome "invalid", NaN times and its one-line reason.
py::dict sweep_columns(const std::vector<std::string>& keys, std::int64_t n, const PointFn& point,
                       const std::vector<explore::Outcome>& rows) {
  const auto& types = explore::event_types();
  const auto un = static_cast<std::size_t>(n);
  std::vector<std::int64_t> index(un);
  std::vector<std::vector<double>> values(keys.size(), std::vector<double>(un));
  std::vector<std::string_view> outcome(un);
  std::vector<double> outcome_t(un), final_r(un), final_phi(un);
  std::vector<std::vector<double>> first(types.size(), std::vector<double>(un));
  std::vector<std::string> error(un);
  std::vector<double> v(keys.size());
  for (std::size_t i = 0; i < un; ++i) {
    const explore::Outcome& o = rows[i];
    index[i] = static_cast<std::int64_t>(i);
    point(static_cast<std::int64_t>(i), v.data());
    for (std::size_t k = 0; k < keys.size(); ++k) values[k][i] = v[k];
    outcome[i] = o.valid ? to_string(o.outcome) : std::string_view("invalid");
    outcome_t[i] = o.valid ? o.outcome_t : kNaN;
    final_r[i] = o.valid ? o.final_r : kNaN;
    final_phi[i] = o.valid ? o.final_phi_l_deg : kNaN;
    for (std::size_t e = 0; e < types.size(); ++e) first[e][i] = o.valid ? o.first[e] : kNaN;
    error[i] = o.error;
  }
  py::dict out;
  out["index"] = adopt(std::move(index), py::dtype::of<std::int64_t>());
  for (std::size_t k = 0; k < keys.size(); ++k) out[py::str(keys[k])] = adopt(std::move(values[k]), py::dtype::of<double>());
  out["outcome"] = name_array(outcome);
  out["outcome_t"] = adopt(std::move(outcome_t), py::dtype::of<double>());
  out["final_r"] = adopt(std::move(final_r), py::dtype::of<double>());
  out["final_phi_l_deg"] = adopt(std::move(final_phi), py::dtype::of<double>());
  for (std::size_t e = 0; e < types.size(); ++e) {
    out[py::str(std::string(to_string(types[e])))] = adopt(std::move(first[e]), py::dtype::of<double>());
  }
  out["error"] = text_array(error);
  return out;
}

using Axis = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The full grid over explicit values per key; the last key varies fastest (as the CLI's grid).
py::dict sweep_grid(const MachineHandle& m, const std::vector<std::string>& keys,
                    const std::vector<Axis>& axes, int threads, std::optional<double> accuracy) {
  check_sweep_keys(keys);
  if (axes.size() != keys.size()) throw std::invalid_argument("sweep: one array of values per key");
  std::vector<std::vector<double>> grid(keys.size());
  std::int64_t n = 1;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (axes[k].ndim() != 1 || axes[k].size() == 0) {
      throw InputError(fmt::format("sweep: {} needs a one-dimensional sequence of at least one value", keys[k]));
    }
    grid[k].assign(axes[k].data(), axes[k].data() + axes[k].size());
    const auto size = static_cast<std::int64_t>(grid[k].size());
    if (n > explore::kMaxMachines / size) {
      throw InputError(fmt::format("sweep: the grid has more than {} machines; use fewer values", explore::kMaxMachines));
    }
    n *= size;
  }
  const PointFn point = [&grid](std::int64_t i, double* out) {
    for (std::size_t d = grid.size(); d-- > 0;) {
      const auto size = static_cast<std::int64_t>(grid[d].size());
      out[d] = grid[d][static_cast<std::size_t>(i % size)];
      i /= size;
    }
  };
  const auto rows = run_points(m, keys, n, point, threads, accuracy);
  return sweep_columns(keys, n, point, rows);
}

// A Latin hypercube of `samples` machines over "KEY=A:B" ranges (the CLI's --samples/--seed).
py::dict sweep_lhs(const MachineHandle& m, const std::vector<std::string>& specs, std::int64_t samples,
                   std::uint64_t seed, int threads, std::optional<double> accuracy) {
  explore::Plan plan;
  plan.samples = samples;
  plan.seed = seed;
  if (samples < 1) throw InputError(fmt::format("--samples: needs at least 1 machine (given {})", samples));
  for (const std::string& s : specs) plan.ranges.push_back(explore::parse_range(s, "--vary", false));
  const explore::Machines machines(plan);
  const PointFn point = [&machines](std::int64_t i, double* out) { machines.point(i, out); };
  const auto keys = plan.keys();
  const auto rows = run_points(m, keys, machines.size(), point, threads, accuracy);
  return sweep_columns(keys, machines.size(), point, rows);
}

// The n values of the CLI's --vary KEY=a:b:n grid, computed by the library (the same doubles).
py::array grid_values(double a, double b, int n) {
  if (!(std::isfinite(a) && std::isfinite(b) && a <= b) || n < 1) {
    throw InputError(fmt::format("grid: needs finite a <= b and n >= 1 (given a = {}, b = {}, n = {})", a, b, n));
  }
  explore::Plan plan;
  plan.ranges.push_back(explore::Range{"grid", a, b, n});
  const explore::Machines machines(plan);
  std::vector<double> values(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) machines.point(i, &values[static_cast<std::size_t>(i)]);
  return adopt(std::move(values), py::dtype::of<double>());
}

}  // namespace

}  // namespace whatnext::python

PYBIND11_MODULE(_core, mod) {
  using namespace whatnext;
  using namespace whatnext::python;
  mod.doc() = "whatnext's compiled core; use the `whatnext` package, not this module.";
  check_columns();

  py::register_exception<InputError>(mod, "InputError", PyExc_ValueError);
  py::register_exception<SimulationError>(mod, "SimulationError", PyExc_RuntimeError);

  py::class_<MachineHandle>(mod, "MachineHandle")
      .def("set", &with_set, py::arg("assignments"))
      .def("to_toml", [](const MachineHandle& m) { return to_toml(m.scenario); })
      .def("inputs", &inputs_of)
      .def_readonly("source", &MachineHandle::source)
      .def_property_readonly("seesaw_right_arm",
                             [](const MachineHandle& m) { return m.scenario.machine.seesaw_right_arm; });

  mod.def("example", [](int n) { return make_machine(example_config(n), fmt::format("example {}", n)); },
          py::arg("n"));
  mod.def("load", [](const std::string& path) { return make_machine(load_config_file(path), path); },
          py::arg("path"));
  mod.def("defaults", [](const std::string& source) { return make_machine(parse_toml("", source), source); },
          py::arg("source"));
  mod.def("known_keys", [] {
    py::list out;
    for (const KeySpec& k : known_keys()) {
      out.append(py::make_tuple(std::string(k.key), std::string(k.unit), std::string(k.help)));
    }
    return out;
  });
  mod.def("simulate", &run_machine, py::arg("machine"), py::arg("samples"));
  mod.def("sweep_grid", &sweep_grid, py::arg("machine"), py::arg("keys"), py::arg("axes"), py::arg("threads"),
          py::arg("accuracy"));
  mod.def("sweep_lhs", &sweep_lhs, py::arg("machine"), py::arg("specs"), py::arg("samples"), py::arg("seed"),
          py::arg("threads"), py::arg("accuracy"));
  mod.attr("DEFAULT_ACCURACY") = explore::kDefaultAccuracy;
  mod.def("grid_values", &grid_values, py::arg("a"), py::arg("b"), py::arg("n"));
  mod.def("csv_columns", [] { return column_names(); });
}
