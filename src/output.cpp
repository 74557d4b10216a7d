#include "whatnext/output.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <atomic>
#include <cerrno>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <condition_variable>
#include <cstdint>
#include <cstring>
#include <deque>
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
  std::lock_guard<std::mutex> hold(interrupts().lock);
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

// A writer's rows as fixed-size records of their numbers, turned into text by `format` (at most
// max_chars characters a row): at once, or in blocks on a thread of its own (Writing).
class RowPipe {
 public:
  using Format = char* (*)(const void* record, char* out);
  RowPipe(std::ostream& out, Writing writing, std::size_t record_size, std::size_t max_chars, Format format)
      : out_(out),
        buf_(out.rdbuf()),
        background_(writing == Writing::background),
        size_(record_size),
        max_chars_(max_chars),
        format_(format),
        block_bytes_(std::max<std::size_t>(1, kBlockBytes / record_size) * record_size) {}
  ~RowPipe() { finish(); }
  RowPipe(const RowPipe&) = delete;
  RowPipe& operator=(const RowPipe&) = delete;

  void add(const void* record) {
    if (!background_) {
      if (text_.empty()) text_.resize(max_chars_);
      const char* end = format_(record, text_.data());
      const auto n = static_cast<std::streamsize>(end - text_.data());
      if (!out_.good() || !buf_ || buf_->sputn(text_.data(), n) != n) out_.setstate(std::ios::badbit);
      return;
    }
    if (block_.data.empty()) block_.data.resize(block_bytes_);
    std::memcpy(block_.data.data() + block_.used, record, size_);
    block_.used += size_;
    if (block_.used == block_bytes_) hand_over();
  }

  // Waits for the worker; the rows are all in the stream after it, and any row added later goes
  // there at once.
  void finish() {
    if (!background_) return;
    background_ = false;
    if (worker_.joinable()) {
      if (block_.used > 0) hand_over();
      {
        std::lock_guard<std::mutex> hold(lock_);
        done_ = true;
      }
      more_.notify_one();
      worker_.join();
    } else if (block_.used > 0) {
      write_block(block_);  // fewer rows than a block: no thread for them
    }
    block_.used = 0;
    if (failed_) out_.setstate(std::ios::badbit);
  }

 private:
  // 32 KiB of records a block, at most kPending of them waiting, so that a slow disk holds back
  // the run instead of filling the memory: every page touched costs (docs/performance.md), and
  // so does every hand-over that wakes the other thread.
  static constexpr std::size_t kBlockBytes = 1 << 15;
  static constexpr std::size_t kPending = 3;
  struct Block {
    std::vector<char> data;  // block_bytes_, once allocated
    std::size_t used = 0;
  };

  void hand_over() {
    if (!worker_.joinable() && !failed_) {
      // Everything the worker uses is allocated here, so that it allocates nothing: a thread's
      // first allocation would make it a malloc arena of its own.
      text_.resize(std::max<std::size_t>(kBlockBytes, max_chars_));
      spare_.reserve(kPending + 2);
      try {
        worker_ = std::thread([this] { work(); });
      } catch (const std::system_error&) {  // no threads here: the rows are written at once
        write_block(block_);
        block_.used = 0;
        background_ = false;
        return;
      }
    }
    Block next;
    {
      std::unique_lock<std::mutex> hold(lock_);
      room_.wait(hold, [this] { return queue_.size() < kPending; });
      queue_.push_back(std::move(block_));
      if (!spare_.empty()) {
        next = std::move(spare_.back());
        spare_.pop_back();
      }
      if (!idle_) {  // the worker looks at the queue before it sleeps: no wake-up needed
        block_ = std::move(next);
        block_.used = 0;
        return;
      }
    }
    more_.notify_one();
    block_ = std::move(next);
    block_.used = 0;
  }

  void work() {
    std::unique_lock<std::mutex> hold(lock_);
    for (;;) {
      if (queue_.empty()) {
        if (done_) return;
        idle_ = true;
        more_.wait(hold, [this] { return !queue_.empty() || done_; });
        idle_ = false;
        continue;
      }
      Block block = std::move(queue_.front());
      queue_.pop_front();
      const bool full = queue_.size() + 1 == kPending;
      hold.unlock();
      if (full) room_.notify_one();
      write_block(block);
      hold.lock();
      spare_.push_back(std::move(block));
    }
  }

  // The records' text, through a buffer of a block's size, to the stream (one thread at a time).
  void write_block(const Block& block) {
    if (failed_) return;
    if (text_.size() < std::max<std::size_t>(kBlockBytes, max_chars_)) {
      text_.resize(std::max<std::size_t>(kBlockBytes, max_chars_));
    }
    char* const begin = text_.data();
    char* p = begin;
    const auto flush = [&] {
      const auto n = static_cast<std::streamsize>(p - begin);
      if (!buf_ || buf_->sputn(begin, n) != n) failed_ = true;
      p = begin;
    };
    for (std::size_t at = 0; at < block.used && !failed_; at += size_) {
      if (static_cast<std::size_t>(begin + text_.size() - p) < max_chars_) flush();
      p = format_(block.data.data() + at, p);
    }
    if (!failed_) flush();
  }

  std::ostream& out_;
  std::streambuf* buf_;
  bool background_;
  const std::size_t size_, max_chars_;
  const Format format_;
  const std::size_t block_bytes_;
  Block block_;             // the records not yet handed over (background)
  std::vector<char> text_;  // at once: one row; background: the worker's, or finish()'s
  std::mutex lock_;
  std::condition_variable more_, room_;
  std::deque<Block> queue_;    // blocks for the worker, in order
  std::vector<Block> spare_;   // written blocks, for reuse
  bool done_ = false;
  bool idle_ = false;  // the worker waits for a block
  std::atomic<bool> failed_{false};
  std::thread worker_;
};

namespace {
char* put_text(char* out, std::string_view text) {
  std::memcpy(out, text.data(), text.size());
  return out + text.size();
}

// A CSV row's numbers: everything after t, event, mode and rope_taut (CsvWriter::header()).
constexpr std::size_t kCsvNumbers = 28;
struct CsvRecord {
  double t;
  double values[kCsvNumbers];
  const char* event;  // to_string(EventType) and to_string(Mode): names that live for good
  const char* mode;
  std::uint8_t event_size, mode_size;
  bool taut;
};
// A comma and numtext::kG9Room characters per number, and the names (CsvRecord's sizes).
constexpr std::size_t kCsvMaxChars = (1 + kCsvNumbers + 1) * (1 + numtext::kG9Room) + 2 * 255 + 8;

char* format_csv(const void* record, char* out) {
  CsvRecord r;
  std::memcpy(&r, record, sizeof r);
  char* p = numtext::put_g9(out, r.t);
  *p++ = ',';
  p = put_text(p, {r.event, r.event_size});
  *p++ = ',';
  p = put_text(p, {r.mode, r.mode_size});
  *p++ = ',';
  *p++ = r.taut ? '1' : '0';
  for (const double v : r.values) {
    *p++ = ',';
    p = numtext::put_g9(p, v);
  }
  *p++ = '\n';
  return p;
}

// A .dat row: seven numbers and the two flags (cr, straight), which are 0 or 1.
struct DatRecord {
  double values[7];
  bool slack, taut;
};
constexpr std::size_t kDatMaxChars = 9 * 8 + 1;

char* format_dat(const void* record, char* out) {
  DatRecord r;
  std::memcpy(&r, record, sizeof r);
  char* p = out;
  for (const double v : r.values) p = numtext::put_f8_3(p, v == 0.0 ? 0.0 : v);  // fortran_f(v, 8, 3): no -0.000
  std::memcpy(p, r.slack ? "   1.000" : "   0.000", 8);
  std::memcpy(p + 8, r.taut ? "   1.000" : "   0.000", 8);
  p[16] = '\n';
  return p + 17;
}
}  // namespace

// --- CSV ---------------------------------------------------------------------------------------

CsvWriter::CsvWriter(std::ostream& out, Writing writing) {
  out << header() << '\n';
  pipe_ = std::make_unique<RowPipe>(out, writing, sizeof(CsvRecord), kCsvMaxChars, format_csv);
}

CsvWriter::~CsvWriter() = default;

void CsvWriter::finish() { pipe_->finish(); }

const char* CsvWriter::header() {
  return "t_s,event,mode,rope_taut,x_m,h_m,r_m,dr_m_per_s,phi_s_deg,dphi_s_deg_per_s,phi_l_deg,"
         "dphi_l_deg_per_s,balloon_h_m,balloon_v_m_per_s,balloon_limit_m,tension_N,energy_J,"
         "sandbag_kinetic_J,sandbag_potential_J,lid_kinetic_J,lid_potential_J,"
         "seesaw_kinetic_J,seesaw_potential_J,balloon_kinetic_J,balloon_potential_J,lost_impacts_J,"
         "lost_balloon_catch_J,dissipated_pivot_J,dissipated_lid_hinge_J,dissipated_drag_J,"
         "lid_push_on_balloon_J,ledger_residual_J";
}

void CsvWriter::row(const Snapshot& s, std::string_view event) {
  require_finite(s);
  const std::string_view mode = to_string(s.mode);
  if (event.size() > 255 || mode.size() > 255) throw std::logic_error("CsvWriter: a name is too long");
  CsvRecord r{s.t,
              {s.x, s.h, s.r, s.dr, s.phi_s * kRadToDeg, s.dphi_s * kRadToDeg, s.phi_l * kRadToDeg,
               s.dphi_l * kRadToDeg, s.balloon_h, s.balloon_v, s.balloon_limit, s.tension, s.energy(),
               s.sandbag_kinetic, s.sandbag_potential, s.lid_kinetic, s.lid_potential, s.seesaw_kinetic,
               s.seesaw_potential, s.balloon_kinetic, s.balloon_potential, s.lost_impacts, s.lost_balloon_catch,
               s.dissipated_pivot, s.dissipated_hinge, s.dissipated_drag, s.lid_push_work, s.ledger_residual()},
              event.data(),
              mode.data(),
              static_cast<std::uint8_t>(event.size()),
              static_cast<std::uint8_t>(mode.size()),
              s.rope_taut};
  for (double& v : r.values) v = clean(v);
  pipe_->add(&r);
}

void CsvWriter::on_sample(const Snapshot& s) { row(s, ""); }
void CsvWriter::on_event(const Event& e) { row(e.after, to_string(e.type)); }

// --- .dat --------------------------------------------------------------------------------------

std::string fortran_f(double value, int width, int decimals) {
  std::string s = fmt::format("{:>{}.{}f}", clean(value), width, decimals);
  if (static_cast<int>(s.size()) > width) return std::string(static_cast<std::size_t>(width), '*');
  return s;
}

DatWriter::DatWriter(std::ostream& out, Writing writing)
    : pipe_(std::make_unique<RowPipe>(out, writing, sizeof(DatRecord), kDatMaxChars, format_dat)) {}

DatWriter::~DatWriter() = default;

void DatWriter::finish() { pipe_->finish(); }

void DatWriter::on_sample(const Snapshot& s) {
  const DatRecord r{{s.t, s.x, s.h, s.phi_s, s.phi_l, s.balloon_limit, s.balloon_h}, slack_since_last_row_,
                    s.rope_taut};
  // Refused as in every writer, but only the numbers written are looked at: the samples are
  // positions (sample_detail), and this runs 80,000 times for example 3 at the paper's step.
  // (x - x is 0 for finite x, NaN otherwise: one test for all seven.)
  double sum = 0.0;
  for (const double v : r.values) sum += v - v;
  if (sum != 0.0) not_finite(s);
  pipe_->add(&r);
  slack_since_last_row_ = false;
}

void DatWriter::on_event(const Event& e) {
  if (e.type == EventType::rope_slack) slack_since_last_row_ = true;
}

}  // namespace whatnext
