#include "whatnext/explore/sweep_job.hpp"

#include <fmt/format.h>

#include "whatnext/output.hpp"

namespace whatnext::explore {

SweepJob::SweepJob(const Config& base, const Machines& machines, double accuracy)
    : base_(base), machines_(machines), accuracy_(accuracy) {}

SweepJob::~SweepJob() = default;

void SweepJob::to_file(const std::string& target, const std::string& given, std::string_view option, bool resume,
                       std::string_view resume_option, const ResumeWords& words) {
  file_ = std::make_unique<SweepFile>(target, given, std::string(option));
  if (!resume) return;
  text_ = file_->previous();
  kept_ = read_resumable(text_, machines_, base_, accuracy_,
                         fmt::format("{} {}", resume_option, printable(file_->source(), 96)), words);
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
  file_->start(std::string_view(text_).substr(0, kept_.prefix_bytes));
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
  if (file_) file_->commit();
}

}  // namespace whatnext::explore
