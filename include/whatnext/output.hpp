// Observers and writers: the readable timeline, events JSON, CSV and the paper's .dat layout.
// Files are written beside their target and renamed into place only when complete.
#pragma once

#include <functional>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <string>
#include <string_view>
#include <vector>

#include "whatnext/columns.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext {

// An output that could not be written once the work was done (disk full, /dev/full, a failing
// pipe). Bad output paths are found before any work and are InputErrors.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

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

// Interrupts (SIGINT, SIGTERM, SIGHUP) of a command that writes files. After this call an
// interrupt removes every AtomicFile temporary in progress and every path handed to
// remove_on_interrupt(), then ends the process by that signal, as it would have ended without.
void install_interrupt_cleanup();
// Files (or empty directories) other writers make, removed on an interrupt until forgotten.
void remove_on_interrupt(const std::string& path);
void forget_on_interrupt(const std::string& path);
// Runs open, in which a writer opens a temporary by its name (PLplot, a rewrite of the file), and
// so may make the name again: an interrupt's cleanup comes wholly before it or after it, never
// between its removal of the temporary and the end of the process (a plot interrupted 0.3 s in
// left its SVG's temporary so).
void opening_by_name(const std::function<void()>& open);
// A child process that writes a temporary by its name (ffmpeg), started by start (which returns
// its process id, or -1) under the interrupts' lock: from then on an interrupt kills it, and
// waits for it, before it removes the temporaries, so that the child cannot make the name again
// after them. Forget it before waiting for it oneself. Returns start's result.
int start_writing_process(const std::function<int()>& start);
void forget_writing_process(int pid);
// While set, an interrupt only calls stop(signal) on a watcher thread (the sweep stops and writes
// what it has), once; temporaries are then cleaned up by their owners. An empty function:
// interrupts end the process again.
void set_interrupt_handler(std::function<void(int)> stop);

// The writers below refuse states that are not finite: they throw SimulationError (from inside
// simulate() for the observers), so a run that turned NaN is reported as failed, never written.
// This is their check, for callers that keep a Result: SimulationError if an event's state is not
// finite.
void require_finite(const Result& result);

// "lid open at 0.820 s" and its relatives.
// An impact's impulses per contact, e.g. "sandbag 1.0600 N s, rope 0.7269 N s" ("" for none).
std::string impulse_text(const Event& e);
std::string outcome_sentence(const Result& result);
// The timeline printed by `whatnext run`.
std::string timeline_text(const Result& result, const Scenario& scenario, const std::string& source);
// {"outcome": {...}, "events": [...]} with the event names of docs/model.md §6.
std::string events_json(const Result& result, const Scenario& scenario, const std::string& source);

// Keeps every sample and event in memory (for plots, animation and tests).
class Recorder : public Observer {
 public:
  void on_sample(const Snapshot& s) override { samples.push_back(s); }
  void on_event(const Event& e) override { events.push_back(e); }
  std::vector<Snapshot> samples;
  std::vector<Event> events;
};

// How the CSV and .dat writers make their rows. at_once: on the thread that runs the machine.
// parallel: a batch of samples (SampleBatch: up to 2048, or a piece's) is made into rows on that
// thread and on a helper thread of the writer's own, in chunks, and written in order before
// on_samples returns (example 3 at the paper's step: the text of 80,000 rows and the positions
// they need cost ten times the run). The same bytes either way; on one core, or where no thread
// can be started, parallel is at_once.
enum class Writing { at_once, parallel };
class RowText;  // output.cpp

// CSV: a row per output sample and a row (with the event's name) after each event.
class CsvWriter : public Observer {
 public:
  // impulses: how many of the impulse columns (columns.hpp impulse_columns(machine)).
  explicit CsvWriter(std::ostream& out, Writing writing = Writing::at_once, std::size_t impulses = kPaperImpulses);
  ~CsvWriter() override;
  void on_sample(const Snapshot& s) override;
  void on_samples(const SampleBatch& batch) override;
  void on_event(const Event& e) override;
  static std::string header(std::size_t impulses = kPaperImpulses);

 private:
  std::size_t impulses_;
  std::unique_ptr<RowText> rows_;
};

// The paper's whatnext.dat: t, xs, hs, phiS, phiL, hbl, hb, cr, straight in Fortran 9F8.3.
// Positions only: it asks for samples of Detail::positions.
class DatWriter : public Observer {
 public:
  explicit DatWriter(std::ostream& out, Writing writing = Writing::at_once);
  ~DatWriter() override;
  Detail sample_detail() const override { return Detail::positions; }
  void on_sample(const Snapshot& s) override;
  void on_samples(const SampleBatch& batch) override;
  void on_event(const Event& e) override;

 private:
  std::unique_ptr<RowText> rows_;
  bool slack_since_last_row_ = false;
};

// Fortran's Fw.d edit descriptor: right-justified, asterisks when the number does not fit.
std::string fortran_f(double value, int width, int decimals);

// Sends each sample and event to several observers.
class Fanout : public Observer {
 public:
  void add(Observer* o) { targets_.push_back(o); }
  bool empty() const { return targets_.empty(); }
  Detail sample_detail() const override {
    for (const Observer* o : targets_) {
      if (o->sample_detail() == Detail::full) return Detail::full;
    }
    return Detail::positions;
  }
  void on_sample(const Snapshot& s) override {
    for (Observer* o : targets_) o->on_sample(s);
  }
  void on_samples(const SampleBatch& batch) override {
    for (Observer* o : targets_) o->on_samples(batch);
  }
  void on_event(const Event& e) override {
    for (Observer* o : targets_) o->on_event(e);
  }

 private:
  std::vector<Observer*> targets_;
};

}  // namespace whatnext
