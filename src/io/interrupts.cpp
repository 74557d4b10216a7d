// Interrupts (SIGINT, SIGTERM, SIGHUP) of a command that writes files: its temporaries are removed
// before the process ends by the signal.
#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <filesystem>
#include <iterator>
#include <thread>

#include "interrupts.hpp"
#include "whatnext/interrupts.hpp"

namespace whatnext {

namespace fs = std::filesystem;

namespace io {
Interrupts& interrupts() {
  static Interrupts* it = new Interrupts;  // never destroyed: the watcher may use it until the end
  return *it;
}
}  // namespace io

using namespace io;

namespace {

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(sig);
  [[maybe_unused]] const ssize_t n = ::write(interrupts().pipe_write, &byte, 1);
  errno = saved;
}

void watch(int pipe_read) {
  for (;;) {
    unsigned char sig = 0;
    const ssize_t n = ::read(pipe_read, &sig, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    Interrupts& in = interrupts();
    std::unique_lock<std::mutex> hold(in.lock);
    if (sig == 0) {  // settle_interrupts(): every signal before it has been handled
      ++in.zeros_read;
      in.settled.notify_all();
      continue;
    }
    if (in.stop) {
      if (!in.stopped) in.stop(sig);
      in.stopped = true;
      continue;  // the owner stops and cleans up; a second interrupt changes nothing
    }
    for (const int pid : in.processes) {  // first, or a child could make its temporary again
      ::kill(pid, SIGKILL);
      while (::waitpid(pid, nullptr, 0) < 0 && errno == EINTR) {
      }
    }
    for (auto it = in.paths.rbegin(); it != in.paths.rend(); ++it) {
      if (::unlink(it->c_str()) != 0 && (errno == EISDIR || errno == EPERM)) ::rmdir(it->c_str());
    }
    std::signal(sig, SIG_DFL);
    ::kill(::getpid(), sig);
    for (;;) ::pause();  // keeps the lock until the signal ends the process
  }
}

void add_path(const std::string& path) {
  std::lock_guard<std::mutex> hold(interrupts().lock);
  interrupts().paths.push_back(path);
}
void drop_path(const std::string& path) {
  Interrupts& in = interrupts();
  std::lock_guard<std::mutex> hold(in.lock);
  const auto it = std::find(in.paths.rbegin(), in.paths.rend(), path);
  if (it != in.paths.rend()) in.paths.erase(std::next(it).base());
}

}  // namespace

void install_interrupt_cleanup() {
  static std::once_flag once;
  std::call_once(once, [] {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) return;  // without it, interrupts behave as by default
    interrupts().pipe_write = fds[1];
    std::thread(watch, fds[0]).detach();
    struct sigaction sa {};
    sa.sa_handler = on_interrupt;
    sigemptyset(&sa.sa_mask);
    sa.sa_flags = SA_RESTART;
    for (int sig : {SIGINT, SIGTERM, SIGHUP}) ::sigaction(sig, &sa, nullptr);
    // Beyond the file-size limit (ulimit -f) a write then fails with EFBIG, like a full disk,
    // instead of SIGXFSZ killing whatnext with a .part file left behind.
    ::signal(SIGXFSZ, SIG_IGN);
  });
}

void opening_by_name(const std::function<void()>& open) {
  // The watcher holds this lock from its first removal until the signal ends the process.
  std::lock_guard<std::mutex> hold(interrupts().lock);
  open();
}

static_assert(sizeof(pid_t) == sizeof(int), "process ids pass as int");

int start_writing_process(const std::function<int()>& start) {
  std::lock_guard<std::mutex> hold(interrupts().lock);
  const int pid = start();
  if (pid > 0) interrupts().processes.push_back(pid);
  return pid;
}

void forget_writing_process(int pid) {
  Interrupts& in = interrupts();
  std::lock_guard<std::mutex> hold(in.lock);
  in.processes.erase(std::remove(in.processes.begin(), in.processes.end(), pid), in.processes.end());
}

void remove_on_interrupt(const std::string& path) { add_path(path); }
void forget_on_interrupt(const std::string& path) { drop_path(path); }

void settle_interrupts() {
  Interrupts& in = interrupts();
  if (in.pipe_write < 0) return;
  std::unique_lock<std::mutex> hold(in.lock);
  const std::uint64_t want = in.zeros_read + 1;
  hold.unlock();
  const unsigned char zero = 0;
  while (::write(in.pipe_write, &zero, 1) < 0 && errno == EINTR) {
  }
  hold.lock();
  in.settled.wait(hold, [&in, want] { return in.zeros_read >= want; });
}

void set_interrupt_handler(std::function<void(int)> stop) {
  std::lock_guard<std::mutex> hold(interrupts().lock);
  interrupts().stop = std::move(stop);
  interrupts().stopped = false;
}

}  // namespace whatnext
