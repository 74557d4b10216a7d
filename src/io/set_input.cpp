// Overrides: --set KEY=VALUE (VALUE as in TOML, bare words as text) and set_number for sweeps.
#include <cctype>
#include <string>

#include "input_common.hpp"

namespace whatnext {

using namespace io;

void apply_set(Config& cfg, std::string_view assignment) {
  const std::string origin = fmt::format("--set {}", printable(assignment));
  for (const char c : assignment) {
    if ((static_cast<unsigned char>(c) < 0x20 && c != '\t') || c == 0x7f) {
      throw InputError(fmt::format("{}: KEY=VALUE must be one line without control characters", origin));
    }
  }
  const auto eq = assignment.find('=');
  if (eq == std::string_view::npos) {
    throw InputError(fmt::format("{}: expected KEY=VALUE", origin));
  }
  auto trim = [](std::string_view s) {
    const auto a = s.find_first_not_of(" \t");
    const auto b = s.find_last_not_of(" \t");
    return a == std::string_view::npos ? std::string_view() : s.substr(a, b - a + 1);
  };
  const std::string key(trim(assignment.substr(0, eq)));
  const std::string value(trim(assignment.substr(eq + 1)));
  if (key.empty()) throw InputError(fmt::format("{}: expected KEY=VALUE (no key before '=')", origin));
  const KeySpec* spec = find_key(key);
  if (!spec) unknown_key("--set", key);
  // A number given as its table's default word ("endless", "inextensible", "bar") is the key left
  // out: how a rope that stretches is set back to the inextensible one (the page compares them).
  const bool word_default =
      !spec->default_text.empty() && std::isalpha(static_cast<unsigned char>(spec->default_text[0]));
  if (word_default && spec->kind != KeyKind::text && spec->kind != KeyKind::flag &&
      value == spec->default_text) {
    cfg.values.erase(key);
    return;
  }
  if (value.empty()) throw InputError(fmt::format("{}: give a value after '='", origin));
  toml::table parsed;
  bool ok = true;
  const std::string line = "v = " + value;
  try {
    parsed = toml::parse(line);
    ok = parsed.size() == 1 && parsed.contains("v");
  } catch (const toml::parse_error&) {
    ok = false;
  }
  if (ok) {
    store(cfg, key, *parsed.get("v"), origin, line);
  } else if (spec->kind == KeyKind::text) {
    store(cfg, key, toml::value<std::string>(value), origin);
  } else if (spec->kind == KeyKind::flag) {
    throw InputError(fmt::format("{}: {} must be true or false (given '{}')", origin, key, printable(value)));
  } else if (spec->kind == KeyKind::pair) {
    throw InputError(fmt::format("{}: {} must be a pair of numbers [dx, dh] in {} (given '{}')", origin, key,
                                 spec->unit, printable(value)));
  } else {
    throw InputError(fmt::format("{}: {} must be a number in {} (given '{}')", origin, key,
                                 spec->unit.empty() ? "plain units" : spec->unit, printable(value)));
  }
  // A new hinge form replaces the other one.
  if (key == "geometry.hinge_offset") {
    cfg.values.erase("geometry.hinge_distance");
    cfg.values.erase("geometry.hinge_angle");
  } else if (key == "geometry.hinge_distance" || key == "geometry.hinge_angle") {
    cfg.values.erase("geometry.hinge_offset");
  }
}

void set_number(Config& cfg, const std::string& key, double value) {
  const KeySpec* spec = find_key(key);
  if (!spec) unknown_key("key", key);
  if (spec->kind == KeyKind::text || spec->kind == KeyKind::pair || spec->kind == KeyKind::flag) {
    throw InputError(fmt::format("key {}: is not a single number", key));
  }
  // Without an origin: a sweep sets its keys for every machine, and the origin ("KEY = VALUE") is
  // written only for a message (Reader::where).
  ConfigValue& v = cfg.values[key];
  v = ConfigValue{};
  v.number = value;
  if (key == "geometry.hinge_distance" || key == "geometry.hinge_angle") {
    cfg.values.erase("geometry.hinge_offset");
  }
}

}  // namespace whatnext
