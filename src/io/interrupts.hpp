// The registry of what an interrupt removes, shared by the interrupt watcher (interrupts.cpp) and
// the files that register their temporaries (atomic_file.cpp).
#pragma once

#include <condition_variable>
#include <cstdint>
#include <functional>
#include <mutex>
#include <set>
#include <string>
#include <utility>
#include <vector>

namespace whatnext::io {

// The signal handler only writes the signal's number into a pipe; a watcher thread does the
// cleaning, where anything may be called. It holds the registry's lock from the first interrupt
// on, so no new temporary can appear behind its back before the process ends.
struct Interrupts {
  std::mutex lock;
  std::vector<std::string> paths;  // removed in reverse order (files before their directory)
  std::vector<int> processes;      // writers of temporaries by name, killed before the removal
  std::function<void(int)> stop;
  bool stopped = false;
  int pipe_write = -1;
  // settle_interrupts(): a zero byte through the pipe, counted when the watcher reads it.
  std::condition_variable settled;
  std::uint64_t zeros_read = 0;
};
Interrupts& interrupts();

}  // namespace whatnext::io
