// Output files that appear under their name only when complete (AtomicFile), and the checks of an
// output path made before any work.
#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
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
#include "whatnext/output.hpp"

namespace whatnext {

namespace fs = std::filesystem;

using namespace io;

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

}  // namespace whatnext
