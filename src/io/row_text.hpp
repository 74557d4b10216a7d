// The rows of the CSV and the .dat, made on one or two threads and written in order.
#pragma once

#include <algorithm>
#include <array>
#include <atomic>
#include <chrono>
#include <condition_variable>
#include <cstdint>
#include <exception>
#include <memory>
#include <mutex>
#include <ostream>
#include <system_error>
#include <thread>

#include "whatnext/writers.hpp"

#if defined(__linux__) && !defined(__EMSCRIPTEN__)
#include <sched.h>
#endif

namespace whatnext {

// The CPUs this process may run on: `taskset -c 0` (or a container's cpuset) leaves one, where
// hardware_concurrency() still counts the machine's. A helper thread on the same single CPU only
// takes turns with the run's thread and spins between batches (docs/performance.md).
inline unsigned usable_cpus() {
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
  cpu_set_t set;
  CPU_ZERO(&set);
  if (::sched_getaffinity(0, sizeof set, &set) == 0) return static_cast<unsigned>(CPU_COUNT(&set));
#endif
  return std::thread::hardware_concurrency();
}

// A batch's rows, made in chunks of kChunkRows on the calling thread and, with Writing::parallel,
// on a helper thread too; written in order by the calling thread as their chunks are done.
// Chunks are claimed from one atomic word (round, chunks, next), so a helper that wakes late or
// never only leaves more chunks to the caller: the caller never waits for a chunk nobody took.
class RowText {
 public:
  // Writes the text of rows from..to-1 at out (at most max_chars characters each) and returns its
  // end. Called from two threads at once with Writing::parallel.
  struct Rows {
    const void* context;
    char* (*make)(const void* context, std::size_t from, std::size_t to, char* out);
  };

  RowText(std::ostream& out, Writing writing, std::size_t max_chars)
      : out_(out),
        buf_(out.rdbuf()),
        parallel_(writing == Writing::parallel && usable_cpus() > 1),
        max_chars_(max_chars) {}
  ~RowText() {
    if (!helper_.joinable()) return;
    {
      std::lock_guard<std::mutex> hold(lock_);
      stop_.store(true, std::memory_order_relaxed);
    }
    wake_.notify_one();
    helper_.join();
  }
  RowText(const RowText&) = delete;
  RowText& operator=(const RowText&) = delete;

  // Rows 0 .. n-1, in order. A row that throws (a state that is not finite) ends the batch: the
  // rows before its chunk are written, and the exception is rethrown here.
  template <class F>
  void write(std::size_t n, const F& row) {
    write(n, Rows{&row, [](const void* c, std::size_t from, std::size_t to, char* out) {
                    for (std::size_t i = from; i < to; ++i) out = (*static_cast<const F*>(c))(i, out);
                    return out;
                  }});
  }
  // The same, with rows(from, to, out) making a run of rows at once (and returning its end): a
  // writer may then overlap one row's work with the next's.
  template <class F>
  void write_runs(std::size_t n, const F& rows) {
    write(n, Rows{&rows, [](const void* c, std::size_t from, std::size_t to, char* out) {
                    return (*static_cast<const F*>(c))(from, to, out);
                  }});
  }

 private:
  static constexpr std::size_t kChunkRows = 128;
  static constexpr std::size_t kChunks = 16;  // a round: 2048 rows, one simulate() batch
  enum : int { pending = 0, done = 1, failed = 2 };

  void write(std::size_t n, Rows row) {
    for (std::size_t base = 0; base < n; base += kChunks * kChunkRows) {
      const std::size_t rows = std::min(n - base, kChunks * kChunkRows);
      const std::size_t chunks = (rows + kChunkRows - 1) / kChunkRows;
      row_ = row;
      base_ = base;
      end_row_ = base + rows;
      for (std::size_t k = 0; k < chunks; ++k) state_[k].store(pending, std::memory_order_relaxed);
      std::uint32_t round = 0;
      {
        std::lock_guard<std::mutex> hold(lock_);
        round = ++round_;
        claim_.store(word(round, chunks, 0), std::memory_order_release);
      }
      if (chunks > 1 && parallel_ && start_helper()) wake_.notify_one();
      std::size_t written = 0, k = 0;
      while (claim(round, k)) {
        make(k);
        written = write_done(written, chunks);
      }
      for (std::size_t j = written; j < chunks; ++j) {  // the helper's last chunks
        while (state_[j].load(std::memory_order_acquire) == pending) std::this_thread::yield();
      }
      written = write_done(written, chunks);
      if (written < chunks) std::rethrow_exception(error_[written]);
    }
  }

  static std::uint64_t word(std::uint32_t round, std::size_t chunks, std::size_t next) {
    return (std::uint64_t{round} << 32) | (std::uint64_t{chunks} << 16) | next;
  }
  // The next chunk of this round, if any is left.
  bool claim(std::uint32_t round, std::size_t& k) {
    std::uint64_t c = claim_.load(std::memory_order_acquire);
    for (;;) {
      const std::size_t chunks = (c >> 16) & 0xffff, next = c & 0xffff;
      if ((c >> 32) != round || next >= chunks) return false;
      if (claim_.compare_exchange_weak(c, c + 1, std::memory_order_acq_rel)) {
        k = next;
        return true;
      }
    }
  }

  void make(std::size_t k) {
    if (!slot_[k]) slot_[k].reset(new char[kChunkRows * max_chars_]);  // pages touched as used
    char* p = slot_[k].get();
    try {
      const std::size_t from = base_ + k * kChunkRows, to = std::min(end_row_, from + kChunkRows);
      p = row_.make(row_.context, from, to, p);
      end_[k] = p;
      state_[k].store(done, std::memory_order_release);
    } catch (...) {
      error_[k] = std::current_exception();
      state_[k].store(failed, std::memory_order_release);
    }
  }

  // Writes the done chunks from `from` on, in order; returns the first one not written.
  std::size_t write_done(std::size_t from, std::size_t chunks) {
    for (; from < chunks && state_[from].load(std::memory_order_acquire) == done; ++from) {
      const auto bytes = static_cast<std::streamsize>(end_[from] - slot_[from].get());
      if (!out_.good() || !buf_ || buf_->sputn(slot_[from].get(), bytes) != bytes)
        out_.setstate(std::ios::badbit);
    }
    return from;
  }

  bool start_helper() {
    if (helper_.joinable()) return true;
    for (std::size_t k = 0; k < kChunks; ++k) {  // allocated here: the helper allocates nothing
      if (!slot_[k]) slot_[k].reset(new char[kChunkRows * max_chars_]);
    }
    try {
      helper_ = std::thread([this] { help(); });
    } catch (const std::system_error&) {  // no threads here (WebAssembly): all rows on this one
      parallel_ = false;
    }
    return parallel_;
  }

  void help() {
    std::uint32_t seen = 0;
    for (;;) {
      // The next round comes within tens of microseconds (the run's next samples): look for it a
      // while before sleeping, for waking a sleeping thread (an idle virtual CPU) takes longer.
      std::uint32_t round = seen;
      const auto until = std::chrono::steady_clock::now() + std::chrono::microseconds(500);
      while (!stop_.load(std::memory_order_relaxed) && std::chrono::steady_clock::now() < until) {
        round = static_cast<std::uint32_t>(claim_.load(std::memory_order_acquire) >> 32);
        if (round != seen) break;
        std::this_thread::yield();
      }
      if (round == seen) {
        std::unique_lock<std::mutex> hold(lock_);
        wake_.wait(hold, [&] { return stop_.load(std::memory_order_relaxed) || round_ != seen; });
        if (stop_.load(std::memory_order_relaxed)) return;
        round = round_;
      }
      seen = round;
      std::size_t k = 0;
      while (claim(round, k)) make(k);
    }
  }

  std::ostream& out_;
  std::streambuf* buf_;
  bool parallel_;
  const std::size_t max_chars_;
  // The round's job: set by the caller before claim_ opens the round, read after a claim.
  Rows row_{};
  std::size_t base_ = 0, end_row_ = 0;
  std::atomic<std::uint64_t> claim_{0};
  std::array<std::atomic<int>, kChunks> state_{};
  std::array<char*, kChunks> end_{};
  std::array<std::exception_ptr, kChunks> error_{};
  std::array<std::unique_ptr<char[]>, kChunks> slot_{};
  std::mutex lock_;
  std::condition_variable wake_;
  std::uint32_t round_ = 0;        // under lock_
  std::atomic<bool> stop_{false};  // set under lock_
  std::thread helper_;
};

}  // namespace whatnext
