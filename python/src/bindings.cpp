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

#include "whatnext/units.hpp"
#include "whatnext/columns.hpp"
#include "whatnext/config.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/explore/sweep_file.hpp"
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
  void on_event(const Event& e) override { row(e.after, to_string(e.type), e.impact ? e.impulse.data() : nullptr); }

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

// The values of machine i, one per key, written to out.
using PointFn = std::function<void(std::int64_t, double*)>;

// Every key must be one the inputs hold as a single number (set_number's rule, as the CLI's
// --vary): one line naming the key otherwise.
void check_sweep_keys(const std::vector<std::string>& keys) {
  if (keys.empty()) throw InputError("sweep: give at least one key to vary");
  for (const std::string& k : keys) {
    if (!find_key(k)) {
      const std::string near = nearest_key(k);
      throw InputError(near.empty()
                           ? fmt::format("sweep: unknown key '{}'", printable(k))
                           : fmt::format("sweep: unknown key '{}' (did you mean '{}'?)", printable(k), near));
    }
    try {
      Config probe;
      set_number(probe, k, 0.0);
    } catch (const InputError&) {
      throw InputError(fmt::format("sweep: {} is not a single number and cannot be varied", k));
    }
  }
}

// Runs machines first..first+n-1 on `threads` threads with explore::evaluate, the GIL released;
// Ctrl-C (checked twenty times a second on the calling thread) stops the workers after the
// machines they are running and raises KeyboardInterrupt. Rows land in their own slots, so they do
// not depend on the thread count. Each machine runs to the event-time accuracy given
// (explore::apply_accuracy; none: the machine's own run settings).
std::vector<explore::Outcome> run_points(const MachineHandle& m, const std::vector<std::string>& keys,
                                         std::int64_t first, std::int64_t n, const PointFn& point,
                                         int threads, std::optional<double> accuracy_given) {
  if (accuracy_given) explore::check_accuracy(*accuracy_given, "sweep: accuracy");
  const double accuracy = accuracy_given.value_or(0.0);
  std::vector<explore::Outcome> rows(static_cast<std::size_t>(n));
  if (n == 0) return rows;
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
        point(first + i, values.data());
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
      if (cv.wait_for(lock, std::chrono::milliseconds(50), [&] { return running == 0; })) break;
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
// and error. An invalid machine has outcome "invalid", a run that failed "failed" (as in the CSV),
// NaN times and its one-line reason.
py::dict sweep_columns(const std::vector<std::string>& keys, std::int64_t first, std::int64_t n,
                       const PointFn& point, const std::vector<explore::Outcome>& rows) {
  const auto& types = explore::event_types();
  const auto un = static_cast<std::size_t>(n);
  std::vector<std::int64_t> index(un);
  std::vector<std::vector<double>> values(keys.size(), std::vector<double>(un));
  std::vector<std::string_view> outcome(un);
  std::vector<double> outcome_t(un), final_r(un), final_phi(un);
  std::vector<std::vector<double>> first_t(types.size(), std::vector<double>(un));
  std::vector<std::string> error(un);
  std::vector<double> v(keys.size());
  for (std::size_t i = 0; i < un; ++i) {
    const explore::Outcome& o = rows[i];
    index[i] = first + static_cast<std::int64_t>(i);
    point(index[i], v.data());
    for (std::size_t k = 0; k < keys.size(); ++k) values[k][i] = v[k];
    outcome[i] = o.valid ? to_string(o.outcome) : std::string_view(o.failed ? "failed" : "invalid");
    outcome_t[i] = o.valid ? o.outcome_t : kNaN;
    final_r[i] = o.valid ? o.final_r : kNaN;
    final_phi[i] = o.valid ? o.final_phi_l_deg : kNaN;
    for (std::size_t e = 0; e < types.size(); ++e) first_t[e][i] = o.valid ? o.first[e] : kNaN;
    error[i] = o.error;
  }
  py::dict out;
  out["index"] = adopt(std::move(index), py::dtype::of<std::int64_t>());
  for (std::size_t k = 0; k < keys.size(); ++k)
    out[py::str(keys[k])] = adopt(std::move(values[k]), py::dtype::of<double>());
  out["outcome"] = name_array(outcome);
  out["outcome_t"] = adopt(std::move(outcome_t), py::dtype::of<double>());
  out["final_r"] = adopt(std::move(final_r), py::dtype::of<double>());
  out["final_phi_l_deg"] = adopt(std::move(final_phi), py::dtype::of<double>());
  for (std::size_t e = 0; e < types.size(); ++e) {
    out[py::str(std::string(to_string(types[e])))] = adopt(std::move(first_t[e]), py::dtype::of<double>());
  }
  out["error"] = text_array(error);
  return out;
}

using Axis = py::array_t<double, py::array::c_style | py::array::forcecast>;

// The full grid over explicit values per key; the last key varies fastest (as the CLI's grid).
// Only machines start..stop-1 of it run (stop < 0: to the end): a chunk of a distributed sweep.
py::dict sweep_grid(const MachineHandle& m, const std::vector<std::string>& keys,
                    const std::vector<Axis>& axes, int threads, std::optional<double> accuracy,
                    std::int64_t start, std::int64_t stop) {
  check_sweep_keys(keys);
  if (axes.size() != keys.size()) throw std::invalid_argument("sweep: one array of values per key");
  std::vector<std::vector<double>> grid(keys.size());
  std::int64_t n = 1;
  for (std::size_t k = 0; k < keys.size(); ++k) {
    if (axes[k].ndim() != 1 || axes[k].size() == 0) {
      throw InputError(
          fmt::format("sweep: {} needs a one-dimensional sequence of at least one value", keys[k]));
    }
    grid[k].assign(axes[k].data(), axes[k].data() + axes[k].size());
    const auto size = static_cast<std::int64_t>(grid[k].size());
    if (n > explore::kMaxMachines / size) {
      throw InputError(
          fmt::format("sweep: the grid has more than {} machines; use fewer values", explore::kMaxMachines));
    }
    n *= size;
  }
  if (stop < 0) stop = n;
  if (start < 0 || start > stop || stop > n) {
    throw std::invalid_argument(
        fmt::format("sweep: machines {}..{} are not within the grid's {}", start, stop, n));
  }
  const PointFn point = [&grid](std::int64_t i, double* out) {
    for (std::size_t d = grid.size(); d-- > 0;) {
      const auto size = static_cast<std::int64_t>(grid[d].size());
      out[d] = grid[d][static_cast<std::size_t>(i % size)];
      i /= size;
    }
  };
  const auto rows = run_points(m, keys, start, stop - start, point, threads, accuracy);
  return sweep_columns(keys, start, stop - start, point, rows);
}

using Points = py::array_t<double, py::array::c_style | py::array::forcecast>;

// Machines given by their values, a row of `points` each (one column per key), numbered from
// `first`: the Latin hypercube's machines, or a chunk of them.
py::dict sweep_points(const MachineHandle& m, const std::vector<std::string>& keys, const Points& points,
                      std::int64_t first, int threads, std::optional<double> accuracy) {
  check_sweep_keys(keys);
  if (points.ndim() != 2 || points.shape(1) != static_cast<py::ssize_t>(keys.size())) {
    throw std::invalid_argument("sweep: points need one column per key");
  }
  const std::int64_t n = points.shape(0);
  const double* data = points.data();
  const std::size_t k = keys.size();
  const PointFn point = [data, first, k](std::int64_t i, double* out) {
    std::copy_n(data + static_cast<std::size_t>(i - first) * k, k, out);
  };
  const auto rows = run_points(m, keys, first, n, point, threads, accuracy);
  return sweep_columns(keys, first, n, point, rows);
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
  std::string text = "index";
  for (const std::string& k : keys) text += "," + k;
  text += ",outcome,outcome_t,final_r,final_phi_l_deg";
  for (EventType t : types) text += "," + std::string(to_string(t));
  text += ",error\n";
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

// --- sweeps written to a file, resumably ---------------------------------------------------------

// One row of a sweep's CSV (explore::csv_row's layout, with its newline) read back; false when the
// line is not one. Numbers are written in the shortest form that reads back as the same double,
// so strtod gives the outcome's own numbers; the caller checks that csv_row gives the line again.
bool parse_row(std::string_view line, std::size_t n_keys, explore::Outcome& o) {
  const auto& types = explore::event_types();
  if (line.empty() || line.back() != '\n') return false;
  line.remove_suffix(1);
  const std::size_t fields = 1 + n_keys + 4 + types.size();  // before the error
  std::vector<std::string_view> cell;
  std::size_t pos = 0;
  for (std::size_t k = 0; k < fields; ++k) {
    const auto comma = line.find(',', pos);
    if (comma == std::string_view::npos) return false;
    cell.push_back(line.substr(pos, comma - pos));
    pos = comma + 1;
  }
  std::string_view error = line.substr(pos);
  const auto number = [](std::string_view text) {
    if (text.empty()) return kNaN;
    const std::string t(text);
    char* end = nullptr;
    const double v = std::strtod(t.c_str(), &end);
    return end == t.c_str() + t.size() ? v : kNaN;
  };
  o = explore::Outcome{};
  o.first.assign(types.size(), kNaN);
  const std::string_view name = cell[1 + n_keys];
  o.failed = name == "failed";
  o.valid = !o.failed && name != "invalid";
  if (o.valid) {
    const auto it = std::find_if(types.begin(), types.end(), [&](EventType t) { return to_string(t) == name; });
    if (it == types.end()) return false;
    o.outcome = *it;
    o.outcome_t = number(cell[2 + n_keys]);
    o.final_r = number(cell[3 + n_keys]);
    o.final_phi_l_deg = number(cell[4 + n_keys]);
    for (std::size_t e = 0; e < types.size(); ++e) o.first[e] = number(cell[5 + n_keys + e]);
  } else {
    std::string text;
    if (error.size() >= 2 && error.front() == '"' && error.back() == '"') {
      error = error.substr(1, error.size() - 2);
      for (std::size_t i = 0; i < error.size(); ++i) {
        text += error[i];
        if (error[i] == '"' && i + 1 < error.size() && error[i + 1] == '"') ++i;
      }
    } else {
      text = std::string(error);
    }
    o.error = std::move(text);
  }
  return true;
}

// A sweep written to the CSV file `path` while it runs, as `whatnext sweep --out` writes it and
// through the same code (explore::run, explore::SweepFile): the same bytes, rows synced about once
// a second to PATH.part, renamed over PATH at the end. With resume, what an interrupted sweep left
// (PATH.part, else PATH) is checked to be this sweep's and kept; only the other machines run.
// Ctrl-C stops the workers, gives the file its name with the rows done (as the command does) and
// raises KeyboardInterrupt. Returns every machine's columns, the kept ones read back from the file.
py::dict sweep_to_file(const MachineHandle& m, const std::vector<std::string>& keys,
                       const std::optional<std::vector<Axis>>& axes, const std::optional<Points>& points,
                       int threads, std::optional<double> accuracy_given, const std::string& path, bool resume) {
  check_sweep_keys(keys);
  if (accuracy_given) explore::check_accuracy(*accuracy_given, "sweep: accuracy");
  const double accuracy = accuracy_given.value_or(0.0);
  std::optional<explore::Machines> made;
  if (axes) {
    std::vector<std::vector<double>> values;
    for (const Axis& a : *axes) {
      if (a.ndim() != 1) throw std::invalid_argument("sweep: one-dimensional values per key");
      values.emplace_back(a.data(), a.data() + a.size());
    }
    made = explore::Machines::grid_of(keys, std::move(values));
  } else if (points) {
    if (points->ndim() != 2 || points->shape(1) != static_cast<py::ssize_t>(keys.size()))
      throw std::invalid_argument("sweep: points need one column per key");
    made = explore::Machines::points_of(keys, std::vector<double>(points->data(), points->data() + points->size()));
  } else {
    throw std::invalid_argument("sweep: axes or points");
  }
  const explore::Machines& machines = *made;
  const std::string option = "sweep: csv";
  explore::SweepFile file(regular_output_target(path, option), path, option);
  explore::Resumable kept;
  std::string text;
  if (resume) {
    text = file.previous();
    explore::ResumeWords words;
    words.remedy = "give another csv= or resume=False";
    words.plan = "other values, samples or seed";
    words.machine = "another machine or accuracy";
    kept = explore::read_resumable(text, machines, m.config, accuracy,
                                   fmt::format("sweep: resume {}", printable(file.source(), 96)), words);
  }
  const std::int64_t n = machines.size();
  // The kept rows, read back: the Sweep holds every machine, as an uninterrupted sweep's does.
  std::vector<explore::Outcome> rows(static_cast<std::size_t>(n));
  std::vector<char> from_file(static_cast<std::size_t>(n), 0);
  {
    std::vector<double> values(keys.size());
    const auto read_back = [&](std::int64_t index, std::string_view line) {
      explore::Outcome& o = rows[static_cast<std::size_t>(index)];
      machines.point(index, values.data());
      if (!parse_row(line, keys.size(), o) || explore::csv_row(index, values, o) != line) {
        throw InputError(fmt::format("sweep: resume {}: the row of machine {} cannot be read back; {}",
                                     printable(file.source(), 96), index, "give another csv= or resume=False"));
      }
      from_file[static_cast<std::size_t>(index)] = 1;
    };
    std::size_t at = text.find('\n') + 1;
    for (std::int64_t i = 0; i < kept.prefix_rows; ++i) {
      const std::size_t end = text.find('\n', at) + 1;
      read_back(i, std::string_view(text).substr(at, end - at));
      at = end;
    }
    for (const auto& [index, line] : kept.later) read_back(index, line);
  }
  file.start(std::string_view(text).substr(0, kept.prefix_bytes));
  std::string().swap(text);

  explore::RunOptions ro;
  ro.threads = threads > 0 ? threads : static_cast<int>(std::max(1u, std::thread::hardware_concurrency()));
  ro.accuracy = accuracy;
  std::atomic<bool> stop{false};
  ro.stop = &stop;
  ro.csv = &file.stream();
  ro.keep_rows = true;
  ro.header_written = kept.header;
  ro.rows_written = kept.prefix_rows;
  ro.known = std::move(kept.later);
  std::exception_ptr write_failure;
  ro.checkpoint = [&] {
    try {
      file.sync();
    } catch (...) {  // thrown here it would end the sweep's threads: they stop, it is thrown below
      if (!write_failure) write_failure = std::current_exception();
      stop.store(true);
    }
  };
  bool interrupted = false;
  ro.progress = [&](std::int64_t, std::int64_t) {  // on the calling thread, ten times a second
    if (interrupted) return;
    py::gil_scoped_acquire gil;
    interrupted = PyErr_CheckSignals() != 0;  // keeps the exception set for below
    if (interrupted) stop.store(true);
  };
  explore::SweepResult result;
  {
    py::gil_scoped_release nogil;
    result = explore::run(m.config, machines, ro);
  }
  if (interrupted) {
    py::error_already_set pending;  // the KeyboardInterrupt, taken aside: a failed write is raised instead
    if (write_failure) std::rethrow_exception(write_failure);
    file.commit();  // the rows done, under the file's name, as the command does when stopped
    throw pending;
  }
  if (write_failure) std::rethrow_exception(write_failure);
  file.commit();
  for (std::int64_t i = 0; i < n; ++i) {
    const auto slot = static_cast<std::size_t>(i);
    if (!from_file[slot]) rows[slot] = std::move(result.rows[slot]);
  }
  const PointFn point = [&machines](std::int64_t i, double* out) { machines.point(i, out); };
  return sweep_columns(keys, 0, n, point, rows);
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
  mod.def("sweep_to_file", &sweep_to_file, py::arg("machine"), py::arg("keys"), py::arg("axes"), py::arg("points"),
          py::arg("threads"), py::arg("accuracy"), py::arg("path"), py::arg("resume"));
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
