// Worker threads over the numbers 0..n-1: each number runs once, on whichever thread claims it,
// while the calling thread reports progress, makes what was done durable and hands on the
// numbers done in order. Generic over what a number means (a sweep's machine, an optimiser's
// grid point).
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <vector>

namespace whatnext::explore {

// What one worker does with number i: its own function (made on its thread by the pool's
// make_worker), so that it may keep scratch state without locks.
using PointFn = std::function<void(std::int64_t)>;

struct PoolHooks {
  const std::atomic<bool>* stop = nullptr;  // set (by an interrupt, a failed write) to stop early
  // On the calling thread about ten times a second, and once at the end, with (done, n).
  std::function<void(std::int64_t, std::int64_t)> progress;
  // On the calling thread about once a second (a sweep syncs its file here).
  std::function<void()> checkpoint;
  // On the calling thread: numbers from..to-1 are done, and every number before them was handed
  // on before (in order, from in_order_from on). What a worker did for a number is visible here.
  std::function<void(std::int64_t, std::int64_t)> in_order;
  std::int64_t in_order_from = 0;
};

// Runs make_worker()(i), on `threads` threads, for every i with !done[i] (done.size() numbers;
// those already done are skipped), marking done[i] as they end. Returns the numbers done (with
// those done before). An exception on a worker (out of memory) stops the others and is thrown
// here after they ended; a hook's exception is thrown the same way.
std::int64_t run_pool(std::vector<char>& done, int threads, const std::function<PointFn()>& make_worker,
                      const PoolHooks& hooks);

// The threads a sweep uses when told 0: every core.
int all_cores();

}  // namespace whatnext::explore
