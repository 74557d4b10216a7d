#include "whatnext/explore/sweep_job.hpp"

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "whatnext/atomic_file.hpp"

#include "whatnext/config.hpp"

namespace whatnext::explore {

namespace {

// The identity beside the file; false when there is none.
bool read_identity(const std::string& path, std::string& out) {
  std::ifstream in(path, std::ios::binary);
  if (!in.is_open()) return false;
  std::ostringstream all;
  all << in.rdbuf();
  out = all.str();
  return true;
}

// Written whole or not at all, as every output (AtomicFile): renamed over the old one.
void write_identity(const std::string& path, const std::string& identity) {
  AtomicFile file(path, "sweep identity");
  file.stream() << identity;
  file.commit();
}

}  // namespace

SweepJob::SweepJob(const Config& base, const Machines& machines, double accuracy)
    : base_(base), machines_(machines), accuracy_(accuracy) {}

SweepJob::~SweepJob() = default;

void SweepJob::to_file(const std::string& target, const std::string& given, std::string_view option,
                       bool resume, std::string_view resume_option, const ResumeWords& words) {
  file_ = std::make_unique<SweepFile>(target, given, std::string(option));
  identity_path_ = target + ".id";
  part_identity_path_ = target + ".part.id";
  identity_ = sweep_identity(base_, machines_, accuracy_);
  if (!resume) return;
  text_ = file_->previous();
  if (text_.empty()) return;  // nothing to resume
  const std::string what = fmt::format("{} {}", resume_option, printable(file_->source(), 96));
  // Its columns first: a sweep over other keys is told so in those words. A file without a
  // complete row holds nothing to keep: whatever wrote it, the sweep starts from its header.
  const std::size_t eol = text_.find('\n');
  (void)read_resumable(std::string_view(text_).substr(0, eol + 1), machines_, base_, accuracy_, what, words);
  if (eol == std::string::npos || text_.find('\n', eol + 1) == std::string::npos) {
    kept_ = read_resumable(text_, machines_, base_, accuracy_, what, words);
    return;
  }
  // The rows are this sweep's only if the identity beside them says so: every input that changes
  // a row, which the rows themselves do not show (a --set, the accuracy, the program).
  // A .part file's identity is NAME.part.id; a finished file's NAME.id, or NAME.part.id where
  // the end of its sweep was cut off between the two renames (commit()).
  std::string file_identity;
  const bool part_identity = file_->from_part() || read_identity(part_identity_path_, file_identity);
  const std::string& path = part_identity ? part_identity_path_ : identity_path_;
  if (!read_identity(path, file_identity)) {
    throw InputError(
        fmt::format("{}: {}{}.id, which says what sweep wrote it, is missing, so its rows cannot be "
                    "proven this sweep's; {}",
                    what, printable(given, 96), part_identity ? ".part" : "", words.remedy));
  }
  check_identity(identity_, file_identity, what, words);
  kept_ = read_resumable(text_, machines_, base_, accuracy_, what, words);
}

void SweepJob::to_stream(std::ostream& out, std::function<void()> sync) {
  stream_ = &out;
  stream_sync_ = std::move(sync);
}

std::vector<Row> SweepJob::kept_rows() const {
  std::vector<Row> rows;
  const std::size_t n_keys = machines_.plan().ranges.size();
  const auto read = [&](std::string_view line) {
    Row row;
    read_row(line, n_keys, row);  // checked when it was kept
    rows.push_back(std::move(row));
  };
  std::size_t at = text_.find('\n') + 1;
  for (std::int64_t i = 0; i < kept_.prefix_rows; ++i) {
    const std::size_t end = text_.find('\n', at) + 1;
    read(std::string_view(text_).substr(at, end - at));
    at = end;
  }
  for (const auto& [index, line] : kept_.later) read(line);
  return rows;
}

void SweepJob::start() {
  if (!file_) return;
  const bool fresh = !kept_.header;
  // An identity beside the .part file says what the .part file holds: from here on, until the
  // new one is written, it holds nothing of the old one's.
  if (!(file_->from_part() && !fresh)) (void)std::remove(part_identity_path_.c_str());
  // Rows kept from the finished file are copied into the .part file only under their identity: a
  // kill while they are copied leaves rows that are still provably this sweep's.
  if (!fresh) write_identity(part_identity_path_, identity_);
  file_->start(fresh ? std::string_view() : std::string_view(text_).substr(0, kept_.prefix_bytes));
  if (fresh) {
    // The file holds its header before the identity is written: a .part file that is empty is
    // never this sweep's (a resumed sweep then reads the target instead).
    const std::string header = csv_header(machines_.plan());
    file_->stream().write(header.data(), static_cast<std::streamsize>(header.size()));
    file_->sync();
    kept_.header = true;
    write_identity(part_identity_path_, identity_);
  }
  stream_ = &file_->stream();
  stream_sync_ = [this] { file_->sync(); };
}

SweepResult SweepJob::run(const JobSettings& settings) {
  RunOptions ro;
  ro.threads = settings.threads;
  ro.accuracy = accuracy_;
  ro.stop = &stop_;
  ro.keep_rows = settings.keep_rows;
  ro.progress = [this, &settings](std::int64_t done, std::int64_t total) {
    if (settings.interrupted && !stop_.load() && settings.interrupted()) stop_.store(true);
    if (settings.progress) settings.progress(done, total);
  };
  ro.csv = stream_;
  ro.header_written = kept_.header;
  ro.rows_written = kept_.prefix_rows;
  ro.known = kept_.later;
  if (stream_sync_) {
    ro.checkpoint = [this] {
      try {
        stream_sync_();
      } catch (...) {  // thrown here it would end the workers: they stop, it is thrown after
        if (!write_failure_) write_failure_ = std::current_exception();
        stop_.store(true);
      }
    };
  }
  SweepResult result = explore::run(base_, machines_, ro);
  if (write_failure_) std::rethrow_exception(write_failure_);
  return result;
}

void SweepJob::sync() {
  if (file_) file_->sync();
}

void SweepJob::commit() {
  if (!file_) return;
  file_->commit();
  // The identity follows its file: the old NAME.id stays until the new NAME is in place.
  if (std::rename(part_identity_path_.c_str(), identity_path_.c_str()) != 0) {
    throw OutputError(
        fmt::format("{}: writing failed: {}", printable(identity_path_, 96), std::strerror(errno)));
  }
}

}  // namespace whatnext::explore
