// The paper's whatnext.inp: fifteen Fortran reals, one per line.
#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <string>

#include "input_common.hpp"

namespace whatnext {

using namespace io;

namespace {

// A Fortran real as the paper's .inp writes it: [+-] digits [. digits] [(e|E|d|D) [+-] digits],
// or with no digits before the point. Returns the end of the number, or `from` when there is none.
std::size_t scan_real(const std::string& s, std::size_t from) {
  std::size_t i = from;
  auto digits = [&] {
    const std::size_t start = i;
    while (i < s.size() && std::isdigit(static_cast<unsigned char>(s[i]))) ++i;
    return i - start;
  };
  if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
  std::size_t mantissa = digits();
  if (i < s.size() && s[i] == '.') {
    ++i;
    mantissa += digits();
  }
  if (mantissa == 0) return from;
  if (i < s.size() && s[i] != '\0' && std::strchr("eEdD", s[i]) != nullptr) {  // strchr finds a NUL too
    const std::size_t mark = i++;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) i = mark;  // "1e" : the e starts the comment
  }
  return i;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

}  // namespace

Config parse_inp(std::string_view text, const std::string& source) {
  // The paper's whatnext.inp: one number per line in this order, anything after it (past a blank,
  // ';' or '!') a comment; blank lines are skipped, as Fortran's read does. Nothing may follow.
  static const char* const kFields[15][2] = {
      {"start.sandbag_height", "hs"},
      {"start.sandbag_x", "xs"},
      {"start.seesaw_angle", "phiS"},
      {"start.lid_angle", "phiL"},
      {"geometry.hinge_distance", "f"},
      {"geometry.rope_length", "lR"},
      {"geometry.hinge_angle", "gamma"},
      {"geometry.lid_half_length", "rL"},
      {"geometry.seesaw_right_arm", "rH"},
      {"masses.sandbag", "ms"},
      {"masses.lid", "mL"},
      {"air.density", "rhoair"},
      {"air.helium_density", "rhohe"},
      {"run.t_max", "tmax"},
      {"run.step", "dt"},
  };
  Config cfg;
  cfg.source = printable(source, 96);
  // A UTF-8 byte order mark, which some editors write first, is not part of the first number.
  if (text.substr(0, 3) == "\xEF\xBB\xBF") text.remove_prefix(3);
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0, field = 0;
  while (field < 15 && std::getline(in, line)) {
    ++line_no;
    if (blank(line)) continue;
    const std::size_t first = line.find_first_not_of(" \t\r");
    const std::string origin = fmt::format("{} line {}", cfg.source, line_no);
    const std::size_t end = scan_real(line, first);
    // strchr finds a NUL too, as the string's end: "0.5<NUL>9" is refused, not read as 0.5.
    const bool separated =
        end < line.size() ? line[end] != '\0' && std::strchr(" \t\r;!", line[end]) != nullptr : true;
    if (end == first || !separated) {
      throw InputError(
          fmt::format("{}: expected a number for {} ({}), got '{}'{}", origin, kFields[field][1],
                      kFields[field][0], printable(line.substr(first)),
                      end > first && line[end] == ',' ? " (a decimal comma? write a point)" : ""));
    }
    std::string token = line.substr(first, end - first);
    std::replace(token.begin(), token.end(), 'd', 'e');  // Fortran's 1.0d0
    std::replace(token.begin(), token.end(), 'D', 'e');
    ConfigValue cv;
    cv.number = std::strtod(token.c_str(), nullptr);  // out of range gives inf or 0: validation says so
    const std::string written = line.substr(first, end - first);
    if (written != fmt_num(cv.number)) cv.text = printable(written, 40);  // messages quote "1e999", not inf
    cv.origin = fmt::format("{} ({})", origin, kFields[field][1]);
    cfg.values[kFields[field][0]] = cv;
    ++field;
  }
  if (field < 15) {
    throw InputError(fmt::format("{}: a whatnext.inp needs 15 numbers, one per line; found {} (next: {})",
                                 cfg.source, field, kFields[field][1]));
  }
  while (std::getline(in, line)) {
    ++line_no;
    if (!blank(line)) {
      throw InputError(
          fmt::format("{} line {}: a whatnext.inp holds exactly 15 numbers; this line is one too "
                      "many ('{}')",
                      cfg.source, line_no, printable(line)));
    }
  }
  // The paper writes a .dat row every time step.
  ConfigValue out = cfg.values["run.step"];
  cfg.values["run.output_step"] = out;
  return cfg;
}

}  // namespace whatnext
