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
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "whatnext/units.hpp"
#include "whatnext/columns.hpp"
#include "whatnext/config.hpp"
#include "whatnext/explore/pool.hpp"
#include "whatnext/explore/sweep_job.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

namespace py = pybind11;

namespace whatnext::python {

namespace {

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

// A message of the library's --set (apply_set names "--set KEY=VALUE", or "--set" alone for an
// unknown key) in the Python call's words: `label` ("set('masses.lid', -0.5)").
std::string relabel(const std::string& message, const std::string& assignment, const std::string& label) {
  for (const std::string& prefix : {"--set " + printable(assignment) + ":", std::string("--set:")}) {
    if (message.compare(0, prefix.size(), prefix) == 0) return label + ":" + message.substr(prefix.size());
  }
  return message;
}

// Applies "KEY=VALUE" overrides (VALUE as TOML, bare words as text) to a copy: the CLI's --set.
// Each value is then known by its label, the Python call that gave it, so that a rule it breaks
// (build_scenario's messages name a value's origin) is told in Python's words, never as a --set.
MachineHandle with_set(const MachineHandle& base, const std::vector<std::string>& assignments,
                       const std::vector<std::string>& labels) {
  if (labels.size() != assignments.size()) throw std::invalid_argument("set: one label per assignment");
  Config config = base.config;
  for (std::size_t i = 0; i < assignments.size(); ++i) {
    const std::string& a = assignments[i];
    try {
      apply_set(config, a);
    } catch (const InputError& e) {
      throw InputError(relabel(e.what(), a, labels[i]));
    }
    std::string key = a.substr(0, a.find('='));
    key.erase(0, key.find_first_not_of(" \t"));
    key.erase(key.find_last_not_of(" \t") + 1);
    if (auto it = config.values.find(key); it != config.values.end()) it->second.origin = labels[i];
  }
  std::vector<std::string> sets = base.sets;
  sets.insert(sets.end(), assignments.begin(), assignments.end());
  return make_machine(std::move(config), base.origin, std::move(sets));
}

// A machine as plain values, for pickle (Dask ships machines to its workers this way): the
// input's every value with its origin, so that the machine rebuilt from it is the same to the
// last bit and names its values in messages as before.
py::tuple machine_state(const MachineHandle& m) {
  py::list values;
  for (const auto& [key, v] : m.config.values) {
    values.append(
        py::make_tuple(key, static_cast<int>(v.type), v.number, v.text, v.pair[0], v.pair[1], v.origin));
  }
  return py::make_tuple(1, m.config.source, values, m.origin, m.sets);
}

MachineHandle machine_from_state(const py::tuple& state) {
  if (state.size() != 5 || state[0].cast<int>() != 1)
    throw std::runtime_error("whatnext: not a pickled Machine");
  Config config;
  config.source = state[1].cast<std::string>();
  for (const py::handle item : state[2].cast<py::list>()) {
    const auto t = item.cast<py::tuple>();
    ConfigValue v;
    v.type = static_cast<ConfigValue::Type>(t[1].cast<int>());
    v.number = t[2].cast<double>();
    v.text = t[3].cast<std::string>();
    v.pair[0] = t[4].cast<double>();
    v.pair[1] = t[5].cast<double>();
    v.origin = t[6].cast<std::string>();
    config.values[t[0].cast<std::string>()] = std::move(v);
  }
  return make_machine(std::move(config), state[3].cast<std::string>(),
                      state[4].cast<std::vector<std::string>>());
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
constexpr std::size_t kNumericCount = std::size(kStateColumns);  // whatnext/columns.hpp
constexpr const char* kLeading[] = {"t_s", "event", "mode", "rope_taut"};

const std::vector<std::string>& column_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    const std::string text = CsvWriter::header(std::size(kImpulseColumns));  // every column there is
    std::string_view header = text;
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
  bool ok = names.size() == std::size(kLeading) + kNumericCount + std::size(kImpulseColumns);
  for (std::size_t i = 0; ok && i < std::size(kLeading); ++i) ok = names[i] == kLeading[i];
  if (!ok) {
    throw std::runtime_error(fmt::format(
        "whatnext._core: the CSV has {} columns ({}), the module knows {}; the table is whatnext/columns.hpp",
        names.size(), CsvWriter::header(std::size(kImpulseColumns)),
        std::size(kLeading) + kNumericCount + std::size(kImpulseColumns)));
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
  py::array a(py::dtype(fmt::format("<U{}", width)),
              std::vector<py::ssize_t>{static_cast<py::ssize_t>(names.size())});
  auto* p = static_cast<std::uint32_t*>(a.mutable_data());
  std::fill(p, p + names.size() * width, 0u);
  for (std::size_t i = 0; i < names.size(); ++i) {
    for (std::size_t j = 0; j < names[i].size(); ++j)
      p[i * width + j] = static_cast<unsigned char>(names[i][j]);
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
  py::array a(py::dtype(fmt::format("<U{}", width)),
              std::vector<py::ssize_t>{static_cast<py::ssize_t>(texts.size())});
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

// An observer that lets Ctrl-C end the run: simulate() asks keep_going() every 256 steps, and
// at most every 20 ms this takes the GIL and runs Python's signal handlers. An exception they
// raise (KeyboardInterrupt) stays set and ends the run; run_machine raises it.
class Interruptible : public Observer {
 public:
  bool keep_going() override {
    const auto now = std::chrono::steady_clock::now();
    if (now < next_check_) return true;
    next_check_ = now + std::chrono::milliseconds(20);
    py::gil_scoped_acquire gil;
    return PyErr_CheckSignals() == 0;
  }

 private:
  std::chrono::steady_clock::time_point next_check_ = std::chrono::steady_clock::now();
};

// For runs without samples: only the checks above (run_machine samples it at most twice).
class EventsOnly : public Interruptible {
 public:
  Detail sample_detail() const override { return Detail::positions; }
  void on_samples(const SampleBatch&) override {}
};

// Keeps the run's CSV rows as columns: a row per output sample and one right after each event.
class ColumnRecorder : public Interruptible {
 public:
  // impulses: how many impulse columns the machine's CSV has (columns.hpp impulse_columns).
  explicit ColumnRecorder(std::size_t impulses) : impulses_(impulses), numeric_(kNumericCount) {}
  void reserve(std::size_t rows) {
    t_.reserve(rows), event_.reserve(rows), mode_.reserve(rows), taut_.reserve(rows);
    for (auto& c : numeric_) c.reserve(rows);
  }
  void on_sample(const Snapshot& s) override { row(s, "", nullptr); }
  void on_event(const Event& e) override {
    row(e.after, to_string(e.type), e.impact ? e.impulse.data() : nullptr);
  }

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
    for (std::size_t c = 0; c < impulses_; ++c) {
      out[py::str(std::string(kImpulseColumns[c]))] = adopt(std::move(impulse_[c]), py::dtype::of<double>());
    }
    return out;
  }

 private:
  void row(const Snapshot& s, std::string_view event, const double* impulses) {
    for (std::size_t c = 0; c < impulses_; ++c) impulse_[c].push_back(impulses ? impulses[c] : 0.0);
    t_.push_back(s.t);
    event_.push_back(event);
    mode_.push_back(s.mode);
    taut_.push_back(s.rope_taut ? 1 : 0);
    for (std::size_t c = 0; c < kNumericCount; ++c) numeric_[c].push_back(kStateColumns[c].value(s));
  }
  std::size_t impulses_;
  std::vector<double> t_;
  std::vector<std::string_view> event_;  // names live in the static names table
  std::vector<Mode> mode_;
  std::vector<std::uint8_t> taut_;  // numpy bool is one byte
  std::vector<std::vector<double>> numeric_;
  std::vector<double> impulse_[std::size(kImpulseColumns)];
};

// An event's state with the CSV's column names.
py::dict state_of(const Snapshot& s) {
  py::dict d;
  const auto& names = column_names();
  d["t_s"] = s.t;
  d["mode"] = py::str(std::string(to_string(s.mode)));
  d["rope_taut"] = s.rope_taut;
  for (std::size_t c = 0; c < kNumericCount; ++c)
    d[py::str(names[std::size(kLeading) + c])] = kStateColumns[c].value(s);
  return d;
}

py::dict run_machine(const MachineHandle& m, bool samples) {
  Result result;
  const std::size_t impulses = impulse_columns(m.scenario.machine);
  ColumnRecorder rec(impulses);
  EventsOnly events_only;
  try {
    py::gil_scoped_release nogil;
    if (samples) {  // the rows up to t_max, but not gigabytes for a run that may stop early
      const RunSettings& r = m.scenario.run;
      rec.reserve(static_cast<std::size_t>(std::min(1e5, r.t_max / r.output_step)) + 64);
      result = simulate(m.scenario, &rec);
    } else {
      // An observer (for Ctrl-C) is sampled on the output grid; one sample at the start and one
      // at t_max cost nothing, and the grid changes no step or event (simulate.cpp).
      Scenario sc = m.scenario;
      sc.run.output_step = sc.run.t_max;
      result = simulate(sc, &events_only);
    }
  } catch (const Cancelled&) {
    throw py::error_already_set();  // the KeyboardInterrupt that keep_going() found
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
    if (e.impact) {  // each contact's impulse and the law applied (docs/model.md §7)
      py::dict p;
      for (std::size_t i = 0; i < impulses; ++i) p[py::str(std::string(impulse_key(i)))] = e.impulse[i];
      d["impulses"] = p;
      d["law_applied"] = py::str(std::string(to_string(e.law)));
      d["law_note"] = py::str(std::string(e.law_note));
    }
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
// Every sweep here is the library's (explore/sweep_job.hpp): its machines, its worker pool, its
// rows and, written to a file, its resumable job. This only turns arrays into machines and rows
// into arrays.

using Axis = py::array_t<double, py::array::c_style | py::array::forcecast>;
using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Every key must be one the inputs hold as a single number (the CLI's --vary rule).
void check_sweep_keys(const std::vector<std::string>& keys) {
  if (keys.empty()) throw InputError("sweep: give at least one key to vary");
  for (const std::string& k : keys) explore::check_numeric_key(k, "sweep");
}

double accuracy_of(std::optional<double> given) {
  if (given) explore::check_accuracy(*given, "sweep: accuracy");
  return given.value_or(0.0);  // none: the machine's own run settings
}

// The machines of a grid (values per key; the last key varies fastest) or of points (a row of
// values per machine, numbered from `first`).
explore::Machines grid_machines(const std::vector<std::string>& keys, const std::vector<Axis>& axes) {
  check_sweep_keys(keys);
  if (axes.size() != keys.size()) throw std::invalid_argument("sweep: one array of values per key");
  std::vector<std::vector<double>> values;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (axes[k].ndim() != 1 || axes[k].size() == 0) {
      throw InputError(
          fmt::format("sweep: {} needs a one-dimensional sequence of at least one value", keys[k]));
    }
    values.emplace_back(axes[k].data(), axes[k].data() + axes[k].size());
  }
  return explore::Machines::grid_of(keys, std::move(values));
}

explore::Machines point_machines(const std::vector<std::string>& keys, const Points& points,
                                 std::int64_t first) {
  check_sweep_keys(keys);
  if (points.ndim() != 2 || points.shape(1) != static_cast<py::ssize_t>(keys.size()))
    throw std::invalid_argument("sweep: points need one column per key");
  return explore::Machines::points_from(
      keys, std::vector<double>(points.data(), points.data() + points.size()), first);
}

int threads_of(int threads) { return threads > 0 ? threads : explore::all_cores(); }

// Ctrl-C, checked on the calling thread ten times a second: Python's signal handlers run with
// the GIL; a KeyboardInterrupt they raise stays set for the caller to raise.
struct PythonInterrupts {
  bool interrupted = false;
  bool check() {
    if (interrupted) return true;
    py::gil_scoped_acquire gil;
    interrupted = PyErr_CheckSignals() != 0;
    return interrupted;
  }
};

// A sweep's columns (explore::columns_of) as numpy arrays, named as the CSV's columns.
py::dict to_numpy(const std::vector<std::string>& keys, explore::Columns c) {
  const auto& types = explore::event_types();
  py::dict out;
  out["index"] = adopt(std::move(c.index), py::dtype::of<std::int64_t>());
  for (std::size_t k = 0; k < keys.size(); ++k)
    out[py::str(keys[k])] = adopt(std::move(c.values[k]), py::dtype::of<double>());
  out["outcome"] = name_array(c.outcome);
  out["outcome_t"] = adopt(std::move(c.outcome_t), py::dtype::of<double>());
  out["final_r"] = adopt(std::move(c.final_r), py::dtype::of<double>());
  out["final_phi_l_deg"] = adopt(std::move(c.final_phi_l_deg), py::dtype::of<double>());
  for (std::size_t e = 0; e < types.size(); ++e)
    out[py::str(std::string(to_string(types[e])))] = adopt(std::move(c.first[e]), py::dtype::of<double>());
  out["error"] = text_array(c.error);
  return out;
}

// Machines begin..end-1 of `machines` on `threads` threads (explore::run_chunk), the GIL released;
// Ctrl-C stops the workers after the machines they are running and raises KeyboardInterrupt.
py::dict run_machines(const MachineHandle& m, const explore::Machines& machines, std::int64_t begin,
                      std::int64_t end, int threads, double accuracy) {
  explore::RunOptions ro;
  ro.threads = threads_of(threads);
  ro.accuracy = accuracy;
  std::atomic<bool> stop{false};
  ro.stop = &stop;
  PythonInterrupts interrupts;
  ro.progress = [&](std::int64_t, std::int64_t) {
    if (interrupts.check()) stop.store(true);
  };
  std::vector<explore::Outcome> rows;
  {
    py::gil_scoped_release nogil;
    rows = explore::run_chunk(m.config, machines, begin, end, ro);
  }
  if (interrupts.interrupted) throw py::error_already_set();
  return to_numpy(machines.plan().keys(), explore::columns_of(machines, begin, rows));
}

// The full grid over explicit values per key; the last key varies fastest (as the CLI's grid).
// Only machines start..stop-1 of it run (stop < 0: to the end): a chunk of a distributed sweep.
py::dict sweep_grid(const MachineHandle& m, const std::vector<std::string>& keys,
                    const std::vector<Axis>& axes, int threads, std::optional<double> accuracy,
                    std::int64_t start, std::int64_t stop) {
  const explore::Machines machines = grid_machines(keys, axes);
  const double acc = accuracy_of(accuracy);
  const std::int64_t n = machines.size();
  if (stop < 0) stop = n;
  if (start < 0 || start > stop || stop > n) {
    throw std::invalid_argument(
        fmt::format("sweep: machines {}..{} are not within the grid's {}", start, stop, n));
  }
  return run_machines(m, machines, start, stop, threads, acc);
}

// Machines given by their values, a row of `points` each (one column per key), numbered from
// `first`: the Latin hypercube's machines, or a chunk of them.
py::dict sweep_points(const MachineHandle& m, const std::vector<std::string>& keys, const Points& points,
                      std::int64_t first, int threads, std::optional<double> accuracy) {
  const explore::Machines machines = point_machines(keys, points, first);
  const double acc = accuracy_of(accuracy);
  return run_machines(m, machines, first, first + machines.size(), threads, acc);
}

// The machines of a Latin hypercube over [lo, hi] per key (the CLI's --samples N --seed S), as an
// N x keys array: the same doubles as `whatnext sweep` draws.
py::array lhs_points(const std::vector<std::string>& keys, const std::vector<double>& lo,
                     const std::vector<double>& hi, std::int64_t samples, std::uint64_t seed) {
  explore::Plan plan;
  plan.samples = samples;
  plan.seed = seed;
  for (std::size_t k = 0; k < keys.size(); ++k)
    plan.ranges.push_back(explore::Range{keys[k], lo[k], hi[k], 0});
  const explore::Machines machines(plan);
  py::array_t<double> out({static_cast<py::ssize_t>(samples), static_cast<py::ssize_t>(keys.size())});
  double* p = out.mutable_data();
  for (std::int64_t i = 0; i < samples; ++i) machines.point(i, p + static_cast<std::size_t>(i) * keys.size());
  return out;
}

// A sweep's columns as `whatnext sweep --out` writes them: the same header and, through the
// library's csv_row, the same bytes for every row.
py::bytes sweep_csv(const std::vector<std::string>& keys, const py::dict& columns) {
  const auto& types = explore::event_types();
  auto column = [&](const std::string& name) {
    if (!columns.contains(name)) throw std::invalid_argument("to_csv: no column " + name);
    return py::array(columns[py::str(name)]);
  };
  auto numbers = [&](const std::string& name) { return Axis::ensure(column(name)); };
  const auto index =
      py::array_t<std::int64_t, py::array::c_style | py::array::forcecast>::ensure(column("index"));
  const std::int64_t n = index.size();
  std::vector<Axis> values;
  for (const std::string& k : keys) values.push_back(numbers(k));
  const Axis outcome_t = numbers("outcome_t"), final_r = numbers("final_r"),
             final_phi = numbers("final_phi_l_deg");
  std::vector<Axis> first;
  for (EventType t : types) first.push_back(numbers(std::string(to_string(t))));
  const py::list outcome = column("outcome").attr("tolist")();
  const py::list error = column("error").attr("tolist")();
  explore::Plan plan;
  for (const std::string& k : keys) plan.ranges.push_back(explore::Range{k, 0.0, 0.0, 0});
  std::string text = explore::csv_header(plan);
  explore::Outcome o;
  std::vector<double> v(keys.size());
  for (std::int64_t i = 0; i < n; ++i) {
    const auto name = outcome[static_cast<std::size_t>(i)].cast<std::string>();
    o.valid = name != "invalid" && name != "failed";
    o.failed = name == "failed";
    o.error = error[static_cast<std::size_t>(i)].cast<std::string>();
    o.first.assign(types.size(), kNaN);
    if (o.valid) {
      const auto it =
          std::find_if(types.begin(), types.end(), [&](EventType t) { return to_string(t) == name; });
      if (it == types.end()) throw std::invalid_argument("to_csv: unknown outcome " + name);
      o.outcome = *it;
      o.outcome_t = outcome_t.at(i), o.final_r = final_r.at(i), o.final_phi_l_deg = final_phi.at(i);
      for (std::size_t e = 0; e < types.size(); ++e) o.first[e] = first[e].at(i);
    }
    for (std::size_t k = 0; k < keys.size(); ++k) v[k] = values[k].at(i);
    text += explore::csv_row(index.at(i), v, o);
  }
  return py::bytes(text);
}

// A sweep written to the CSV file `path` while it runs: the command's job (explore::SweepJob) in
// Python's words, so the same bytes, synced about once a second to PATH.part and renamed over
// PATH at the end; with resume, what an interrupted sweep left is checked and kept. Ctrl-C stops
// the workers, gives the file its name with the rows done (as the command does) and raises
// KeyboardInterrupt. Returns every machine's columns, the kept ones read back from the file.
// The sweep's identity (explore::sweep_identity, the lines of a CSV's NAME.id): what a Zarr store
// of a study holds to prove it is this study's.
std::string sweep_identity_of(const MachineHandle& m, const std::vector<std::string>& keys,
                              const std::optional<std::vector<Axis>>& axes,
                              const std::optional<Points>& points, std::optional<double> accuracy_given) {
  if (!axes && !points) throw std::invalid_argument("sweep: axes or points");
  const explore::Machines machines = axes ? grid_machines(keys, *axes) : point_machines(keys, *points, 0);
  return explore::sweep_identity(m.config, machines, accuracy_of(accuracy_given));
}

py::dict sweep_to_file(const MachineHandle& m, const std::vector<std::string>& keys,
                       const std::optional<std::vector<Axis>>& axes, const std::optional<Points>& points,
                       int threads, std::optional<double> accuracy_given, const std::string& path,
                       bool resume) {
  if (!axes && !points) throw std::invalid_argument("sweep: axes or points");
  const explore::Machines machines = axes ? grid_machines(keys, *axes) : point_machines(keys, *points, 0);
  explore::SweepJob job(m.config, machines, accuracy_of(accuracy_given));
  const std::string option = "sweep: csv";
  explore::ResumeWords words;
  words.remedy = "give another csv= or resume=False";
  words.plan = "other values, samples or seed";
  words.machine = "another machine or accuracy";
  job.to_file(regular_output_target(path, option), path, option, resume, "sweep: resume", words);
  job.start();
  explore::JobSettings settings;
  settings.threads = threads_of(threads);
  PythonInterrupts interrupts;
  settings.interrupted = [&interrupts] { return interrupts.check(); };
  explore::SweepResult result;
  {
    py::gil_scoped_release nogil;
    result = job.run(settings);  // a failed write is thrown here, before the KeyboardInterrupt
  }
  job.commit();  // after Ctrl-C: the rows done, under the file's name, as the command does
  if (interrupts.interrupted) throw py::error_already_set();
  // The kept rows read back: the Sweep holds every machine, as an uninterrupted sweep's does.
  for (explore::Row& row : job.kept_rows())
    result.rows[static_cast<std::size_t>(row.index)] = std::move(row.outcome);
  return to_numpy(keys, explore::columns_of(machines, 0, result.rows));
}

// The n values of the CLI's --vary KEY=a:b:n grid, computed by the library (the same doubles).
py::array grid_values(double a, double b, int n) {
  if (!(std::isfinite(a) && std::isfinite(b) && a <= b) || n < 1) {
    throw InputError(
        fmt::format("grid: needs finite a <= b and n >= 1 (given a = {}, b = {}, n = {})", a, b, n));
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
      .def("set", &with_set, py::arg("assignments"), py::arg("labels"))
      .def("to_toml", [](const MachineHandle& m) { return to_toml(m.scenario); })
      .def("inputs", &inputs_of)
      .def_readonly("source", &MachineHandle::source)
      .def_property_readonly("seesaw_right_arm",
                             [](const MachineHandle& m) { return m.scenario.machine.seesaw_right_arm; })
      .def(py::pickle(&machine_state, &machine_from_state));

  mod.def(
      "example", [](int n) { return make_machine(example_config(n), fmt::format("example {}", n)); },
      py::arg("n"));
  mod.def(
      "load", [](const std::string& path) { return make_machine(load_config_file(path), path); },
      py::arg("path"));
  mod.def(
      "parse",
      [](const std::string& text, const std::string& source) {
        return make_machine(parse_toml(text, source), source);
      },
      py::arg("text"), py::arg("source"));
  mod.def(
      "defaults", [](const std::string& source) { return make_machine(parse_toml("", source), source); },
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
          py::arg("accuracy"), py::arg("start"), py::arg("stop"));
  mod.def("sweep_points", &sweep_points, py::arg("machine"), py::arg("keys"), py::arg("points"),
          py::arg("first"), py::arg("threads"), py::arg("accuracy"));
  mod.def("lhs_points", &lhs_points, py::arg("keys"), py::arg("lo"), py::arg("hi"), py::arg("samples"),
          py::arg("seed"));
  mod.def("sweep_csv", &sweep_csv, py::arg("keys"), py::arg("columns"));
  mod.def("sweep_to_file", &sweep_to_file, py::arg("machine"), py::arg("keys"), py::arg("axes"),
          py::arg("points"), py::arg("threads"), py::arg("accuracy"), py::arg("path"), py::arg("resume"));
  mod.def("sweep_identity", &sweep_identity_of, py::arg("machine"), py::arg("keys"), py::arg("axes"),
          py::arg("points"), py::arg("accuracy"));
  mod.attr("VERSION") = explore::kProgramVersion;
  mod.attr("DEFAULT_ACCURACY") = explore::kDefaultAccuracy;
  mod.attr("MAX_MACHINES") = explore::kMaxMachines;
  mod.def("grid_values", &grid_values, py::arg("a"), py::arg("b"), py::arg("n"));
  mod.def("csv_columns", [] { return column_names(); });
  mod.def("event_names", [] {
    std::vector<std::string> out;
    for (EventType t : explore::event_types()) out.emplace_back(to_string(t));
    return out;
  });
}
