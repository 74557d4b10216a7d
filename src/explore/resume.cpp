#include "whatnext/explore/resume.hpp"

#include <iterator>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "whatnext/explore/evaluate.hpp"
#include "whatnext/explore/rows.hpp"
#include "whatnext/output.hpp"

namespace whatnext::explore {

namespace {
// The start of machine i's row: its index and values, and the comma before its outcome.
std::string row_start(const Machines& machines, std::int64_t i, std::vector<double>& values) {
  machines.point(i, values.data());
  std::string out = fmt::format(FMT_COMPILE("{}"), i);
  for (double v : values) fmt::format_to(std::back_inserter(out), FMT_COMPILE(",{}"), v);
  return out + ",";
}

// The varied keys of a header line, for a message: "a, b" of "index,a,b,outcome,...".
std::string header_keys(std::string_view line) {
  const auto a = line.find(',');
  const auto b = line.find(",outcome,");
  if (line.rfind("index,", 0) != 0 || a == std::string_view::npos || b == std::string_view::npos || b <= a) {
    return fmt::format("'{}'", printable(line, 60));
  }
  std::string keys(line.substr(a + 1, b - a - 1));
  for (std::size_t p = 0; (p = keys.find(',', p)) != std::string::npos; p += 2) keys.replace(p, 1, ", ");
  return printable(keys, 120);
}

// The header line. Another sweep's columns are refused; false when the line is incomplete (the
// sweep was killed before it was written whole), and then nothing is kept.
bool check_header(std::string_view text, const std::string& header, std::string_view what,
                  const ResumeWords& words) {
  const auto eol = text.find('\n');
  if (eol == std::string_view::npos) {
    if (header.compare(0, text.size(), text) != 0 && text.find('\0') == std::string_view::npos) {
      throw InputError(fmt::format("{}: is not a CSV of this sweep (its first line is '{}'); {}", what,
                                   printable(text, 60), words.remedy));
    }
    return false;
  }
  const std::string_view first = text.substr(0, eol + 1);
  if (first != header) {
    throw InputError(
        fmt::format("{}: was written by a sweep over other columns (it varies {}; this sweep varies {}); {}",
                    what, header_keys(first.substr(0, first.size() - 1)),
                    header_keys(std::string_view(header).substr(0, header.size() - 1)), words.remedy));
  }
  return true;
}

// A row's machine index, or -1 for a damaged line (the zeros a power cut can leave, a line cut
// short): it and all after it are run again.
std::int64_t row_index(std::string_view line) {
  if (line.find('\0') != std::string_view::npos) return -1;
  std::int64_t index = 0;
  std::size_t k = 0;
  while (k < line.size() && line[k] >= '0' && line[k] <= '9' && k < 12)
    index = index * 10 + (line[k++] - '0');
  if (k == 0 || k >= line.size() || line[k] != ',') return -1;
  return index;
}

// A row of machine index (after the row of machine previous) must be this sweep's: in order, and
// with this plan's values. Returns what follows the values: the outcome's columns.
std::string_view checked_outcome(std::string_view line, std::int64_t index, std::int64_t previous,
                                 const Machines& machines, std::vector<double>& values, std::string_view what,
                                 const ResumeWords& words) {
  if (index <= previous || index >= machines.size()) {
    throw InputError(
        fmt::format("{}: holds a row for machine {}{}, which this sweep does not have there; the "
                    "file is another sweep's ({}): {}",
                    what, index, index <= previous ? " out of order" : "", words.plan, words.remedy));
  }
  const std::string start = row_start(machines, index, values);
  if (line.compare(0, start.size(), start) != 0) {
    throw InputError(
        fmt::format("{}: its row for machine {} has other values than this sweep's ({}); the file "
                    "is another sweep's ({}): {}",
                    what, index, printable(start.substr(0, start.size() - 1), 80), words.plan, words.remedy));
  }
  return line.substr(start.size());
}

// Running the first and the last kept machine again checks what the rows do not show: the
// machine the values were set on and the accuracy.
void check_by_running_again(const std::pair<std::int64_t, std::string_view> (&rows)[2],
                            const Machines& machines, const Config& base, double accuracy,
                            std::string_view what, const ResumeWords& words) {
  std::vector<double> values(machines.plan().ranges.size());
  const std::vector<std::string> keys = machines.plan().keys();
  for (const auto& [index, line] : rows) {
    machines.point(index, values.data());
    const std::string again = csv_row(index, values, evaluate(base, keys, values.data(), accuracy));
    if (again != line) {
      throw InputError(
          fmt::format("{}: machine {} gives another row now than in the file; the file is another "
                      "sweep's ({}): {}",
                      what, index, words.machine, words.remedy));
    }
  }
}
}  // namespace

Resumable read_resumable(std::string_view text, const Machines& machines, const Config& base, double accuracy,
                         std::string_view what, const ResumeWords& words) {
  Resumable r;
  const std::string header = csv_header(machines.plan());
  if (!check_header(text, header, what, words)) return r;
  r.header = true;
  r.prefix_bytes = header.size();
  std::vector<double> values(machines.plan().ranges.size());
  std::int64_t previous = -1;
  std::pair<std::int64_t, std::string_view> checked[2] = {{-1, {}}, {-1, {}}};  // the first and last row
  for (std::size_t pos = header.size(); pos < text.size();) {
    const auto end = text.find('\n', pos);
    if (end == std::string_view::npos) break;  // a partial last line
    const std::string_view line = text.substr(pos, end + 1 - pos);
    const std::int64_t index = row_index(line);
    if (index < 0) break;
    const std::string_view rest = checked_outcome(line, index, previous, machines, values, what, words);
    if (rest.rfind("invalid,", 0) == 0) ++r.invalid;
    if (rest.rfind("failed,", 0) == 0) ++r.failed;
    if (index == r.prefix_rows && r.later.empty()) {
      ++r.prefix_rows;
      r.prefix_bytes = end + 1;
    } else {
      r.later.emplace_back(index, std::string(line));
    }
    if (checked[0].first < 0) checked[0] = {index, line};
    checked[1] = {index, line};
    previous = index;
    ++r.kept;
    pos = end + 1;
  }
  if (checked[1].first >= 0) check_by_running_again(checked, machines, base, accuracy, what, words);
  return r;
}

}  // namespace whatnext::explore
