#include "whatnext/explore/sweep_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/atomic_file.hpp"

namespace whatnext::explore {

SweepFile::SweepFile(std::string target, std::string given, std::string option)
    : target_(std::move(target)),
      part_(target_ + ".part"),
      given_(std::move(given)),
      option_(std::move(option)) {
  struct stat st {};
  if (::lstat(part_.c_str(), &st) == 0 && !S_ISREG(st.st_mode)) {
    throw InputError(fmt::format("{} {}: {}.part is not a regular file", option_, printable(given_, 96),
                                 printable(given_, 96)));
  }
  fd_ = ::open(part_.c_str(), O_RDWR | O_CREAT | O_EXCL | O_CLOEXEC | O_NOFOLLOW, 0666);
  created_ = fd_ >= 0;
  if (fd_ < 0 && errno == EEXIST) fd_ = ::open(part_.c_str(), O_RDWR | O_CLOEXEC | O_NOFOLLOW);
  if (fd_ < 0) fail("cannot write its .part file", false);
  from_part_ = !created_;
  // Two sweeps writing one .part file would interleave their rows: the second is refused. The
  // lock is the process's and goes with it, however it ends.
  if (::flock(fd_, LOCK_EX | LOCK_NB) != 0) {
    const int err = errno;
    ::close(fd_);
    fd_ = -1;
    if (err == EWOULDBLOCK) {
      throw InputError(
          fmt::format("{} {}: another sweep is writing {}.part now; wait for it to end, or give another name",
                      option_, printable(given_, 96), printable(given_, 96)));
    }
    errno = err;
    fail("cannot lock its .part file", false);
  }
}

SweepFile::~SweepFile() {
  if (fd_ < 0) return;
  if (out_) out_->flush();
  // A .part file made here and never started holds nothing of anyone's: no trace of a refused sweep.
  if (created_ && !started_) ::unlink(part_.c_str());
  ::close(fd_);
}

std::string SweepFile::source() const { return from_part_ ? given_ + ".part" : given_; }

std::string SweepFile::previous() {
  std::string text;
  if (from_part_) {
    char block[1 << 16];
    for (off_t at = 0;;) {
      const ssize_t n = ::pread(fd_, block, sizeof block, at);
      if (n < 0 && errno == EINTR) continue;
      if (n < 0) {
        throw InputError(
            fmt::format("{} {}: cannot read it: {}", option_, printable(source(), 96), std::strerror(errno)));
      }
      if (n == 0) break;
      text.append(block, static_cast<std::size_t>(n));
      at += n;
    }
    return text;
  }
  struct stat st {};
  if (::stat(target_.c_str(), &st) != 0) return text;  // nothing to resume
  std::ifstream in(target_, std::ios::binary);
  std::ostringstream all;
  if (in.is_open() && st.st_size > 0) all << in.rdbuf();
  if (!in.is_open() || in.bad())
    throw InputError(fmt::format("{} {}: cannot read it", option_, printable(source(), 96)));
  return all.str();
}

void SweepFile::start(std::string_view kept) {
  const bool in_place = from_part_ && !kept.empty();  // else the file is made anew
  if (from_part_ && !in_place) {
    // A file of that name that no sweep wrote is the user's: never cut. A sweep's begins with its
    // header, or with the zeros a power cut can leave.
    char head[6] = {};
    ssize_t n = 0;
    do n = ::pread(fd_, head, sizeof head, 0);
    while (n < 0 && errno == EINTR);
    if (n > 0 && head[0] != '\0' &&
        std::string_view(head, static_cast<std::size_t>(n)) !=
            std::string_view("index,", static_cast<std::size_t>(n))) {
      throw InputError(
          fmt::format("{} {}: {}.part exists and is not a sweep's CSV; whatnext does not write over "
                      "it (move it away, or give another name)",
                      option_, printable(given_, 96), printable(given_, 96)));
    }
  }
  if (::ftruncate(fd_, static_cast<off_t>(in_place ? kept.size() : 0)) != 0)
    fail("cannot cut its .part file", false);
  struct stat st {};
  if (!in_place && ::stat(target_.c_str(), &st) == 0) (void)::fchmod(fd_, st.st_mode & 07777);
  if (::lseek(fd_, 0, SEEK_END) < 0) fail("cannot write its .part file", false);
  started_ = true;
  buf_ = std::make_unique<FdStreamBuf>(fd_);
  out_ = std::make_unique<std::ostream>(buf_.get());
  if (!in_place) out_->write(kept.data(), static_cast<std::streamsize>(kept.size()));
  out_->flush();
  if (!*out_ || buf_->error != 0) {
    errno = buf_->error;
    fail("cannot write its .part file", false);
  }
  if (::fdatasync(fd_) != 0) fail("cannot sync its .part file", false);
}

std::ostream& SweepFile::stream() { return *out_; }

void SweepFile::sync() {
  out_->flush();
  if (!*out_ || buf_->error != 0) {
    errno = buf_->error ? buf_->error : EIO;
    fail("writing failed", true);
  }
  if (::fdatasync(fd_) != 0) fail("writing failed", true);
}

void SweepFile::commit() {
  sync();
  // Renamed while still locked: no other sweep starts on this .part file before it has its name.
  if (::rename(part_.c_str(), target_.c_str()) != 0) fail("writing failed", true);
  const int fd = fd_;
  fd_ = -1;
  if (::close(fd) != 0) fail("writing failed", true);
}

void SweepFile::fail(const std::string& why, bool output) const {
  const int err = errno ? errno : EIO;
  const std::string line =
      fmt::format("{} {}: {}: {}", option_, printable(given_, 96), why, std::strerror(err));
  if (output) throw OutputError(line);
  throw InputError(line);
}

}  // namespace whatnext::explore
