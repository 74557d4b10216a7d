#include "whatnext/explore/rows.hpp"

#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <ostream>

#include <fmt/compile.h>
#include <fmt/format.h>

#include "whatnext/explore/sweep.hpp"
#include "whatnext/config.hpp"

namespace whatnext::explore {

namespace {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

std::string csv_quote(std::string_view s) {
  if (s.find_first_of(",\"\n\r") == std::string_view::npos) return std::string(s);
  std::string out = "\"";
  for (char c : s) {
    if (c == '"') out += '"';
    out += (c == '\n' || c == '\r') ? ' ' : c;
  }
  return out + "\"";
}

std::string csv_unquote(std::string_view s) {
  if (s.size() < 2 || s.front() != '"' || s.back() != '"') return std::string(s);
  s = s.substr(1, s.size() - 2);
  std::string text;
  for (std::size_t i = 0; i < s.size(); ++i) {
    text += s[i];
    if (s[i] == '"' && i + 1 < s.size() && s[i + 1] == '"') ++i;
  }
  return text;
}

// A whole cell as a finite number; false for an empty or other cell.
bool finite_cell(std::string_view cell, double& out) {
  if (cell.empty() || cell.size() > 40) return false;
  const std::string text(cell);
  char* end = nullptr;
  out = std::strtod(text.c_str(), &end);
  return end == text.c_str() + text.size() && std::isfinite(out);
}

}  // namespace

std::string csv_header(const Plan& plan) {
  fmt::memory_buffer line;
  auto put = [&line](std::string_view text) { line.append(text.data(), text.data() + text.size()); };
  put("index");
  for (const Range& r : plan.ranges) fmt::format_to(std::back_inserter(line), ",{}", r.key);
  put(",outcome,outcome_t,final_r,final_phi_l_deg");
  for (EventType t : event_types()) fmt::format_to(std::back_inserter(line), ",{}", to_string(t));
  put(",error\n");
  return std::string(line.data(), line.size());
}

std::string csv_row(std::int64_t index, const std::vector<double>& values, const Outcome& o) {
  // Compiled formats: the row is formatted for every machine, and the format strings' parsing
  // took as long as the formatting (callgrind).
  fmt::memory_buffer line;
  auto put = [&line](std::string_view text) { line.append(text.data(), text.data() + text.size()); };
  fmt::format_to(std::back_inserter(line), FMT_COMPILE("{}"), index);
  // "{}" prints the shortest text that reads back to the same double: lossless and deterministic.
  for (double v : values) fmt::format_to(std::back_inserter(line), FMT_COMPILE(",{}"), v);
  if (o.valid) {
    put(",");
    put(to_string(o.outcome));
    fmt::format_to(std::back_inserter(line), FMT_COMPILE(",{},{},{}"), o.outcome_t, o.final_r,
                   o.final_phi_l_deg);
    for (double t : o.first) {
      put(",");
      if (!std::isnan(t)) fmt::format_to(std::back_inserter(line), FMT_COMPILE("{}"), t);
    }
    put(",\n");
  } else {
    put(o.failed ? ",failed,,," : ",invalid,,,");
    for (std::size_t k = 0; k < o.first.size(); ++k) put(",");
    put(",");
    put(csv_quote(o.error));
    put("\n");
  }
  return std::string(line.data(), line.size());
}

std::string read_row(std::string_view line, std::size_t n_keys, Row& row) {
  const auto& types = event_types();
  if (line.empty() || line.back() != '\n') return "it is cut short";
  line.remove_suffix(1);
  if (line.find('\0') != std::string_view::npos) return "it holds zero bytes";
  if (!line.empty() && line.back() == '\r') return "it ends in CRLF, not in a newline as whatnext writes";
  const std::size_t fields = 1 + n_keys + 4 + types.size();  // before the error
  std::vector<std::string_view> cell;
  cell.reserve(fields);
  std::size_t pos = 0;
  for (std::size_t k = 0; k < fields; ++k) {
    const auto comma = line.find(',', pos);
    if (comma == std::string_view::npos) return fmt::format("{} columns where {} belong", k + 1, fields + 1);
    cell.push_back(line.substr(pos, comma - pos));
    pos = comma + 1;
  }
  const std::string_view error = line.substr(pos);
  row = Row{};
  double index = 0.0;
  if (cell[0].empty() || cell[0].find_first_not_of("0123456789") != std::string_view::npos ||
      !finite_cell(cell[0], index))
    return fmt::format("its index '{}' is not a whole number", printable(cell[0], 24));
  row.index = static_cast<std::int64_t>(index);
  row.values.resize(n_keys);
  for (std::size_t k = 0; k < n_keys; ++k) {
    if (!finite_cell(cell[1 + k], row.values[k]))
      return fmt::format("its value '{}' is not a finite number", printable(cell[1 + k], 24));
  }
  Outcome& o = row.outcome;
  o.first.assign(types.size(), kNaN);
  const std::string_view name = cell[1 + n_keys];
  o.failed = name == "failed";
  o.valid = !o.failed && name != "invalid";
  const auto numbers = [&](std::size_t from) { return cell.begin() + static_cast<std::ptrdiff_t>(from); };
  if (o.valid) {
    std::size_t t = 0;
    while (t < types.size() && to_string(types[t]) != name) ++t;
    if (t == types.size())
      return fmt::format("its outcome '{}' is no event's name, nor invalid or failed", printable(name, 24));
    o.outcome = types[t];
    double* const own[] = {&o.outcome_t, &o.final_r, &o.final_phi_l_deg};
    for (std::size_t k = 0; k < 3; ++k) {
      if (!finite_cell(cell[2 + n_keys + k], *own[k]))
        return fmt::format("its {} '{}' is not a finite number",
                           k == 0   ? "outcome_t"
                           : k == 1 ? "final_r"
                                    : "final_phi_l_deg",
                           printable(cell[2 + n_keys + k], 24));
    }
    for (std::size_t e = 0; e < types.size(); ++e) {
      const std::string_view c = cell[5 + n_keys + e];
      if (!c.empty() && !finite_cell(c, o.first[e]))
        return fmt::format("its {} time '{}' is not a finite number", to_string(types[e]), printable(c, 24));
    }
    if (!error.empty()) return "it has more columns than a sweep's row";
  } else {
    for (auto c = numbers(2 + n_keys); c != cell.end(); ++c) {
      if (!c->empty()) return fmt::format("it is {} but has times", name);
    }
    o.error = csv_unquote(error);
    if (o.error.empty()) return fmt::format("it is {} without a reason", name);
  }
  if (csv_row(row.index, row.values, o) != std::string_view(line.data(), line.size() + 1))
    return "it is not written as whatnext writes a row";
  return {};
}

void write_csv(std::ostream& out, const Machines& machines, const SweepResult& result) {
  const std::string header = csv_header(machines.plan());
  out.write(header.data(), static_cast<std::streamsize>(header.size()));
  std::vector<double> values(machines.plan().ranges.size());
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    const auto slot = static_cast<std::size_t>(i);
    if (!result.done[slot]) continue;
    if (slot < result.lines.size() && !result.lines[slot].empty()) {
      out.write(result.lines[slot].data(), static_cast<std::streamsize>(result.lines[slot].size()));
      continue;
    }
    machines.point(i, values.data());
    const std::string row = csv_row(i, values, result.rows[slot]);
    out.write(row.data(), static_cast<std::streamsize>(row.size()));
  }
}

Columns columns_of(const Machines& machines, std::int64_t first, const std::vector<Outcome>& rows) {
  const auto& types = event_types();
  const std::size_t n = rows.size(), keys = machines.plan().ranges.size();
  Columns c;
  c.index.resize(n);
  c.values.assign(keys, std::vector<double>(n));
  c.outcome.resize(n);
  c.outcome_t.resize(n), c.final_r.resize(n), c.final_phi_l_deg.resize(n);
  c.first.assign(types.size(), std::vector<double>(n));
  c.error.resize(n);
  std::vector<double> v(keys);
  for (std::size_t i = 0; i < n; ++i) {
    const Outcome& o = rows[i];
    c.index[i] = first + static_cast<std::int64_t>(i);
    machines.point(c.index[i], v.data());
    for (std::size_t k = 0; k < keys; ++k) c.values[k][i] = v[k];
    c.outcome[i] = o.valid ? to_string(o.outcome) : std::string_view(o.failed ? "failed" : "invalid");
    c.outcome_t[i] = o.valid ? o.outcome_t : kNaN;
    c.final_r[i] = o.valid ? o.final_r : kNaN;
    c.final_phi_l_deg[i] = o.valid ? o.final_phi_l_deg : kNaN;
    for (std::size_t e = 0; e < types.size(); ++e) c.first[e][i] = o.valid ? o.first[e] : kNaN;
    c.error[i] = o.error;
  }
  return c;
}

}  // namespace whatnext::explore
