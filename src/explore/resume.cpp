#include "whatnext/explore/resume.hpp"

#include <cstring>
#include <iterator>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "whatnext/explore/evaluate.hpp"
#include "whatnext/explore/rows.hpp"
#include "whatnext/config.hpp"

#ifndef WHATNEXT_VERSION
#define WHATNEXT_VERSION "unknown"
#endif

namespace whatnext::explore {

const char* const kProgramVersion = WHATNEXT_VERSION;

namespace {
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
  if (eol > 0 && text[eol - 1] == '\r' &&
      header.compare(0, header.size() - 1, first.substr(0, eol - 1)) == 0) {
    throw InputError(
        fmt::format("{}: its lines end in CR LF (as an editor or a copy from Windows may leave them), "
                    "not in the LF whatnext writes; convert them back (dos2unix) or {}",
                    what, words.remedy));
  }
  if (first != header) {
    throw InputError(
        fmt::format("{}: was written by a sweep over other columns (it varies {}; this sweep varies {}); {}",
                    what, header_keys(first.substr(0, first.size() - 1)),
                    header_keys(std::string_view(header).substr(0, header.size() - 1)), words.remedy));
  }
  return true;
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
  const std::size_t n_keys = machines.plan().ranges.size();
  std::vector<double> values(n_keys);
  std::int64_t previous = -1;
  std::pair<std::int64_t, std::string_view> checked[2] = {{-1, {}}, {-1, {}}};  // the first and last row
  Row row;
  for (std::size_t pos = header.size(); pos < text.size();) {
    const auto end = text.find('\n', pos);
    if (end == std::string_view::npos) break;  // a partial last line
    const std::string_view line = text.substr(pos, end + 1 - pos);
    // The file is this sweep's (its identity says so): a row that is not complete, or not of this
    // plan's machine in its place, is damage. It and every row after it run again.
    if (!read_row(line, n_keys, row).empty() || row.index <= previous || row.index >= machines.size()) break;
    machines.point(row.index, values.data());
    if (row.values != values) break;
    if (!row.outcome.valid) ++(row.outcome.failed ? r.failed : r.invalid);
    if (row.index == r.prefix_rows && r.later.empty()) {
      ++r.prefix_rows;
      r.prefix_bytes = end + 1;
    } else {
      r.later.emplace_back(row.index, std::string(line));
    }
    if (checked[0].first < 0) checked[0] = {row.index, line};
    checked[1] = {row.index, line};
    previous = row.index;
    ++r.kept;
    pos = end + 1;
  }
  if (checked[1].first >= 0) check_by_running_again(checked, machines, base, accuracy, what, words);
  return r;
}

namespace {

// A value as the identity writes it: numbers in the shortest form that reads back the same.
std::string value_text(const ConfigValue& v) {
  switch (v.type) {
    case ConfigValue::Type::text: return fmt::format("'{}'", printable(v.text, 200));
    case ConfigValue::Type::pair: return fmt::format("[{}, {}]", shortest(v.pair[0]), shortest(v.pair[1]));
    case ConfigValue::Type::number: break;
  }
  return shortest(v.number);
}

// FNV-1a over the values' bits: a digest of values too many to write out.
struct Digest {
  std::uint64_t h = 1469598103934665603ull;
  void add(double v) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &v, sizeof bits);
    for (int b = 0; b < 8; ++b) h = (h ^ ((bits >> (8 * b)) & 0xff)) * 1099511628211ull;
  }
};

// "name = value" lines, by name.
std::vector<std::pair<std::string_view, std::string_view>> identity_lines(std::string_view text) {
  std::vector<std::pair<std::string_view, std::string_view>> out;
  while (!text.empty()) {
    const auto eol = text.find('\n');
    const std::string_view line = text.substr(0, eol);
    text = eol == std::string_view::npos ? std::string_view() : text.substr(eol + 1);
    const auto eq = line.find(" = ");
    if (eq == std::string_view::npos) {
      out.emplace_back(line, std::string_view());
    } else {
      out.emplace_back(line.substr(0, eq), line.substr(eq + 3));
    }
  }
  return out;
}

}  // namespace

std::string sweep_identity(const Config& base, const Machines& machines, double accuracy) {
  std::string out = fmt::format("whatnext sweep identity 1\nprogram = whatnext {}\n", kProgramVersion);
  out +=
      fmt::format("accuracy = {}\n", accuracy > 0.0 ? shortest(accuracy) : "the machine's own run settings");
  for (const auto& [key, value] : base.values)
    out += fmt::format("machine {} = {}\n", key, value_text(value));
  const Plan& plan = machines.plan();
  if (machines.is_grid()) {
    for (std::size_t d = 0; d < plan.ranges.size(); ++d) {
      const std::vector<double> axis = machines.axis(d);
      Digest digest;
      for (double v : axis) digest.add(v);
      out += fmt::format("values of {} = {} from {} to {} (digest {:016x})\n", plan.ranges[d].key,
                         axis.size(), shortest(axis.front()), shortest(axis.back()), digest.h);
    }
    return out;
  }
  Digest digest;
  std::vector<double> values(plan.ranges.size());
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    machines.point(machines.first() + i, values.data());
    for (double v : values) digest.add(v);
  }
  std::string keys;
  for (const Range& r : plan.ranges) keys += (keys.empty() ? "" : ", ") + r.key;
  out += fmt::format("machines = {} drawn over {} (digest {:016x})\n", machines.size(), keys, digest.h);
  return out;
}

void check_identity(std::string_view now, std::string_view file, std::string_view what,
                    const ResumeWords& words) {
  if (now == file) return;
  const auto here = identity_lines(now), there = identity_lines(file);
  const auto find = [](const auto& lines, std::string_view name) -> const std::string_view* {
    for (const auto& [n, v] : lines) {
      if (n == name) return &v;
    }
    return nullptr;
  };
  std::string_view name, a = "not given", b = "not given";
  for (const auto& [n, v] : here) {
    const std::string_view* w = find(there, n);
    if (!w || *w != v) {
      name = n, a = v, b = w ? *w : "not given";
      break;
    }
  }
  if (name.empty()) {
    for (const auto& [n, v] : there) {
      if (!find(here, n)) {
        name = n, b = v;
        break;
      }
    }
  }
  const bool plan = name.rfind("values of ", 0) == 0 || name.rfind("machines", 0) == 0;
  if (name.rfind("machine ", 0) == 0) name.remove_prefix(8);
  throw InputError(
      fmt::format("{}: was written by another sweep ({}: {} here, {} in the file); the file is another "
                  "sweep's ({}): {}",
                  what, printable(name, 80), printable(a, 80), printable(b, 80),
                  plan ? words.plan : words.machine, words.remedy));
}

}  // namespace whatnext::explore
