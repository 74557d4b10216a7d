// TOML inputs: [section] name = value, each value checked against its key's kind; numbers keep the
// text they were written as, for messages.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "input_common.hpp"

namespace whatnext {

using namespace io;

namespace {

// A number as the input wrote it, from the node's place in the text it was parsed from: "1e-400"
// (which reads as 0), "9007199254740993" (which a double rounds). Empty if it cannot be found or
// does not read as the node's value.
std::string literal_of(const toml::node& node, std::string_view source, double value) {
  const toml::source_region& where = node.source();
  if (source.empty() || where.begin.line != where.end.line || where.end.column <= where.begin.column)
    return {};
  std::size_t at = 0;
  for (auto line = where.begin.line; line > 1 && at != std::string_view::npos; --line) {
    at = source.find('\n', at);
    if (at != std::string_view::npos) ++at;
  }
  if (at == std::string_view::npos) return {};
  const std::size_t from = at + where.begin.column - 1, n = where.end.column - where.begin.column;
  if (from + n > source.size()) return {};
  std::string text(source.substr(from, n)), digits;
  for (char c : text) {
    if (c != '_') digits += c;
  }
  char* end = nullptr;
  const double read = std::strtod(digits.c_str(), &end);
  if (digits.empty() || *end != '\0' || !(read == value || (std::isnan(read) && std::isnan(value))))
    return {};
  return printable(text, 40);
}

// TOML integers become doubles too (rounded when they have more than 53 bits). `literal` gets the
// number as written, for messages ("given 9007199254740993", not ...992; "given 1e-400", not 0).
bool number_of(const toml::node& node, double& out, std::string* literal = nullptr,
               std::string_view source = {}) {
  if (const auto* i = node.as_integer()) {
    out = static_cast<double>(i->get());
    if (literal) {
      *literal = literal_of(node, source, out);
      if (literal->empty())
        *literal = std::fabs(out) >= 9007199254740992.0 ? std::to_string(i->get()) : fmt_num(out);
    }
    return true;
  }
  if (literal) literal->clear();
  if (const auto* f = node.as_floating_point()) {
    out = f->get();
    if (literal) *literal = literal_of(node, source, out);
    return true;
  }
  return false;
}

std::string shown_node(const toml::node& node) {
  std::ostringstream given;
  node.visit([&](const auto& n) { given << n; });
  return printable(given.str());
}

}  // namespace

namespace io {

// Stores one TOML node under key, checking its type against the key's kind; `source` is the text the
// node was parsed from (for numbers as written in messages).
void store(Config& cfg, const std::string& key, const toml::node& node, const std::string& origin,
           std::string_view source) {
  const KeySpec* spec = find_key(key);
  if (!spec) unknown_key(origin, key);
  ConfigValue v;
  v.origin = origin;
  if (spec->kind == KeyKind::flag) {
    if (!node.is_boolean()) {
      throw InputError(fmt::format("{}: {} must be true or false (given {})", origin, key, shown_node(node)));
    }
    v.number = node.as_boolean()->get() ? 1.0 : 0.0;
  } else if (spec->kind == KeyKind::text) {
    if (!node.is_string()) {
      throw InputError(fmt::format("{}: {} must be a text value, one of: {} (given {})", origin, key,
                                   spec->help, shown_node(node)));
    }
    v.type = ConfigValue::Type::text;
    v.text = node.as_string()->get();
  } else if (spec->kind == KeyKind::pair) {
    const toml::array* arr = node.as_array();
    std::string lit[2];
    if (!arr || arr->size() != 2 || !number_of((*arr)[0], v.pair[0], &lit[0], source) ||
        !number_of((*arr)[1], v.pair[1], &lit[1], source)) {
      throw InputError(fmt::format("{}: {} must be a pair of numbers [dx, dh] in {} (given {})", origin, key,
                                   spec->unit, shown_node(node)));
    }
    v.type = ConfigValue::Type::pair;
    if ((!lit[0].empty() && lit[0] != fmt_num(v.pair[0])) ||
        (!lit[1].empty() && lit[1] != fmt_num(v.pair[1]))) {
      v.text = fmt::format("[{}, {}]", lit[0].empty() ? fmt_num(v.pair[0]) : lit[0],
                           lit[1].empty() ? fmt_num(v.pair[1]) : lit[1]);
    }
  } else {
    std::string lit;
    if (!number_of(node, v.number, &lit, source)) {
      throw InputError(fmt::format("{}: {} must be a number in {} (given {})", origin, key,
                                   spec->unit.empty() ? "plain units" : spec->unit, shown_node(node)));
    }
    if (!lit.empty() && lit != fmt_num(v.number)) v.text = lit;  // an integer a double rounds
  }
  cfg.values[key] = v;
}
}  // namespace io

namespace {
// An empty table must still be a section of known keys ([foo] alone was accepted).
void check_section(const std::string& origin, const std::string& sect) {
  std::vector<std::string> sections;
  for (const KeySpec& k : known_keys()) {
    const std::string s(k.key.substr(0, k.key.find('.')));
    if (s == sect) return;
    if (std::find(sections.begin(), sections.end(), s) == sections.end()) sections.push_back(s);
  }
  const std::string near = nearest_word(sect, sections);
  throw InputError(fmt::format("{}: unknown section [{}]{}", origin, printable(sect),
                               near.empty() ? "" : fmt::format(" (did you mean [{}]?)", near)));
}

std::string line_origin(const std::string& source, const toml::node& node) {
  return fmt::format("{}:{}", source, node.source().begin.line);
}
}  // namespace

Config parse_toml(std::string_view text, const std::string& source) {
  Config cfg;
  cfg.source = printable(source, 96);
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& err) {
    throw InputError(fmt::format("{}:{}:{}: not valid TOML: {}", cfg.source, err.source().begin.line,
                                 err.source().begin.column, printable(err.description(), 120)));
  }
  for (const auto& [section, node] : root) {
    const std::string sect(section.str());
    const toml::table* table = node.as_table();
    if (!table && find_key(sect)) {
      // "masses.sandbag" = 0.5: quoted, the dot is part of one key's name, not a section's.
      throw InputError(fmt::format(
          "{}: key \"{}\" is quoted, so its dot does not make a section: write {} = ... "
          "without the quotes, or the name after the dot under [{}]",
          line_origin(cfg.source, node), printable(sect), printable(sect), sect.substr(0, sect.find('.'))));
    }
    if (!table) unknown_key(line_origin(cfg.source, node), sect);
    if (table->empty()) check_section(line_origin(cfg.source, node), sect);
    for (const auto& [name, value] : *table) {
      store(cfg, sect + "." + std::string(name.str()), value, line_origin(cfg.source, value), text);
    }
  }
  return cfg;
}

}  // namespace whatnext
