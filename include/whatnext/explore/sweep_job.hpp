// A sweep as one job: its machines, the file its CSV goes to (resumably), what an interrupted
// sweep left there, the interrupts that stop it, the syncs that keep its rows, and the commit that
// gives the file its name. The command's `sweep` and Python's whatnext.sweep(csv=...) are this job
// with their own words.
#pragma once

#include <atomic>
#include <cstdint>
#include <exception>
#include <functional>
#include <iosfwd>
#include <memory>
#include <string>
#include <string_view>
#include <vector>

#include "whatnext/explore/resume.hpp"
#include "whatnext/explore/rows.hpp"
#include "whatnext/explore/sweep.hpp"
#include "whatnext/explore/sweep_file.hpp"

namespace whatnext::explore {

struct JobSettings {
  int threads = 1;
  bool keep_rows = true;  // SweepResult::rows (a heat map's, a summary's, Python's columns)
  // On the calling thread about ten times a second with (done, total).
  std::function<void(std::int64_t, std::int64_t)> progress;
  // On the calling thread about ten times a second: true stops the sweep (Python's Ctrl-C).
  std::function<bool()> interrupted;
};

class SweepJob {
 public:
  // The machines of `machines` built on base, each run to `accuracy` (0: the machine's own run
  // settings). Both must outlive the job.
  SweepJob(const Config& base, const Machines& machines, double accuracy);
  ~SweepJob();
  SweepJob(const SweepJob&) = delete;
  SweepJob& operator=(const SweepJob&) = delete;

  // The CSV goes to the regular file `target` (regular_output_target's; given: the name as the
  // user wrote it, option: the argument that gave it) through a SweepFile. With resume, what an
  // interrupted sweep left there is read now and checked to be this sweep's: its identity
  // (TARGET.id) the same as this sweep's, then every row (read_resumable); InputError in words'
  // terms otherwise (`resume_option` names the argument, "--resume"). Nothing is written before
  // start().
  void to_file(const std::string& target, const std::string& given, std::string_view option, bool resume,
               std::string_view resume_option, const ResumeWords& words = {});
  // Or to a stream the caller owns and commits (standard output, a pipe, an AtomicFile), made
  // durable by `sync` about once a second.
  void to_stream(std::ostream& out, std::function<void()> sync);

  // What was kept of an interrupted sweep (nothing unless resumed).
  const Resumable& kept() const { return kept_; }
  // The kept rows read back, in index order.
  std::vector<Row> kept_rows() const;

  // After every other check: only now is the file cut or made (a refused sweep touches nothing),
  // with its header, and the sweep's identity written beside it (TARGET.part.id).
  void start();
  // Runs the machines not kept; the rows go to the file or stream in index order as they are done.
  // A failed write stops the workers and is thrown once they ended.
  SweepResult run(const JobSettings& settings);
  // From any thread (an interrupt's watcher): the workers stop after the machines they run.
  void stop() { stop_.store(true); }
  // Makes every row written durable (the file's sync); OutputError when a write failed.
  void sync();
  // sync(), then the file appears under its name and its identity as TARGET.id (a file job only).
  void commit();

 private:
  const Config& base_;
  const Machines& machines_;
  double accuracy_;
  std::unique_ptr<SweepFile> file_;
  std::ostream* stream_ = nullptr;
  std::function<void()> stream_sync_;
  // TARGET.id, TARGET.part.id (the .part file's, renamed to TARGET.id by commit()) and this
  // sweep's identity (resume.hpp).
  std::string identity_path_, part_identity_path_, identity_;
  std::string text_;  // what an interrupted sweep left, while kept rows are read from it
  Resumable kept_;
  std::atomic<bool> stop_{false};
  std::exception_ptr write_failure_;
};

}  // namespace whatnext::explore
