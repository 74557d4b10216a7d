#include "whatnext/explore/pool.hpp"

#include <algorithm>
#include <chrono>
#include <condition_variable>
#include <exception>
#include <mutex>
#include <thread>

namespace whatnext::explore {

int all_cores() { return static_cast<int>(std::max(1u, std::thread::hardware_concurrency())); }

namespace {

// One pool as it runs: what its workers and the calling thread share. Workers claim small
// blocks of numbers; a finished block is marked done under the lock, which also hands it to the
// calling thread.
class Pool {
 public:
  Pool(std::vector<char>& done, const std::function<PointFn()>& make_worker, const PoolHooks& hooks)
      : done_(done),
        make_worker_(make_worker),
        hooks_(hooks),
        total_(static_cast<std::int64_t>(done.size())) {
    std::int64_t first = 0, already = 0;
    while (first < total_ && done_[static_cast<std::size_t>(first)]) ++first;
    for (char d : done_) already += d != 0;
    next_ = first, completed_ = already;
    ordered_ = std::clamp<std::int64_t>(hooks_.in_order_from, 0, total_);
  }

  std::int64_t run(int threads) {
    std::vector<std::thread> pool = start_workers(threads);
    try {
      watch();
    } catch (...) {  // a hook failed: the workers stop, then it is thrown
      failed_ = true;
      for (std::thread& t : pool) t.join();
      throw;
    }
    for (std::thread& t : pool) t.join();
    if (failure_) std::rethrow_exception(failure_);
    if (hooks_.progress) hooks_.progress(completed_.load(), total_);
    return completed_.load();
  }

 private:
  static constexpr std::int64_t kBlock = 8, kWake = 256;

  bool stopped() const {
    return failed_.load(std::memory_order_relaxed) ||
           (hooks_.stop && hooks_.stop->load(std::memory_order_relaxed));
  }

  // A worker's life. An exception in it (out of memory) stops the others and is thrown again by
  // the calling thread; escaping a worker it would end the process through std::terminate.
  void work() {
    try {
      const PointFn point = make_worker_();
      for (;;) {
        const std::int64_t start = next_.fetch_add(kBlock);
        if (start >= total_) break;
        const std::int64_t end = std::min(total_, start + kBlock);
        std::int64_t i = start;
        for (; i < end && !stopped(); ++i) {
          if (done_[static_cast<std::size_t>(i)]) continue;  // done before the pool started
          point(i);
          completed_.fetch_add(1, std::memory_order_relaxed);
        }
        {
          std::lock_guard<std::mutex> lock(m_);
          for (std::int64_t j = start; j < i; ++j) done_[static_cast<std::size_t>(j)] = 1;
        }
        // A few hundred numbers waiting: time for the calling thread (cheap when it is awake).
        if (hooks_.in_order &&
            completed_.load(std::memory_order_relaxed) - ordered_.load(std::memory_order_relaxed) >= kWake) {
          cv_.notify_one();
        }
        if (stopped()) break;
      }
    } catch (...) {
      std::lock_guard<std::mutex> lock(m_);
      if (!failure_) failure_ = std::current_exception();
      failed_ = true;
    }
    std::lock_guard<std::mutex> lock(m_);
    --running_;
    cv_.notify_all();
  }

  // As many workers as asked and there are numbers.
  std::vector<std::thread> start_workers(int threads) {
    threads = static_cast<int>(std::max<std::int64_t>(1, std::min<std::int64_t>(threads, total_)));
    running_ = threads;
    std::vector<std::thread> pool;
    pool.reserve(static_cast<std::size_t>(threads));
    try {
      for (int i = 0; i < threads; ++i) pool.emplace_back([this] { work(); });
    } catch (...) {  // no thread to be had (out of memory): stop those started, then say so
      failed_ = true;
      running_ -= threads - static_cast<int>(pool.size());
      for (std::thread& t : pool) t.join();
      throw;
    }
    return pool;
  }

  // Meanwhile the calling thread hands on the numbers done in order every kWake of them (waking
  // it for every block cost more than it saved), checkpoints about once a second and reports
  // progress about ten times a second, until the workers end.
  void watch() {
    std::unique_lock<std::mutex> lock(m_);
    auto last_progress = std::chrono::steady_clock::now();
    auto last_checkpoint = last_progress;
    for (;;) {
      const std::int64_t from = ordered_.load(std::memory_order_relaxed);
      std::int64_t to = from;
      if (hooks_.in_order) {
        while (to < total_ && done_[static_cast<std::size_t>(to)]) ++to;
        ordered_.store(to, std::memory_order_relaxed);
      }
      const bool finished = running_ == 0;
      if (to > from) {
        lock.unlock();
        hooks_.in_order(from, to);
        lock.lock();
      }
      if (finished) break;
      const auto now = std::chrono::steady_clock::now();
      if (hooks_.checkpoint && now - last_checkpoint >= std::chrono::seconds(1)) {
        last_checkpoint = now;
        lock.unlock();
        hooks_.checkpoint();
        lock.lock();
      }
      if (hooks_.progress && now - last_progress >= std::chrono::milliseconds(100)) {
        last_progress = now;
        lock.unlock();
        hooks_.progress(completed_.load(), total_);
        lock.lock();
      }
      // The last worker may have ended while the hooks above ran without the lock: its
      // notification is gone, and waiting for one would wait the whole 100 ms. Under the lock
      // from here to the wait, none is lost.
      if (running_ == 0) continue;
      if (hooks_.progress || hooks_.in_order || hooks_.checkpoint || hooks_.stop) {
        cv_.wait_for(lock, std::chrono::milliseconds(100));
      } else {
        cv_.wait(lock);  // until a worker ends
      }
    }
  }

  std::vector<char>& done_;  // written under m_ once the pool runs
  const std::function<PointFn()>& make_worker_;
  const PoolHooks& hooks_;
  const std::int64_t total_;
  std::atomic<std::int64_t> next_{0}, completed_{0}, ordered_{0};
  int running_ = 0;  // workers not yet ended (under m_)
  std::mutex m_;
  std::condition_variable cv_;
  std::exception_ptr failure_;
  std::atomic<bool> failed_{false};
};

}  // namespace

std::int64_t run_pool(std::vector<char>& done, int threads, const std::function<PointFn()>& make_worker,
                      const PoolHooks& hooks) {
  if (done.empty()) return 0;
  return Pool(done, make_worker, hooks).run(threads);
}

}  // namespace whatnext::explore
