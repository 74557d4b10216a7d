// Output files that appear under their name only when complete (AtomicFile), and the checks of an
// output path made before any work.
#include <fcntl.h>
#include <time.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cctype>
#include <cstdint>
#include <ctime>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <functional>
#include <iterator>
#include <mutex>

#include <fmt/format.h>

#include "interrupts.hpp"
#include "whatnext/config.hpp"
#include "whatnext/atomic_file.hpp"
#include "whatnext/interrupts.hpp"

namespace whatnext {

namespace fs = std::filesystem;

using namespace io;

// --- AtomicFile --------------------------------------------------------------------------------

FdStreamBuf::FdStreamBuf(int descriptor) : fd(descriptor) { setp(buffer_, buffer_ + sizeof buffer_); }

bool FdStreamBuf::drain() {
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
    written_ += n;
  }
  setp(buffer_, buffer_ + sizeof buffer_);
  if (write_behind && error == 0) send_behind();
  return error == 0;
}

// When a rename replaces a file, ext4 first starts writing the new file's pages that were not yet
// written (auto_da_alloc: so that a power cut cannot leave the name holding an empty file), and
// the rename waits for that: 3.5 ms of the 17 ms of example 3's .dat on one core. Started as the
// file grows, the writes go on while the rows are made, and the rename finds little left to do.
// Only a hint to the kernel: what it refuses changes nothing but the time (docs/performance.md).
void FdStreamBuf::send_behind() {
  constexpr long long kWriteBehind = 1 << 20;
  if (written_ - sent_ < kWriteBehind) return;
#if defined(__linux__) && !defined(__EMSCRIPTEN__)
  (void)::sync_file_range(fd, sent_, written_ - sent_, SYNC_FILE_RANGE_WRITE);
#endif
  sent_ = written_;
}

FdStreamBuf::int_type FdStreamBuf::overflow(int_type ch) {
  if (!drain()) return traits_type::eof();
  if (!traits_type::eq_int_type(ch, traits_type::eof())) {
    *pptr() = traits_type::to_char_type(ch);
    pbump(1);
  }
  return traits_type::not_eof(ch);
}

int FdStreamBuf::sync() { return drain() ? 0 : -1; }

std::streamsize FdStreamBuf::xsputn(const char* s, std::streamsize n) {
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
  for (const std::string& prefix :
       {std::string("/dev/fd/"), std::string("/proc/self/fd/"), fmt::format("/proc/{}/fd/", ::getpid())}) {
    if (p.size() > prefix.size() && p.compare(0, prefix.size(), prefix) == 0) {
      const std::string num = p.substr(prefix.size());
      if (num.size() < 6 &&
          std::all_of(num.begin(), num.end(), [](char c) { return c >= '0' && c <= '9'; })) {
        return std::stoi(num);
      }
    }
  }
  return -1;
}

// The folder a file is in, opened: the temporary is created, renamed and removed through it, so
// that a folder moved meanwhile keeps no temporary and receives the complete file.
int open_folder_of(const std::string& path) {
  const std::string dir = fs::path(path).parent_path().string();
  return ::open(dir.empty() ? "." : dir.c_str(), O_PATH | O_DIRECTORY | O_CLOEXEC);
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

// A new file beside target, created exclusively under a name no other process holds:
// ".NAME.XXXXXX.part", XXXXXX random (as rsync's temporaries). A user's own NAME.part is never
// touched, and two processes writing one name each write their own temporary.
// dir_fd is target's folder, opened; tmp gets the temporary's path, name its name in the folder.
int create_temp(int dir_fd, const std::string& target, std::string& tmp, std::string& name) {
  static std::atomic<std::uint64_t> counter{0};
  const fs::path p(target);
  std::string base = p.filename().string();
  if (base.size() > 200) base.resize(200);  // within NAME_MAX with the marks around it
  timespec now{};
  ::clock_gettime(CLOCK_REALTIME, &now);
  std::uint64_t x = (static_cast<std::uint64_t>(::getpid()) << 32) ^ static_cast<std::uint64_t>(now.tv_nsec) ^
                    (static_cast<std::uint64_t>(now.tv_sec) << 20);
  static const char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  for (int attempt = 0; attempt < 1000; ++attempt) {
    // splitmix64: a different name on every attempt, in every process and thread.
    std::uint64_t z = (x += 0x9e3779b97f4a7c15ull + counter.fetch_add(1, std::memory_order_relaxed));
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    z ^= z >> 31;
    std::string suffix(6, 'x');
    for (char& c : suffix) c = kChars[z % 62], z /= 62;
    name = "." + base + "." + suffix + ".part";
    tmp = (p.parent_path() / name).string();
    const int fd = ::openat(dir_fd, name.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
    if (fd >= 0 || errno != EEXIST) return fd;
  }
  errno = EEXIST;
  return -1;
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

int can_create_in(const std::string& dir) {
  std::string tmp, name;
  const std::string probe = (fs::path(dir.empty() ? "." : dir) / "probe").string();
  const int dir_fd = open_folder_of(probe);
  if (dir_fd < 0) return errno;
  // Made and removed under the interrupts' lock: an interrupt meanwhile waits for it to be gone
  // (a SIGHUP 9 ms into an animation left it behind).
  std::lock_guard<std::mutex> hold(interrupts().lock);
  const int fd = create_temp(dir_fd, probe, tmp, name);
  const int err = errno;
  if (fd >= 0) {
    ::close(fd);
    ::unlinkat(dir_fd, name.c_str(), 0);  // the file just made, exclusively: nobody else's
  }
  ::close(dir_fd);
  return fd >= 0 ? 0 : err;
}

void AtomicFile::fail(const std::string& why) const {
  throw InputError(fmt::format("{} {}: {}", option_, path_.empty() ? "''" : printable(path_, 96), why));
}

AtomicFile::AtomicFile(std::string path, std::string option)
    : option_(std::move(option)), path_(std::move(path)) {
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
  int fd = -1;
  {
    // Registered under the lock: an interrupt between creating and registering cannot leave it.
    std::lock_guard<std::mutex> hold(interrupts().lock);
    dir_fd_ = open_folder_of(target_);
    if (dir_fd_ >= 0) fd = create_temp(dir_fd_, target_, tmp_, tmp_name_);
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
  buf_.write_behind = true;
}

std::unique_ptr<AtomicFile> AtomicFile::during_work(std::string path, std::string option) {
  try {
    return std::make_unique<AtomicFile>(std::move(path), std::move(option));
  } catch (const InputError& e) {
    throw OutputError(e.what());
  }
}

AtomicFile::~AtomicFile() {
  if (owns_fd_) ::close(buf_.fd);
  struct CloseFolder {
    int fd;
    ~CloseFolder() {
      if (fd >= 0) ::close(fd);
    }
  } close_folder{dir_fd_};
  if (!committed_ && !tmp_.empty()) {
    std::lock_guard<std::mutex> hold(interrupts().lock);
    ::unlinkat(dir_fd_, tmp_name_.c_str(), 0);
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

void AtomicFile::finish() {
  if (finished_) return;
  flush();
  if (through_) {
    finished_ = true;
    return;
  }
  if (named_) check_written_by_name();
  const int fd = buf_.fd;
  owns_fd_ = false;
  buf_.fd = -1;
  if (::close(fd) != 0) write_failed(std::strerror(errno));
  finished_ = true;
}

void AtomicFile::commit() {
  finish();
  if (through_) {
    committed_ = true;
    return;
  }
  std::lock_guard<std::mutex> hold(interrupts().lock);  // an interrupt waits for the name
  // rename() replaces the old file in one step: the name holds the old file or the new one, never
  // none and never a part, and of two writers of one name the later rename wins whole.
  const std::string target_name = fs::path(target_).filename().string();
  if (::renameat(dir_fd_, tmp_name_.c_str(), dir_fd_, target_name.c_str()) != 0)
    write_failed(std::strerror(errno));
  committed_ = true;
  auto& paths = interrupts().paths;
  const auto it = std::find(paths.rbegin(), paths.rend(), tmp_);
  if (it != paths.rend()) paths.erase(std::next(it).base());
}

const std::string& AtomicFile::temp_path() const {
  named_ = !tmp_.empty();
  return tmp_;
}

void AtomicFile::write_failed(const std::string& why) const {
  throw OutputError(fmt::format("{} {}: writing failed: {}", option_, printable(path_, 96), why));
}

// A library that writes by name (PLplot) does not say when a write failed: on a full disk it
// leaves a short file. Each format's end is checked instead (PNG's IEND chunk, SVG's closing tag,
// PDF's %%EOF); any other file must at least not be empty.
void AtomicFile::check_written_by_name() const {
  std::string tail;
  const int fd = ::openat(dir_fd_, tmp_name_.c_str(), O_RDONLY | O_CLOEXEC);
  struct stat st {};
  if (fd < 0 || ::fstat(fd, &st) != 0) {
    const std::string why = std::strerror(errno);
    if (fd >= 0) ::close(fd);
    write_failed(why);
  }
  const off_t want = std::min<off_t>(st.st_size, 64);
  tail.resize(static_cast<std::size_t>(want));
  const ssize_t n = want > 0 ? ::pread(fd, tail.data(), tail.size(), st.st_size - want) : 0;
  ::close(fd);
  if (n != want) write_failed("cannot read it back");
  const auto ends = [&](std::string_view ext) {
    return target_.size() >= ext.size() &&
           std::equal(ext.rbegin(), ext.rend(), target_.rbegin(),
                      [](char a, char b) { return a == std::tolower(static_cast<unsigned char>(b)); });
  };
  while (!tail.empty() && std::isspace(static_cast<unsigned char>(tail.back()))) tail.pop_back();
  bool complete = !tail.empty();
  if (ends(".png"))
    complete = tail.size() >= 8 && tail.compare(tail.size() - 8, 8, "IEND\xae\x42\x60\x82") == 0;
  if (ends(".svg")) complete = tail.size() >= 6 && tail.compare(tail.size() - 6, 6, "</svg>") == 0;
  if (ends(".pdf")) complete = tail.find("%%EOF") != std::string::npos;
  if (!complete) {
    // Why the library's write failed is not known; writing on past the end (the temporary is
    // discarded) tells the likely reason: a full disk, the file size limit.
    const std::string zeros(1 << 16, '\0');
    for (off_t at = st.st_size; at < st.st_size + (off_t{1} << 20); at += static_cast<off_t>(zeros.size())) {
      if (::pwrite(buf_.fd, zeros.data(), zeros.size(), at) < 0) write_failed(std::strerror(errno));
    }
    write_failed("the drawing library left the file incomplete");
  }
}

int AtomicFile::descriptor() const { return buf_.fd; }

void AtomicFile::check_distinct(const std::vector<const AtomicFile*>& files) {
  for (std::size_t i = 0; i < files.size(); ++i) {
    for (std::size_t j = 0; j < i; ++j) {
      const AtomicFile& a = *files[i];
      const AtomicFile& b = *files[j];
      if (a.null_device_ && b.null_device_) continue;
      const bool same_existing = a.ino_ != 0 && a.dev_ == b.dev_ && a.ino_ == b.ino_;
      const bool same_new =
          a.ino_ == 0 && b.ino_ == 0 && !a.target_.empty() &&
          fs::absolute(a.target_).lexically_normal() == fs::absolute(b.target_).lexically_normal();
      if (same_existing || same_new)
        a.fail(fmt::format("is the same file as {}; give each output its own", b.option_));
    }
  }
}

}  // namespace whatnext
