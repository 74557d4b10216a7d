// Output files that appear whole or not at all: written beside their target and renamed into
// place only when complete.
#pragma once

#include <memory>
#include <ostream>
#include <streambuf>
#include <string>
#include <vector>

#include "whatnext/errors.hpp"

namespace whatnext {

// Buffered writes to a file descriptor that keep the errno of the first one that failed (then
// nothing more is written): the outputs' files and a sweep's resumable .part file.
class FdStreamBuf : public std::streambuf {
 public:
  explicit FdStreamBuf(int descriptor = -1);
  int fd = -1;
  int error = 0;  // errno of the first failed write
  // A new regular file of this process (AtomicFile's temporary): its pages are sent to the disk
  // every megabyte as it grows (write-behind), not all at once by the rename that replaces an
  // old file with it. It is complete and in place no sooner: the rename still comes after the last
  // write and the close.
  bool write_behind = false;

 protected:
  int_type overflow(int_type ch) override;
  int sync() override;
  std::streamsize xsputn(const char* s, std::streamsize n) override;

 private:
  bool drain();
  void send_behind();
  char buffer_[1 << 16];
  long long written_ = 0, sent_ = 0;  // bytes written, and of those sent on their way
};

// An output file, checked when constructed (before any work; InputError naming `option` and the
// path otherwise) and complete only after commit():
//  * "-" is standard output; /dev/stdout, /dev/stderr and /dev/fd/N are those open descriptors;
//    an existing character device, pipe or socket (/dev/null, a FIFO) is written through in place.
//    These are never replaced, and what was written before a failure stays written.
//  * anything else is a regular file: symlinks are followed to their target, which is written as a
//    temporary beside it, created exclusively under a name of this process's own
//    (".NAME.XXXXXX.part"), and renamed over the target by commit() only when every write and
//    the close succeeded, keeping an existing file's permissions: the name holds the old file or
//    the complete new one, never a part, and no other file is touched. Nothing is left behind
//    without commit(), nor when the process is interrupted (see install_interrupt_cleanup). A
//    directory, or an existing file without write permission (even for root), is refused.
class AtomicFile {
 public:
  explicit AtomicFile(std::string path, std::string option = "output");
  // An output opened once the work is under way (a figure, a frame): a path that fails now, its
  // directory removed meanwhile, is a failed write (OutputError), not bad input.
  static std::unique_ptr<AtomicFile> during_work(std::string path, std::string option);
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  std::ostream& stream() { return out_; }
  const std::string& path() const { return path_; }
  // Where a writer that needs a file name (PLplot) writes instead of stream(); empty for outputs
  // that are written through in place. commit() then checks that the file it wrote is complete
  // (a PNG, SVG or PDF by its end; anything else not empty), for such writers ignore failed writes.
  const std::string& temp_path() const;
  // The open descriptor, for a writer that writes and checks its writes itself (giflib).
  int descriptor() const;
  bool to_stdout() const;
  // Sends everything written so far on its way; OutputError when that failed.
  void flush();
  // Everything but putting the file in place: flush(), the check of a file written by name, and
  // closing it; OutputError when any failed. Several files committed together finish() first.
  void finish();
  // finish(), then the file appears under its name.
  void commit();
  // Throws InputError when two of the files are the same (as given, through a symlink or a
  // descriptor); several outputs may go to /dev/null.
  static void check_distinct(const std::vector<const AtomicFile*>& files);

 private:
  std::string option_, path_, target_, tmp_, tmp_name_;
  int dir_fd_ = -1;       // target's folder (the temporary's), for renameat and unlinkat
  bool through_ = false;  // written in place (no temporary)
  bool owns_fd_ = false;
  bool committed_ = false;
  bool finished_ = false;
  unsigned long long dev_ = 0, ino_ = 0;  // identity, for check_distinct (0: a new file)
  bool null_device_ = false;
  mutable bool named_ = false;  // temp_path() was handed out: written by name
  FdStreamBuf buf_;
  std::ostream out_{&buf_};
  [[noreturn]] void fail(const std::string& why) const;
  [[noreturn]] void write_failed(const std::string& why) const;
  void check_written_by_name() const;
};

// 0 when a new file can be created in dir (tried with a temporary of this process's own, removed
// at once), the errno otherwise.
int can_create_in(const std::string& dir);

// The regular file an output path names, symlinks followed, for writers that make and rename
// their own temporary (the animation). InputError naming option when it is a directory, a device,
// a pipe or read-only.
std::string regular_output_target(const std::string& path, const std::string& option);

}  // namespace whatnext
