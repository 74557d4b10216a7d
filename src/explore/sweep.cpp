#include "whatnext/explore/sweep.hpp"

#include <algorithm>
#include <memory>
#include <ostream>

#include "whatnext/explore/pool.hpp"

namespace whatnext::explore {

namespace {

// A worker's point function: machine i evaluated in the worker's own scratch machine.
template <class Keep>
std::function<PointFn()> workers(const Config& base, const Machines& machines, double accuracy, Keep keep) {
  return [&base, &machines, accuracy, keep] {
    const auto evaluator = std::make_shared<Evaluator>(base, machines.plan().keys(), accuracy);
    auto values = std::make_shared<std::vector<double>>(machines.plan().ranges.size());
    return PointFn([&machines, evaluator, values, keep](std::int64_t i) {
      machines.point(i, values->data());
      keep(i, *values, (*evaluator)(values->data()));
    });
  };
}

}  // namespace

SweepResult run(const Config& base, const Machines& machines, const RunOptions& options) {
  const std::int64_t total = machines.size();
  SweepResult res;
  if (options.keep_rows) res.rows.resize(static_cast<std::size_t>(total));
  res.done.assign(static_cast<std::size_t>(total), 0);
  res.lines.resize(static_cast<std::size_t>(total));
  // A resumed sweep's rows: those already in the file and the known ones are done before any
  // worker starts (workers skip them; nothing else writes their slots).
  const std::int64_t already = std::clamp<std::int64_t>(options.rows_written, 0, total);
  std::fill(res.done.begin(), res.done.begin() + already, 1);
  for (const auto& [index, line] : options.known) {
    if (index < already || index >= total || res.done[static_cast<std::size_t>(index)]) continue;
    res.done[static_cast<std::size_t>(index)] = 1;
    res.lines[static_cast<std::size_t>(index)] = line;
  }
  std::ostream* csv = options.csv;
  if (csv && !options.header_written) {
    const std::string header = csv_header(machines.plan());
    csv->write(header.data(), static_cast<std::streamsize>(header.size()));
  }
  std::atomic<std::int64_t> invalid{0}, failed{0};
  const auto keep = [&res, &invalid, &failed, keep_rows = options.keep_rows](
                        std::int64_t i, const std::vector<double>& values, Outcome&& o) {
    const auto slot = static_cast<std::size_t>(i);
    if (!o.valid) (o.failed ? failed : invalid).fetch_add(1, std::memory_order_relaxed);
    res.lines[slot] = csv_row(i, values, o);  // formatted here, on all cores
    if (keep_rows) res.rows[slot] = std::move(o);
  };
  // The calling thread writes the rows done, in index order, and lets their lines go (their
  // memory is used again: every page a sweep touches costs).
  const auto write = [&res, csv](std::int64_t from, std::int64_t to) {
    for (std::int64_t i = from; i < to; ++i) {
      std::string& line = res.lines[static_cast<std::size_t>(i)];
      csv->write(line.data(), static_cast<std::streamsize>(line.size()));
      std::string().swap(line);
    }
  };
  std::int64_t written = already;
  PoolHooks hooks;
  hooks.stop = options.stop;
  hooks.progress = options.progress;
  hooks.checkpoint = options.checkpoint;
  hooks.in_order_from = already;
  if (csv) {
    hooks.in_order = [&write, &written](std::int64_t from, std::int64_t to) {
      write(from, to);
      written = to;
    };
  }
  res.completed = run_pool(res.done, options.threads, workers(base, machines, options.accuracy, keep), hooks);
  if (csv) {  // after a stop: the rows done beyond the first one that is not
    for (std::int64_t i = written; i < total; ++i) {
      if (res.done[static_cast<std::size_t>(i)]) write(i, i + 1);
    }
    res.lines.clear();
  }
  res.invalid = invalid.load();
  res.failed = failed.load();
  res.interrupted = res.completed < total;
  return res;
}

std::vector<Outcome> run_chunk(const Config& base, const Machines& machines, std::int64_t begin,
                               std::int64_t end, const RunOptions& options, std::vector<char>* done) {
  std::vector<Outcome> rows(static_cast<std::size_t>(std::max<std::int64_t>(0, end - begin)));
  std::vector<char> own(rows.size(), 0);
  std::vector<char>& ran = done ? *done : own;
  ran.assign(rows.size(), 0);
  const auto keep = [&rows, begin](std::int64_t i, const std::vector<double>&, Outcome&& o) {
    rows[static_cast<std::size_t>(i - begin)] = std::move(o);
  };
  // The pool numbers the chunk's machines from 0.
  const std::function<PointFn()> machine_workers = workers(base, machines, options.accuracy, keep);
  const std::function<PointFn()> shifted = [&machine_workers, begin] {
    return PointFn([point = machine_workers(), begin](std::int64_t i) { point(begin + i); });
  };
  PoolHooks hooks;
  hooks.stop = options.stop;
  hooks.progress = options.progress;
  run_pool(ran, options.threads, shifted, hooks);
  return rows;
}

}  // namespace whatnext::explore
