#include "whatnext/explore/spec.hpp"

#include <cmath>
#include <cstdlib>
#include <vector>

#include <fmt/format.h>

#include "whatnext/config.hpp"

namespace whatnext::explore {

namespace {

std::string_view trim(std::string_view s) {
  const auto a = s.find_first_not_of(" \t");
  const auto b = s.find_last_not_of(" \t");
  return a == std::string_view::npos ? std::string_view() : s.substr(a, b - a + 1);
}

// Whole-string number parse; strtod because it accepts every spelling users write (1e-3, .5).
bool parse_double(std::string_view text, double& out) {
  const std::string s(trim(text));
  if (s.empty()) return false;
  char* end = nullptr;
  out = std::strtod(s.c_str(), &end);
  return end == s.c_str() + s.size() && std::isfinite(out);
}

std::string num(double v) { return fmt::format("{}", v); }

}  // namespace

void check_numeric_key(const std::string& key, std::string_view where) {
  if (!find_key(key)) {
    const std::string near = nearest_key(key);
    throw InputError(
        near.empty() ? fmt::format("{}: unknown key '{}'", where, printable(key))
                     : fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, printable(key), near));
  }
  try {  // set_number knows which kinds of key hold one number (text, pairs and flags do not)
    Config probe;
    set_number(probe, key, 0.0);
  } catch (const InputError&) {
    throw InputError(fmt::format("{}: {} is not a single number and cannot be varied", where, key));
  }
}

Spread parse_spread(std::string_view spec, std::string_view option) {
  const std::string where = fmt::format("{} {}", option, printable(spec));
  const auto eq = spec.find('=');
  if (eq == std::string_view::npos)
    throw InputError(fmt::format("{}: expected KEY=±X (given no '=')", where));
  Spread s;
  s.key = std::string(trim(spec.substr(0, eq)));
  check_numeric_key(s.key, where);
  std::string_view rest = trim(spec.substr(eq + 1));
  constexpr std::string_view kPlusMinus = "\u00b1";
  if (rest.substr(0, kPlusMinus.size()) == kPlusMinus) {
    rest.remove_prefix(kPlusMinus.size());
  } else if (rest.substr(0, 2) == "+-") {
    rest.remove_prefix(2);
  } else {
    throw InputError(fmt::format("{}: expected KEY=±X (or KEY=+-X): ± before the spread X (given '{}')",
                                 where, printable(rest)));
  }
  if (!parse_double(rest, s.x)) {
    throw InputError(fmt::format("{}: X must be a finite number (given '{}')", where, printable(trim(rest))));
  }
  if (!(s.x > 0.0)) throw InputError(fmt::format("{}: X must be > 0 (given {})", where, num(s.x)));
  return s;
}

SpreadKind parse_spread_kind(std::string_view kind, std::string_view option) {
  if (kind == "normal") return SpreadKind::normal;
  if (kind == "uniform") return SpreadKind::uniform;
  throw InputError(fmt::format("{}: normal or uniform (given '{}')", option, printable(kind)));
}

double base_value(const Config& config, const std::string& key, std::string_view option) {
  const auto it = config.values.find(key);
  if (it != config.values.end() && it->second.type == ConfigValue::Type::number) return it->second.number;
  const KeySpec* spec = find_key(key);
  const double v = key_default(key);
  if (it == config.values.end() && !std::isnan(v)) return v;
  throw InputError(
      fmt::format("{} {}: the machine does not give {} as a number (its default is '{}'); give it "
                  "with --set {}=VALUE",
                  option, key, key, spec ? spec->default_text : "?", key));
}

Range parse_range(std::string_view spec, std::string_view option, bool need_count) {
  const std::string where = fmt::format("{} {}", option, printable(spec));
  const std::string_view form = need_count ? "KEY=A:B:N" : "KEY=A:B";
  const auto eq = spec.find('=');
  if (eq == std::string_view::npos) {
    throw InputError(fmt::format("{}: expected {} (given no '=')", where, form));
  }
  Range r;
  r.key = std::string(trim(spec.substr(0, eq)));
  check_numeric_key(r.key, where);
  std::vector<std::string_view> parts;
  std::string_view rest = spec.substr(eq + 1);
  for (;;) {
    const auto colon = rest.find(':');
    parts.push_back(rest.substr(0, colon));
    if (colon == std::string_view::npos) break;
    rest = rest.substr(colon + 1);
  }
  const bool count_given = parts.size() == 3;
  if (parts.size() != 2 && !count_given) {
    throw InputError(fmt::format("{}: expected {} ({} fields after '=')", where, form, parts.size()));
  }
  if (need_count && !count_given) {
    throw InputError(fmt::format("{}: expected {}: a grid needs the number of values N", where, form));
  }
  if (!parse_double(parts[0], r.lo)) {
    throw InputError(
        fmt::format("{}: A must be a finite number (given '{}')", where, printable(trim(parts[0]))));
  }
  if (!parse_double(parts[1], r.hi)) {
    throw InputError(
        fmt::format("{}: B must be a finite number (given '{}')", where, printable(trim(parts[1]))));
  }
  if (r.lo > r.hi) {
    throw InputError(fmt::format("{}: needs A <= B (given A = {}, B = {})", where, num(r.lo), num(r.hi)));
  }
  if (count_given) {
    double n = 0.0;
    if (!parse_double(parts[2], n) || n != std::floor(n) || n < 1.0 || n > 1e9) {
      throw InputError(fmt::format("{}: N must be a whole number from 1 to 10^9 (given '{}')", where,
                                   printable(trim(parts[2]))));
    }
    r.n = static_cast<int>(n);
  }
  return r;
}

}  // namespace whatnext::explore
