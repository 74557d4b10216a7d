// The CSV file of a sweep, written so that an interrupted sweep can be resumed (docs/explore.md,
// "Resuming a sweep"): the command's --out and --resume, and Python's sweep(csv=..., resume=...).
#pragma once

#include <memory>
#include <ostream>
#include <string>
#include <string_view>

#include "whatnext/atomic_file.hpp"

namespace whatnext::explore {

// The rows go to TARGET.part beside the target (in index order, as explore::run writes them) and
// are synced to the disk by sync(); commit() syncs the file and renames it over TARGET, which until
// then stays as it was. TARGET.part is never removed once started: a kill, a crash or a power cut
// leaves the rows written so far there for the next sweep that resumes. It is locked while a sweep
// writes it (flock), so that two sweeps never write one file; the lock goes with the process.
class SweepFile {
 public:
  // target: the regular file the CSV ends in, symlinks followed (regular_output_target); given: the
  // name as the user wrote it, and option the argument that gave it ("--out", "sweep(csv=...)"),
  // for messages. Claims TARGET.part, creating it if there is none. InputError (one line) when it is
  // not a regular file, cannot be made, or another sweep is writing it.
  SweepFile(std::string target, std::string given, std::string option);
  ~SweepFile();
  SweepFile(const SweepFile&) = delete;
  SweepFile& operator=(const SweepFile&) = delete;

  // What an interrupted sweep left to resume: the .part file's text if it held any, else the
  // target's, else nothing. from_part() says which; source() names it for messages (as given).
  // InputError when it cannot be read.
  std::string previous();
  bool from_part() const { return from_part_; }
  std::string source() const;

  // Starts the sweep's file with `kept`: when from_part(), the first kept.size() bytes of the .part
  // file stay and the rest is cut; otherwise the file is made anew from kept (empty: a sweep from
  // the start), keeping the target's permissions. Synced before it returns. InputError, and the
  // file untouched, where an existing .part file is not a sweep's (the user's own file).
  void start(std::string_view kept);
  // Where the rows are written (buffered).
  std::ostream& stream();
  // Flushes and syncs what was written (fdatasync): a kill or power cut after this keeps it.
  // OutputError when a write failed.
  void sync();
  // sync(), then the file appears under the target's name. OutputError when that failed.
  void commit();

 private:
  std::string target_, part_, given_, option_;
  int fd_ = -1;
  bool created_ = false;  // TARGET.part did not exist before: removed again if never started
  bool started_ = false, from_part_ = false;
  std::unique_ptr<FdStreamBuf> buf_;  // atomic_file.hpp
  std::unique_ptr<std::ostream> out_;
  [[noreturn]] void fail(const std::string& why, bool output) const;
};

}  // namespace whatnext::explore
