#include "whatnext/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iterator>
#include <mutex>
#include <set>
#include <stdexcept>
#include <system_error>
#include <thread>

#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "number_text.hpp"
#include "whatnext/config.hpp"

namespace whatnext {

namespace fs = std::filesystem;

namespace {
constexpr double kRadToDeg = 180.0 / 3.14159265358979323846;

// Never let -0.000 reach a file.
double clean(double v) { return (std::isfinite(v) && v != 0.0) ? v : 0.0; }

// Nor a NaN or an infinity: a state that is not finite ends the run as failed (the writers are
// called from inside simulate(), so the run stops there and no file is committed).
[[noreturn]] void not_finite(const Snapshot& s) {
  throw SimulationError(fmt::format("the state is not finite at t = {} s in mode {}", s.t, to_string(s.mode)));
}

void require_finite(const Snapshot& s) {
  const double values[] = {s.t,         s.x,         s.h,       s.r,        s.dr,
                           s.phi_s,     s.dphi_s,    s.phi_l,   s.dphi_l,   s.balloon_h,
                           s.balloon_v, s.tension,   s.energy(), s.total_energy(), s.ledger_residual()};
  for (const double v : values) {
    if (!std::isfinite(v)) not_finite(s);
  }
}

}  // namespace

void require_finite(const Result& result) {
  for (const Event& e : result.events) require_finite(e.after);
}

// --- interrupts ------------------------------------------------------------------------------

namespace {

// The signal handler only writes the signal's number into a pipe; a watcher thread does the
// cleaning, where anything may be called. It holds the registry's lock from the first interrupt
// on, so no new temporary can appear behind its back before the process ends.
struct Interrupts {
  std::mutex lock;
  std::vector<std::string> paths;  // removed in reverse order (files before their directory)
  std::vector<std::pair<std::string, std::set<std::string>>> dirs;  // dir, .part files already there
  std::function<void(int)> stop;
  bool stopped = false;
  int pipe_write = -1;
};
Interrupts& interrupts() {
  static Interrupts* it = new Interrupts;  // never destroyed: the watcher may use it until the end
  return *it;
}

extern "C" void on_interrupt(int sig) {
  const int saved = errno;
  const unsigned char byte = static_cast<unsigned char>(sig);
  [[maybe_unused]] const ssize_t n = ::write(interrupts().pipe_write, &byte, 1);
  errno = saved;
}

std::set<std::string> part_files(const std::string& dir) {
  std::set<std::string> out;
  std::error_code ec;
  for (fs::directory_iterator it(dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() > 5 && name.compare(name.size() - 5, 5, ".part") == 0) out.insert(it->path().string());
  }
  return out;
}

void watch(int pipe_read) {
  for (;;) {
    unsigned char sig = 0;
    const ssize_t n = ::read(pipe_read, &sig, 1);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) return;
    Interrupts& in = interrupts();
    std::unique_lock<std::mutex> hold(in.lock);
    if (in.stop) {
      if (!in.stopped) in.stop(sig);
      in.stopped = true;
      continue;  // the owner stops and cleans up; a second interrupt changes nothing
    }
    for (const auto& [dir, before] : in.dirs) {
      for (const std::string& f : part_files(dir)) {
        if (!before.count(f)) ::unlink(f.c_str());
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

void remove_on_interrupt(const std::string& path) { add_path(path); }
void forget_on_interrupt(const std::string& path) { drop_path(path); }

void remove_new_parts_on_interrupt(const std::string& dir) {
  std::set<std::string> before = part_files(dir);
  std::lock_guard<std::mutex> hold(interrupts().lock);
  interrupts().dirs.emplace_back(dir, std::move(before));
}

void set_interrupt_handler(std::function<void(int)> stop) {
  std::lock_guard<std::mutex> hold(interrupts().lock);
  interrupts().stop = std::move(stop);
  interrupts().stopped = false;
}

// --- AtomicFile --------------------------------------------------------------------------------

AtomicFile::FdBuf::FdBuf() { setp(buffer_, buffer_ + sizeof buffer_); }

bool AtomicFile::FdBuf::drain() {
  const char* p = pbase();
  std::size_t left = static_cast<std::size_t>(pptr() - pbase());
  while (left > 0 && error == 0) {
    const ssize_t n = ::write(fd, p, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      error = n < 0 ? errno : EIO;
      break;
    }
    p += n;
    left -= static_cast<std::size_t>(n);
  }
  setp(buffer_, buffer_ + sizeof buffer_);
  return error == 0;
}

AtomicFile::FdBuf::int_type AtomicFile::FdBuf::overflow(int_type ch) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(ch, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(ch);
    pbump(1);
  }
  return traits_type::not_eof(ch);
}

int AtomicFile::FdBuf::sync() { return drain() ? 0 : -1; }

std::streamsize AtomicFile::FdBuf::xsputn(const char* s, std::streamsize n) {
  std::streamsize done = 0;
  while (done < n) {
    if (pptr() == epptr() && !drain()) return done;
    const std::streamsize room = std::min<std::streamsize>(epptr() - pptr(), n - done);
    std::memcpy(pptr(), s + done, static_cast<std::size_t>(room));
    pbump(static_cast<int>(room));
    done += room;
  }
  return done;
}

namespace {

// "/dev/stdout", "/dev/fd/3", "/proc/self/fd/3": an open descriptor of this process, or -1.
int descriptor_path(const std::string& p) {
  if (p == "/dev/stdout") return 1;
  if (p == "/dev/stderr") return 2;
  for (const std::string& prefix : {std::string("/dev/fd/"), std::string("/proc/self/fd/"),
                                   fmt::format("/proc/{}/fd/", ::getpid())}) {
    if (p.size() > prefix.size() && p.compare(0, prefix.size(), prefix) == 0) {
      const std::string num = p.substr(prefix.size());
      if (num.size() < 6 && std::all_of(num.begin(), num.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return std::stoi(num);
      }
    }
  }
  return -1;
}

struct stat null_device_stat() {
  struct stat st {};
  if (::stat("/dev/null", &st) != 0) st.st_rdev = static_cast<dev_t>(-1);
  return st;
}

// What an output path names, symlinks followed.
struct Target {
  std::string path;     // the last name reached (the file to replace, or the device)
  int fd = -1;          // an open descriptor of this process (/dev/stdout, /dev/fd/N, "-")
  bool exists = false;  // path exists (st is valid)
  struct stat st {};
};

Target resolve(const std::string& given, const std::function<void(const std::string&)>& fail) {
  if (given.empty()) fail("give a file name");
  Target t;
  t.path = given == "-" ? "/dev/stdout" : given;
  for (int hops = 0;; ++hops) {
    if (hops > 40) fail("too many symbolic links");
    t.fd = descriptor_path(t.path);
    if (t.fd >= 0) return t;
    if (::lstat(t.path.c_str(), &t.st) != 0) {
      if (errno != ENOENT) fail(std::strerror(errno));
      break;
    }
    if (!S_ISLNK(t.st.st_mode)) {
      t.exists = true;
      break;
    }
    std::string link(4096, '\0');
    const ssize_t n = ::readlink(t.path.c_str(), link.data(), link.size());
    if (n <= 0 || static_cast<std::size_t>(n) >= link.size()) fail("cannot follow this symbolic link");
    link.resize(static_cast<std::size_t>(n));
    t.path = link[0] == '/' ? link : (fs::path(t.path).parent_path() / link).string();
  }
  if (t.exists && S_ISDIR(t.st.st_mode)) fail("is a directory");
  if (!t.exists && t.path.back() == '/') fail("names a directory");
  if (t.exists && S_ISREG(t.st.st_mode) &&
      (::access(t.path.c_str(), W_OK) != 0 || (t.st.st_mode & (S_IWUSR | S_IWGRP | S_IWOTH)) == 0)) {
    fail("is read-only; whatnext does not replace it");
  }
  return t;
}

}  // namespace

std::string regular_output_target(const std::string& path, const std::string& option) {
  const auto fail = [&](const std::string& why) {
    throw InputError(fmt::format("{} {}: {}", option, path.empty() ? "''" : printable(path, 96), why));
  };
  const Target t = resolve(path, fail);
  if (t.fd >= 0 || (t.exists && !S_ISREG(t.st.st_mode))) fail("must be a regular file");
  return t.path;
}

void AtomicFile::fail(const std::string& why) const {
  throw InputError(fmt::format("{} {}: {}", option_, path_.empty() ? "''" : printable(path_, 96), why));
}

AtomicFile::AtomicFile(std::string path, std::string option) : option_(std::move(option)), path_(std::move(path)) {
  const Target t = resolve(path_, [this](const std::string& why) { fail(why); });
  const struct stat& st = t.st;
  if (t.fd >= 0) {
    // An open descriptor: written through, if it is open for writing.
    const int flags = ::fcntl(t.fd, F_GETFL);
    if (flags < 0) fail(fmt::format("descriptor {} is not open", t.fd));
    if ((flags & O_ACCMODE) == O_RDONLY) fail(fmt::format("descriptor {} is not open for writing", t.fd));
    struct stat fst {};
    if (::fstat(t.fd, &fst) == 0) dev_ = fst.st_dev, ino_ = fst.st_ino;
    if (t.fd == 1) std::fflush(stdout);
    through_ = true;
    buf_.fd = t.fd;
    return;
  }
  if (t.exists && !S_ISREG(st.st_mode)) {
    // A device, pipe or socket: written through in place, never replaced.
    const int fd = ::open(t.path.c_str(), O_WRONLY | O_CLOEXEC | O_NOCTTY);
    if (fd < 0) fail(fmt::format("cannot write: {}", std::strerror(errno)));
    const struct stat null = null_device_stat();
    null_device_ = S_ISCHR(st.st_mode) && st.st_rdev == null.st_rdev;
    dev_ = st.st_dev, ino_ = st.st_ino;
    through_ = owns_fd_ = true;
    buf_.fd = fd;
    return;
  }
  if (t.exists) dev_ = st.st_dev, ino_ = st.st_ino;
  target_ = t.path;
  tmp_ = t.path + ".part";
  int fd = -1;
  {
    std::lock_guard<std::mutex> hold(interrupts().lock);
    fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd < 0 && errno == EEXIST) {  // left by a killed run: ours to replace
      ::unlink(tmp_.c_str());
      fd = ::open(tmp_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    }
    if (fd < 0) {
      const std::string why = std::strerror(errno);
      tmp_.clear();
      fail(fmt::format("cannot write here: {}", why));
    }
    interrupts().paths.push_back(tmp_);
  }
  if (t.exists) (void)::fchmod(fd, st.st_mode & 07777);
  owns_fd_ = true;
  buf_.fd = fd;
}

AtomicFile::~AtomicFile() {
  if (owns_fd_) ::close(buf_.fd);
  if (!committed_ && !tmp_.empty()) {
    std::lock_guard<std::mutex> hold(interrupts().lock);
    ::unlink(tmp_.c_str());
    auto& paths = interrupts().paths;
    const auto it = std::find(paths.rbegin(), paths.rend(), tmp_);
    if (it != paths.rend()) paths.erase(std::next(it).base());
  }
}

bool AtomicFile::to_stdout() const { return through_ && buf_.fd == 1; }

void AtomicFile::flush() {
  out_.flush();
  if (buf_.error != 0 || !out_) {
    throw OutputError(fmt::format("{} {}: writing failed: {}", option_, printable(path_, 96),
                                  std::strerror(buf_.error != 0 ? buf_.error : EIO)));
  }
}

void AtomicFile::commit() {
  flush();
  if (through_) {
    committed_ = true;
    return;
  }
  const int fd = buf_.fd;
  owns_fd_ = false;
  buf_.fd = -1;
  if (::close(fd) != 0) {
    throw OutputError(fmt::format("{} {}: writing failed: {}", option_, printable(path_, 96), std::strerror(errno)));
  }
  std::lock_guard<std::mutex> hold(interrupts().lock);  // an interrupt waits for the name
  // The old file goes first, then the new one takes its name: never a partial file under it, and
  // for the microseconds between, none. Renamed over the old file, ext4 would write the new one's
  // delayed blocks out at once (auto_da_alloc, its guard against empty files after a power cut,
  // a promise this program does not make: it never fsyncs): 2.6 ms of example 3's 5.8 MB .dat,
  // a fifth of the whole run (docs/performance.md). An unlink that fails leaves it to rename.
  ::unlink(target_.c_str());
  if (::rename(tmp_.c_str(), target_.c_str()) != 0) {
    throw OutputError(fmt::format("{} {}: writing failed: {}", option_, printable(path_, 96), std::strerror(errno)));
  }
  committed_ = true;
  auto& paths = interrupts().paths;
  const auto it = std::find(paths.rbegin(), paths.rend(), tmp_);
  if (it != paths.rend()) paths.erase(std::next(it).base());
}

void AtomicFile::check_distinct(const std::vector<const AtomicFile*>& files) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const AtomicFile& a = *files[i];
      const AtomicFile& b = *files[j];
      if (a.null_device_ && b.null_device_) continue;
      const bool same_existing = a.ino_ != 0 && a.dev_ == b.dev_ && a.ino_ == b.ino_;
      const bool same_new = a.ino_ == 0 && b.ino_ == 0 && !a.target_.empty() &&
                            fs::absolute(a.target_).lexically_normal() == fs::absolute(b.target_).lexically_normal();
      if (same_existing || same_new) a.fail(fmt::format("is the same file as {}; give each output its own", b.option_));
    }
  }
}

// --- text --------------------------------------------------------------------------------------

std::string outcome_sentence(const Result& result) {
  require_finite(result);
  const Event& e = result.outcome();
  const Snapshot& s = e.after;
  switch (e.type) {
    case EventType::lid_open:
      return fmt::format("lid open at {:.3f} s", e.t);
    case EventType::seesaw_vertical:
      return fmt::format("seesaw vertical at {:.3f} s with the sandbag {:.4g} m out; the lid never "
                         "opens (it is at {:.1f} deg)", e.t, s.r, s.phi_l * kRadToDeg);
    case EventType::sandbag_at_pivot:
      return fmt::format("sandbag reaches the pivot at {:.3f} s; the lid has not opened (it is at "
                         "{:.1f} deg)", e.t, s.phi_l * kRadToDeg);
    case EventType::rope_locked:
      // Either the lid or the seesaw's arm has come in line with the straight rope (docs/model.md):
      // the linkage cannot move on; which of the two is not in the result, so the line names both.
      return fmt::format("linkage locked at {:.3f} s: the straight rope is in line with the lid or the seesaw's "
                         "arm; the lid is at {:.1f} deg", e.t, s.phi_l * kRadToDeg);
    case EventType::radio_on:
      return fmt::format("radio on at t = {:.3f} s", e.t);
    case EventType::timeout:
      // With the radio the lid may have opened (and latched) before: say so, not "no outcome".
      for (const Event& open : result.events) {
        if (open.type == EventType::lid_open) {
          return fmt::format("lid open at {:.3f} s; the radio is not on by t_max = {:.3f} s", open.t, e.t);
        }
      }
      return fmt::format("no outcome by t_max = {:.3f} s: the lid is at {:.1f} deg", e.t,
                         s.phi_l * kRadToDeg);
    case EventType::event_limit:
      return fmt::format("stopped after {} events at {:.3f} s", result.events.size(), e.t);
    default:
      return fmt::format("{} at {:.3f} s", to_string(e.type), e.t);
  }
}

std::string timeline_text(const Result& result, const Scenario& sc, const std::string& source) {
  // Every cell is formatted first and the columns are as wide as their widest cell, so long event
  // names (sandbag_falls_off) and large values (r = 1929.5922 m) never shift a column.
  std::vector<std::array<std::string, 7>> rows;
  rows.push_back({"t [s]", "event", "mode", "phiS[deg]", "phiL[deg]", "r [m]", ""});
  for (const Event& e : result.events) {
    const Snapshot& s = e.after;
    rows.push_back({fmt::format("{:.6f}", e.t), std::string(to_string(e.type)),
                    e.mode_before == e.mode_after
                        ? std::string(to_string(e.mode_after))
                        : fmt::format("{}>{}", to_string(e.mode_before), to_string(e.mode_after)),
                    fmt::format("{:.3f}", s.phi_s * kRadToDeg), fmt::format("{:.3f}", s.phi_l * kRadToDeg),
                    fmt::format("{:.4f}", s.r),
                    e.impact ? fmt::format("energy {:.4f} J -> {:.4f} J", e.energy_before, e.energy_after) : ""});
  }
  std::array<std::size_t, 7> width{12, 16, 7, 9, 9, 9, 0};
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out = fmt::format("whatnext: {} (impact law {}, integrator {})\n", source,
                                to_string(sc.run.impact_law), to_string(sc.run.integrator));
  for (const auto& row : rows) {
    std::string line = fmt::format("{:>{}}  {:<{}} {:<{}} {:>{}} {:>{}} {:>{}}", row[0], width[0], row[1], width[1],
                                   row[2], width[2], row[3], width[3], row[4], width[4], row[5], width[5]);
    if (!row[6].empty()) line += "  " + row[6];
    out += line + "\n";
  }
  out += fmt::format("Outcome: {}.\n", outcome_sentence(result));
  return out;
}

namespace {
// Where the energy is and where it went (docs/extensions.md "Energy ledger").
nlohmann::json ledger(const Snapshot& s) {
  return nlohmann::json{{"sandbag_kinetic", clean(s.sandbag_kinetic)},
                        {"sandbag_potential", clean(s.sandbag_potential)},
                        {"seesaw_kinetic", clean(s.seesaw_kinetic)},
                        {"seesaw_potential", clean(s.seesaw_potential)},
                        {"lid_kinetic", clean(s.lid_kinetic)},
                        {"lid_potential", clean(s.lid_potential)},
                        {"balloon_kinetic", clean(s.balloon_kinetic)},
                        {"balloon_potential", clean(s.balloon_potential)},
                        {"lost_impacts", clean(s.lost_impacts)},
                        {"lost_balloon_catch", clean(s.lost_balloon_catch)},
                        {"dissipated_pivot", clean(s.dissipated_pivot)},
                        {"dissipated_lid_hinge", clean(s.dissipated_hinge)},
                        {"dissipated_drag", clean(s.dissipated_drag)},
                        {"lid_push_on_balloon", clean(s.lid_push_work)},
                        {"initial_total", clean(s.initial_total)},
                        {"residual", s.ledger_residual()}};
}
}  // namespace

std::string events_json(const Result& result, const Scenario& sc, const std::string& source) {
  require_finite(result);
  using nlohmann::json;
  auto state = [](const Snapshot& s) {
    return json{{"x", clean(s.x)},
                {"h", clean(s.h)},
                {"r", clean(s.r)},
                {"dr", clean(s.dr)},
                {"phi_s_deg", clean(s.phi_s * kRadToDeg)},
                {"dphi_s_deg_per_s", clean(s.dphi_s * kRadToDeg)},
                {"phi_l_deg", clean(s.phi_l * kRadToDeg)},
                {"dphi_l_deg_per_s", clean(s.dphi_l * kRadToDeg)},
                {"balloon_h", clean(s.balloon_h)},
                {"energy", clean(s.energy())}};
  };
  json events = json::array();
  for (const Event& e : result.events) {
    json j{{"type", std::string(to_string(e.type))},
           {"t", e.t},
           {"mode_before", std::string(to_string(e.mode_before))},
           {"mode_after", std::string(to_string(e.mode_after))},
           {"state", state(e.after)}};
    if (e.impact) {
      j["energy_before"] = clean(e.energy_before);
      j["energy_after"] = clean(e.energy_after);
    }
    j["ledger"] = ledger(e.after);
    events.push_back(std::move(j));
  }
  const Event& last = result.outcome();
  json doc{{"input", source},
           {"impact_law", std::string(to_string(sc.run.impact_law))},
           {"integrator", std::string(to_string(sc.run.integrator))},
           {"outcome", {{"type", std::string(to_string(last.type))},
                        {"t", last.t},
                        {"sentence", outcome_sentence(result)}}},
           {"events", std::move(events)}};
  return doc.dump(2) + "\n";
}

// --- rows of the CSV and the .dat ------------------------------------------------------------

// A batch's rows, made in chunks of kChunkRows on the calling thread and, with Writing::parallel,
// on a helper thread too; written in order by the calling thread as their chunks are done.
// Chunks are claimed from one atomic word (round, chunks, next), so a helper that wakes late or
// never only leaves more chunks to the caller: the caller never waits for a chunk nobody took.
class RowText {
 public:
  // Writes the text of row i at out (at most max_chars characters) and returns its end. Called
  // from two threads at once with Writing::parallel.
  struct Row {
    const void* context;
    char* (*make)(const void* context, std::size_t i, char* out);
  };

  RowText(std::ostream& out, Writing writing, std::size_t max_chars)
      : out_(out),
        buf_(out.rdbuf()),
        parallel_(writing == Writing::parallel && std::thread::hardware_concurrency() > 1),
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
    write(n, Row{&row, [](const void* c, std::size_t i, char* out) { return (*static_cast<const F*>(c))(i, out); }});
  }

 private:
  static constexpr std::size_t kChunkRows = 128;
  static constexpr std::size_t kChunks = 16;  // a round: 2048 rows, one simulate() batch
  enum : int { pending = 0, done = 1, failed = 2 };

  void write(std::size_t n, Row row) {
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
      for (std::size_t i = from; i < to; ++i) p = row_.make(row_.context, i, p);
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
      if (!out_.good() || !buf_ || buf_->sputn(slot_[from].get(), bytes) != bytes) out_.setstate(std::ios::badbit);
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
  Row row_{};
  std::size_t base_ = 0, end_row_ = 0;
  std::atomic<std::uint64_t> claim_{0};
  std::array<std::atomic<int>, kChunks> state_{};
  std::array<char*, kChunks> end_{};
  std::array<std::exception_ptr, kChunks> error_{};
  std::array<std::unique_ptr<char[]>, kChunks> slot_{};
  std::mutex lock_;
  std::condition_variable wake_;
  std::uint32_t round_ = 0;  // under lock_
  std::atomic<bool> stop_{false};  // set under lock_
  std::thread helper_;
};

namespace {
char* put_text(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

// A CSV row's numbers after t, event, mode and rope_taut (CsvWriter::header()).
constexpr std::size_t kCsvNumbers = 28;
// A comma and numtext::kG9Room characters per number (t and the others), and the two names.
constexpr std::size_t kCsvMaxChars = (1 + kCsvNumbers + 1) * (1 + numtext::kG9Room) + 2 * 255 + 8;

char* format_csv(const Snapshot& s, std::string_view event, char* out) {
  require_finite(s);
  const std::string_view mode = to_string(s.mode);
  if (event.size() > 255 || mode.size() > 255) throw std::logic_error("CsvWriter: a name is too long");
  const double values[kCsvNumbers] = {
      s.x, s.h, s.r, s.dr, s.phi_s * kRadToDeg, s.dphi_s * kRadToDeg, s.phi_l * kRadToDeg,
      s.dphi_l * kRadToDeg, s.balloon_h, s.balloon_v, s.balloon_limit, s.tension, s.energy(),
      s.sandbag_kinetic, s.sandbag_potential, s.lid_kinetic, s.lid_potential, s.seesaw_kinetic,
      s.seesaw_potential, s.balloon_kinetic, s.balloon_potential, s.lost_impacts, s.lost_balloon_catch,
      s.dissipated_pivot, s.dissipated_hinge, s.dissipated_drag, s.lid_push_work, s.ledger_residual()};
  char* p = numtext::put_g9(out, s.t);
  *p++ = ',';
  p = put_text(p, event);
  *p++ = ',';
  p = put_text(p, mode);
  *p++ = ',';
  *p++ = s.rope_taut ? '1' : '0';
  for (const double v : values) {
    *p++ = ',';
    p = numtext::put_g9(p, clean(v));
  }
  *p++ = '\n';
  return p;
}

// A .dat row: seven numbers and the two flags (cr, straight), which are 0 or 1.
constexpr std::size_t kDatMaxChars = 9 * 8 + 1;

char* format_dat(const Snapshot& s, bool slack, char* out) {
  const double values[7] = {s.t, s.x, s.h, s.phi_s, s.phi_l, s.balloon_limit, s.balloon_h};
  // Refused as in every writer, but only the numbers written are looked at: the samples are
  // positions (sample_detail), and this runs 80,000 times for example 3 at the paper's step.
  // (x - x is 0 for finite x, NaN otherwise: one test for all seven.)
  double sum = 0.0;
  for (const double v : values) sum += v - v;
  if (sum != 0.0) not_finite(s);
  char* p = out;
  for (const double v : values) p = numtext::put_f8_3(p, v == 0.0 ? 0.0 : v);  // fortran_f(v, 8, 3): no -0.000
  std::memcpy(p, slack ? "   1.000" : "   0.000", 8);
  std::memcpy(p + 8, s.rope_taut ? "   1.000" : "   0.000", 8);
  p[16] = '\n';
  return p + 17;
}
}  // namespace

// --- CSV ---------------------------------------------------------------------------------------

CsvWriter::CsvWriter(std::ostream& out, Writing writing) {
  out << header() << '\n';
  rows_ = std::make_unique<RowText>(out, writing, kCsvMaxChars);
}

CsvWriter::~CsvWriter() = default;

const char* CsvWriter::header() {
  return "t_s,event,mode,rope_taut,x_m,h_m,r_m,dr_m_per_s,phi_s_deg,dphi_s_deg_per_s,phi_l_deg,"
         "dphi_l_deg_per_s,balloon_h_m,balloon_v_m_per_s,balloon_limit_m,tension_N,energy_J,"
         "sandbag_kinetic_J,sandbag_potential_J,lid_kinetic_J,lid_potential_J,"
         "seesaw_kinetic_J,seesaw_potential_J,balloon_kinetic_J,balloon_potential_J,lost_impacts_J,"
         "lost_balloon_catch_J,dissipated_pivot_J,dissipated_lid_hinge_J,dissipated_drag_J,"
         "lid_push_on_balloon_J,ledger_residual_J";
}

void CsvWriter::on_sample(const Snapshot& s) {
  rows_->write(1, [&](std::size_t, char* out) { return format_csv(s, "", out); });
}

void CsvWriter::on_samples(const SampleBatch& batch) {
  rows_->write(batch.size(), [&](std::size_t i, char* out) { return format_csv(batch.snapshot(i), "", out); });
}

void CsvWriter::on_event(const Event& e) {
  rows_->write(1, [&](std::size_t, char* out) { return format_csv(e.after, to_string(e.type), out); });
}

// --- .dat ------------------------------------------------------------------------------------------

std::string fortran_f(double value, int width, int decimals) {
  std::string s = fmt::format("{:>{}.{}f}", clean(value), width, decimals);
  if (static_cast<int>(s.size()) > width) return std::string(static_cast<std::size_t>(width), '*');
  return s;
}

DatWriter::DatWriter(std::ostream& out, Writing writing)
    : rows_(std::make_unique<RowText>(out, writing, kDatMaxChars)) {}

DatWriter::~DatWriter() = default;

void DatWriter::on_sample(const Snapshot& s) {
  rows_->write(1, [&](std::size_t, char* out) { return format_dat(s, slack_since_last_row_, out); });
  slack_since_last_row_ = false;
}

void DatWriter::on_samples(const SampleBatch& batch) {
  const bool slack = slack_since_last_row_;
  rows_->write(batch.size(),
               [&](std::size_t i, char* out) { return format_dat(batch.snapshot(i), i == 0 && slack, out); });
  slack_since_last_row_ = false;
}

void DatWriter::on_event(const Event& e) {
  if (e.type == EventType::rope_slack) slack_since_last_row_ = true;
}

}  // namespace whatnext
