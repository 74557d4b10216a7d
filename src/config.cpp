#include "whatnext/config.hpp"

#include <fcntl.h>
#include <poll.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cmath>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#define TOML_EXCEPTIONS 1
#include <toml++/toml.h>

#include "whatnext/geometry.hpp"

namespace whatnext {

namespace {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDeg = kPi / 180.0;
constexpr double kMaxSteps = 1e8;    // fixed-step runs longer than this are refused
constexpr double kMaxSamples = 1e7;  // output rows

const std::vector<KeySpec> kKeys = {
    {"geometry.seesaw_right_arm", KeyKind::length, "m", "r_H: pivot to the rope's end of the seesaw", "0.6"},
    {"geometry.lid_half_length", KeyKind::length, "m", "r_L: half the lid (and box) edge", "0.2"},
    {"geometry.rope_length", KeyKind::length, "m", "l_R: rope between seesaw end and lid edge", "1.0"},
    {"geometry.hinge_distance", KeyKind::length, "m", "f: pivot to lid hinge", "0.8"},
    {"geometry.hinge_angle", KeyKind::angle, "deg", "gamma: hinge below the pivot's horizontal", "27"},
    {"geometry.hinge_offset", KeyKind::pair, "m",
     "[dx, dh]: hinge dx right of and dh below the pivot (instead of distance + angle)", "none"},
    {"masses.sandbag", KeyKind::mass, "kg", "m_S: the sandbag (a point mass)", "0.6"},
    {"masses.lid", KeyKind::mass, "kg", "m_L: the lid (a uniform plate)", "0.5"},
    {"air.density", KeyKind::density, "kg/m^3", "density of air", "1.29"},
    {"air.helium_density", KeyKind::density, "kg/m^3", "density of the balloon's helium", "0.18"},
    {"balloon.radius", KeyKind::length, "m", "r_B", "r_L"},
    {"balloon.model", KeyKind::text, "",
     "program (a = g (rho_air - rho_He) / rho_air), lagrangian (/ rho_He) or added-mass "
     "(/ (rho_He + rho_air / 2))", "program"},
    {"balloon.rubber_mass", KeyKind::mass, "kg", "the balloon's rubber: weight and inertia", "0"},
    {"balloon.drag", KeyKind::flag, "", "true: quadratic air drag 1/2 rho_air Cd pi r_B^2 v|v|", "false"},
    {"balloon.drag_coefficient", KeyKind::positive, "", "Cd of the air drag (a sphere); giving it turns drag on",
     "0.47"},
    {"radio.enabled", KeyKind::flag, "",
     "true: after lid_open run on until the balloon's string switches the radio on (any other radio key "
     "turns it on too)", "false"},
    {"radio.switch_offset", KeyKind::pair, "m",
     "[dx, dh]: the radio's switch dx right of and dh above the box's top-right corner", "[0.5, 0]"},
    {"radio.string_length", KeyKind::length, "m", "the balloon's string, centre to switch", "1.0"},
    {"damping.pivot", KeyKind::positive, "N m s/rad", "viscous torque -c phiS' at the seesaw's pivot", "0"},
    {"damping.lid_hinge", KeyKind::positive, "N m s/rad", "viscous torque -c phiL' at the lid's hinge", "0"},
    {"seesaw.left_arm", KeyKind::length, "m", "pivot to the left arm's end", "endless"},
    {"seesaw.mass", KeyKind::mass, "kg",
     "a seesaw with mass: a uniform bar from -left_arm to r_H unless inertia/com_offset are given", "0"},
    {"seesaw.inertia", KeyKind::positive, "kg m^2", "the seesaw's moment of inertia about the pivot", "bar"},
    {"seesaw.com_offset", KeyKind::length, "m",
     "the seesaw's centre of mass along the bar from the pivot, + towards the rope's end", "bar"},
    {"start.sandbag_x", KeyKind::length, "m", "sandbag's start, horizontal from the pivot (< 0)", "-0.3"},
    {"start.sandbag_height", KeyKind::length, "m", "sandbag's start height above the pivot", "1.0"},
    {"start.seesaw_angle", KeyKind::angle, "deg", "phiS0, positive = left arm down", "-25"},
    {"start.lid_angle", KeyKind::angle, "deg", "phiL0, the lid's resting (lowest) angle", "5"},
    {"run.t_max", KeyKind::time, "s", "end of the simulated time", "5"},
    {"run.output_step", KeyKind::time, "s", "spacing of CSV/.dat rows", "0.001"},
    {"run.integrator", KeyKind::text, "", "adaptive, euler or rk4", "adaptive"},
    {"run.step", KeyKind::time, "s", "time step of euler and rk4", "0.001"},
    {"run.tolerance", KeyKind::positive, "", "adaptive: error tolerance per step (abs. and rel.), 1e-15 to 1e-3",
     "1e-12"},
    {"run.impact_law", KeyKind::text, "", "rope, angular-momentum-sum, kinetic-energy or linear-momentum", "rope"},
    {"run.vertical_margin", KeyKind::angle, "deg", "stop this far before 90 deg", "0.9"},
    {"run.gravity", KeyKind::acceleration, "m/s^2", "g", "9.81"},
};

// Where the model is made for (docs/inputs.md "Limits"): a tabletop machine. Far outside, lengths
// fall below the contact tolerance (1e-9 m) or the rounding of the others, energies overflow, and
// the integrator cannot meet its tolerance in any number of steps.
constexpr double kMinLength = 1e-3, kMaxLength = 1e3;      // [m]
constexpr double kMinMass = 1e-3, kMaxMass = 1e3;          // [kg]
constexpr double kMinDensity = 1e-3, kMaxDensity = 1e3;    // [kg/m^3]
constexpr double kMinGravity = 1e-2, kMaxGravity = 1e3;    // [m/s^2]
constexpr double kMaxTime = 1e4;                           // run.t_max [s]
constexpr double kMinTolerance = 1e-15, kMaxTolerance = 1e-3;
constexpr double kMaxBalloonG = 1e3;                       // free balloon's acceleration [g]
constexpr double kMaxDrag = 10.0;                          // drag coefficient
constexpr double kMaxDamping = 1e3;                        // [N m s/rad]
constexpr double kMaxInertia = 1e4;                        // seesaw [kg m^2]

std::string fmt_num(double v) { return fmt::format("{}", v); }

// How long a pipe (a FIFO, or `<(command)`) may keep whatnext waiting for its first byte: a FIFO
// that nobody writes into would otherwise block it for ever.
constexpr int kPipeWaitMs = 5000;

// Reads at most kMaxInputBytes from a regular file or a pipe: a directory, a device (/dev/null,
// /dev/zero, a terminal) or a huge file is refused at once, an idle pipe after kPipeWaitMs.
std::string read_file(const std::string& path) {
  const std::string shown = printable(path, 96);
  // Non-blocking, so that opening a FIFO without a writer returns at once.
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC | O_NONBLOCK);
  if (fd < 0) {
    throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
  }
  struct Closer {
    int fd;
    ~Closer() { ::close(fd); }
  } closer{fd};
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
  }
  if (S_ISDIR(st.st_mode)) throw InputError(fmt::format("{}: is a directory, not an input file", shown));
  if (!S_ISREG(st.st_mode) && !S_ISFIFO(st.st_mode)) {
    throw InputError(fmt::format("{}: is a device, not an input file (give a machine's TOML or .inp file)", shown));
  }
  if (S_ISFIFO(st.st_mode)) {
    pollfd p{fd, POLLIN, 0};
    int ready = 0;
    do {
      ready = ::poll(&p, 1, kPipeWaitMs);
    } while (ready < 0 && errno == EINTR);
    if (ready == 0) {
      throw InputError(fmt::format("{}: a pipe that nothing was written into within {} s; nothing to read",
                                   shown, kPipeWaitMs / 1000));
    }
  }
  ::fcntl(fd, F_SETFL, ::fcntl(fd, F_GETFL) & ~O_NONBLOCK);
  const auto too_big = [&] {
    return InputError(fmt::format("{}: an input file has at most {} bytes; this one has more", shown,
                                  kMaxInputBytes));
  };
  if (S_ISREG(st.st_mode) && static_cast<std::uintmax_t>(st.st_size) > kMaxInputBytes) throw too_big();
  std::string text;
  char buf[65536];
  for (;;) {
    const ssize_t n = ::read(fd, buf, sizeof buf);
    if (n < 0 && errno == EINTR) continue;
    if (n < 0) throw InputError(fmt::format("{}: cannot read the input file: {}", shown, std::strerror(errno)));
    if (n == 0) break;
    text.append(buf, static_cast<std::size_t>(n));
    if (text.size() > kMaxInputBytes) throw too_big();
  }
  return text;
}

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

[[noreturn]] void unknown_key(const std::string& where, std::string_view key) {
  const std::string near = nearest_key(key);
  if (near.empty()) throw InputError(fmt::format("{}: unknown key '{}'", where, printable(key)));
  throw InputError(fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, printable(key), near));
}

// A number as the input wrote it, from the node's place in the text it was parsed from: "1e-400"
// (which reads as 0), "9007199254740993" (which a double rounds). Empty if it cannot be found or
// does not read as the node's value.
std::string literal_of(const toml::node& node, std::string_view source, double value) {
  const toml::source_region& where = node.source();
  if (source.empty() || where.begin.line != where.end.line || where.end.column <= where.begin.column) return {};
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
  if (digits.empty() || *end != '\0' || !(read == value || (std::isnan(read) && std::isnan(value)))) return {};
  return printable(text, 40);
}

// TOML integers become doubles too (rounded when they have more than 53 bits). `literal` gets the
// number as written, for messages ("given 9007199254740993", not ...992; "given 1e-400", not 0).
bool number_of(const toml::node& node, double& out, std::string* literal = nullptr, std::string_view source = {}) {
  if (const auto* i = node.as_integer()) {
    out = static_cast<double>(i->get());
    if (literal) {
      *literal = literal_of(node, source, out);
      if (literal->empty()) *literal = std::fabs(out) >= 9007199254740992.0 ? std::to_string(i->get()) : fmt_num(out);
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

// Stores one TOML node under key, checking its type against the key's kind; `source` is the text the
// node was parsed from (for numbers as written in messages).
void store(Config& cfg, const std::string& key, const toml::node& node, const std::string& origin,
           std::string_view source = {}) {
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
      throw InputError(fmt::format("{}: {} must be a text value, one of: {} (given {})", origin, key, spec->help,
                                   shown_node(node)));
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
    if ((!lit[0].empty() && lit[0] != fmt_num(v.pair[0])) || (!lit[1].empty() && lit[1] != fmt_num(v.pair[1]))) {
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

std::string line_origin(const std::string& source, const toml::node& node) {
  return fmt::format("{}:{}", source, node.source().begin.line);
}

// --- validation helpers ---------------------------------------------------------------------

struct Reader {
  const Config& cfg;

  // Keys are literals: looked up as string_views (Config's map compares transparently), and the
  // unit looked up only for a message, since a sweep builds a machine for every row.
  const ConfigValue* find(std::string_view key) const {
    auto it = cfg.values.find(key);
    return it == cfg.values.end() ? nullptr : &it->second;
  }
  std::string where(std::string_view key) const {
    const ConfigValue* v = find(key);
    return v ? v->origin : cfg.source;
  }
  [[noreturn]] void fail(std::string_view key, const std::string& rule) const {
    throw InputError(fmt::format("{}: {} {}", where(key), key, rule));
  }
  // The value as the input gave it: an integer too long for a double as written.
  std::string shown(std::string_view key, double x) const {
    const ConfigValue* v = find(key);
    if (v && v->type == ConfigValue::Type::number && !v->text.empty() && v->number == x) return v->text;
    return fmt_num(x);
  }
  std::string unit(std::string_view key) const {
    const KeySpec* spec = find_key(key);
    return spec ? std::string(spec->unit) : std::string();
  }
  double number(std::string_view key, double fallback) const {
    const ConfigValue* v = find(key);
    if (!v) return fallback;
    if (!std::isfinite(v->number)) fail(key, fmt::format("must be a finite number (given {})", shown(key, v->number)));
    return v->number;
  }
  double positive(std::string_view key, double fallback) const {
    const double x = number(key, fallback);
    if (!(x > 0.0)) {
      const std::string u = unit(key);
      fail(key, fmt::format("must be > 0{} (given {})", u.empty() ? "" : " " + u, shown(key, x)));
    }
    return x;
  }
  double in_range(std::string_view key, double fallback, double lo, bool lo_closed, double hi,
                  bool hi_closed) const {
    const double x = number(key, fallback);
    const bool ok = (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    if (!ok) {
      const std::string u = unit(key);
      fail(key, fmt::format("must be in {}{}, {}{}{} (given {})", lo_closed ? "[" : "(", fmt_num(lo), fmt_num(hi),
                            hi_closed ? "]" : ")", u.empty() ? "" : " " + u, shown(key, x)));
    }
    return x;
  }
  // The plausibility limits: a value the rules accept, outside what the model is made for.
  void plausible(std::string_view key, double x, double lo, double hi) const {
    if (!(x >= lo && x <= hi)) {
      const std::string u = unit(key);
      fail(key, fmt::format("must be within [{}, {}]{}, the range the model is made for (given {})", fmt_num(lo),
                            fmt_num(hi), u.empty() ? "" : " " + u, shown(key, x)));
    }
  }
  double length(std::string_view key, double fallback) const {
    const double x = positive(key, fallback);
    plausible(key, x, kMinLength, kMaxLength);
    return x;
  }
  double mass(std::string_view key, double fallback) const {
    const double x = positive(key, fallback);
    plausible(key, x, kMinMass, kMaxMass);
    return x;
  }
  // A signed distance (an offset or a start position) within the machine's reach.
  double offset(std::string_view key, double fallback) const {
    const double x = number(key, fallback);
    plausible(key, x, -kMaxLength, kMaxLength);
    return x;
  }
  Vec2 pair(std::string_view key) const {
    const ConfigValue& v = *find(key);
    // As the input wrote it (v.text: numbers a double rounds), for the messages.
    const auto given = [&v] {
      return v.text.empty() ? fmt::format("[{}, {}]", fmt_num(v.pair[0]), fmt_num(v.pair[1])) : v.text;
    };
    if (!std::isfinite(v.pair[0]) || !std::isfinite(v.pair[1])) {
      fail(key, fmt::format("must hold finite numbers (given {})", given()));
    }
    if (std::fabs(v.pair[0]) > kMaxLength || std::fabs(v.pair[1]) > kMaxLength) {
      fail(key, fmt::format("must hold numbers within [{}, {}] m, the range the model is made for (given {})",
                            fmt_num(-kMaxLength), fmt_num(kMaxLength), given()));
    }
    return {v.pair[0], v.pair[1]};
  }
  std::string text(std::string_view key, const std::string& fallback) const {
    const ConfigValue* v = find(key);
    return v ? v->text : fallback;
  }
};

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
  if (i < s.size() && std::strchr("eEdD", s[i]) != nullptr) {
    const std::size_t mark = i++;
    if (i < s.size() && (s[i] == '+' || s[i] == '-')) ++i;
    if (digits() == 0) i = mark;  // "1e" : the e starts the comment
  }
  return i;
}

bool blank(const std::string& line) { return line.find_first_not_of(" \t\r") == std::string::npos; }

}  // namespace

const std::vector<KeySpec>& known_keys() { return kKeys; }

const KeySpec* find_key(std::string_view key) {
  for (const KeySpec& k : kKeys) {
    if (k.key == key) return &k;
  }
  return nullptr;
}

std::string nearest_key(std::string_view key) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const KeySpec& k : kKeys) {
    // Compare both the full key and its last part, so "rope_lenght" finds geometry.rope_length.
    const std::string_view tail = k.key.substr(k.key.find('.') + 1);
    const std::size_t d = std::min(edit_distance(key, k.key), edit_distance(key, tail));
    if (d < best_d) best_d = d, best = std::string(k.key);
  }
  return best_d <= std::max<std::size_t>(3, key.size() / 3) ? best : std::string();
}

std::string nearest_word(std::string_view word, const std::vector<std::string>& choices) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const std::string& c : choices) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best_d <= std::max<std::size_t>(2, word.size() / 3) ? best : std::string();
}

std::string printable(std::string_view text, std::size_t max_chars) {
  // Split into characters as shown: an escape or one whole UTF-8 character each.
  std::vector<std::string> chars;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t n = 0;  // length of a valid, printable UTF-8 sequence at i
    if (c >= 0x20 && c < 0x7f) {
      n = 1;
    } else if (c >= 0xc2 && c <= 0xf4) {
      const std::size_t want = c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
      n = want;
      for (std::size_t k = 1; k < want; ++k) {
        if (i + k >= text.size() || (static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) n = 0;
      }
      if (n == 2 && static_cast<unsigned char>(text[i + 1]) < 0xa0 && c == 0xc2) n = 0;  // C1 controls
      if (n == 3 && c == 0xe0 && static_cast<unsigned char>(text[i + 1]) < 0xa0) n = 0;  // overlong
      if (n == 4 && c == 0xf0 && static_cast<unsigned char>(text[i + 1]) < 0x90) n = 0;  // overlong
    }
    if (n > 0) {
      chars.emplace_back(text.substr(i, n));
      i += n;
      continue;
    }
    chars.push_back(c == '\n' ? "\\n" : c == '\t' ? "\\t" : c == '\r' ? "\\r" : fmt::format("\\x{:02x}", c));
    ++i;
  }
  std::string out;
  if (chars.size() <= max_chars || max_chars < 8) {
    for (const std::string& ch : chars) out += ch;
    return out;
  }
  const std::size_t head = (max_chars - 3) * 2 / 3, tail = max_chars - 3 - head;
  for (std::size_t i = 0; i < head; ++i) out += chars[i];
  out += "...";
  for (std::size_t i = chars.size() - tail; i < chars.size(); ++i) out += chars[i];
  return out;
}

std::string shortest(double value) { return fmt::format("{}", value); }

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
    if (!table) unknown_key(line_origin(cfg.source, node), sect);
    for (const auto& [name, value] : *table) {
      store(cfg, sect + "." + std::string(name.str()), value, line_origin(cfg.source, value), text);
    }
  }
  return cfg;
}

Config parse_inp(std::string_view text, const std::string& source) {
  // The paper's whatnext.inp: one number per line in this order, anything after it (past a blank,
  // ';' or '!') a comment; blank lines are skipped, as Fortran's read does. Nothing may follow.
  static const char* const kFields[15][2] = {
      {"start.sandbag_height", "hs"},      {"start.sandbag_x", "xs"},
      {"start.seesaw_angle", "phiS"},      {"start.lid_angle", "phiL"},
      {"geometry.hinge_distance", "f"},    {"geometry.rope_length", "lR"},
      {"geometry.hinge_angle", "gamma"},   {"geometry.lid_half_length", "rL"},
      {"geometry.seesaw_right_arm", "rH"}, {"masses.sandbag", "ms"},
      {"masses.lid", "mL"},                {"air.density", "rhoair"},
      {"air.helium_density", "rhohe"},     {"run.t_max", "tmax"},
      {"run.step", "dt"},
  };
  Config cfg;
  cfg.source = printable(source, 96);
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0, field = 0;
  while (field < 15 && std::getline(in, line)) {
    ++line_no;
    if (blank(line)) continue;
    const std::size_t first = line.find_first_not_of(" \t\r");
    const std::string origin = fmt::format("{} line {}", cfg.source, line_no);
    const std::size_t end = scan_real(line, first);
    const bool separated = end < line.size() ? std::strchr(" \t\r;!", line[end]) != nullptr : true;
    if (end == first || !separated) {
      throw InputError(fmt::format("{}: expected a number for {} ({}), got '{}'{}", origin, kFields[field][1],
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
      throw InputError(fmt::format("{} line {}: a whatnext.inp holds exactly 15 numbers; this line is one too "
                                   "many ('{}')", cfg.source, line_no, printable(line)));
    }
  }
  // The paper writes a .dat row every time step.
  ConfigValue out = cfg.values["run.step"];
  cfg.values["run.output_step"] = out;
  return cfg;
}

Config load_config_file(const std::string& path) {
  const std::string text = read_file(path);
  const auto first = text.find_first_not_of(" \t\r\n");
  const bool looks_inp =
      (path.size() >= 4 && path.compare(path.size() - 4, 4, ".inp") == 0) ||
      (first != std::string::npos &&
       (std::isdigit(static_cast<unsigned char>(text[first])) || text[first] == '-' ||
        text[first] == '+' || text[first] == '.'));
  return looks_inp ? parse_inp(text, path) : parse_toml(text, path);
}

std::string input_label(std::string machine, const std::vector<std::string>& sets) {
  if (sets.empty()) return machine;
  std::string joined;
  for (const std::string& s : sets) {
    if (!joined.empty()) joined += ", ";
    joined += s;
  }
  return machine + " with --set " + printable(joined, 120);
}

Config example_config(int n) {
  if (n < 1 || n > 4) {
    throw InputError(fmt::format("--example: the paper has examples 1 to 4 (given '{}')", n));
  }
  return parse_toml(example_toml(n), fmt::format("example{}.toml", n));
}

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
  ConfigValue v;
  v.number = value;
  v.origin = fmt::format("{} = {}", key, shortest(value));
  cfg.values[key] = v;
  if (key == "geometry.hinge_distance" || key == "geometry.hinge_angle") {
    cfg.values.erase("geometry.hinge_offset");
  }
}

namespace {

bool flag(const Reader& in, std::string_view key, bool fallback) {
  const ConfigValue* v = in.find(key);
  return v ? v->number != 0.0 : fallback;
}

// The switches beyond the paper (docs/extensions.md); with none of their keys given the machine
// is MODEL.md's.
void build_extensions(const Reader& in, Machine& m) {
  // Kermit's radio stands 0.5 m right of the box, its switch level with the box's top. The radio is
  // opt-in: radio.enabled, or any other radio key, turns it on.
  Vec2 offset{0.5, 0.0};
  if (in.find("radio.switch_offset")) offset = in.pair("radio.switch_offset");
  m.radio_switch = m.hinge + Vec2{2.0 * m.lid_half_length, 0.0} + offset;
  m.string_length = in.length("radio.string_length", 1.0);
  const bool any_radio = in.find("radio.switch_offset") || in.find("radio.string_length");
  m.radio = flag(in, "radio.enabled", any_radio);
  if (!m.radio && any_radio && in.find("radio.enabled")) {
    in.fail("radio.enabled", "is false but other radio keys are given: remove them or enable the radio");
  }

  m.balloon_rubber_mass = in.number("balloon.rubber_mass", 0.0);
  if (!(m.balloon_rubber_mass >= 0.0)) {
    in.fail("balloon.rubber_mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.balloon_rubber_mass)));
  }
  in.plausible("balloon.rubber_mass", m.balloon_rubber_mass, 0.0, kMaxMass);
  if (!(m.balloon_acceleration() > 0.0)) {
    const double most = (m.air_density - m.helium_density) * m.balloon_volume();
    in.fail("balloon.rubber_mass",
            fmt::format("must be below the lift {:.4g} kg (displaced air minus helium) so that the balloon "
                        "rises (given {})", most, fmt_num(m.balloon_rubber_mass)));
  }
  const bool drag_given = in.find("balloon.drag_coefficient") != nullptr;
  const bool drag = flag(in, "balloon.drag", drag_given);
  if (!drag && drag_given && in.find("balloon.drag")) {
    in.fail("balloon.drag", "is false but balloon.drag_coefficient is given: remove one");
  }
  m.balloon_drag_coefficient = drag ? in.positive("balloon.drag_coefficient", 0.47) : 0.0;
  in.plausible("balloon.drag_coefficient", m.balloon_drag_coefficient, 0.0, kMaxDrag);

  m.pivot_damping = in.in_range("damping.pivot", 0.0, 0.0, true, kMaxDamping, true);
  m.lid_hinge_damping = in.in_range("damping.lid_hinge", 0.0, 0.0, true, kMaxDamping, true);

  if (in.find("seesaw.left_arm")) m.seesaw_left_arm = in.length("seesaw.left_arm", 1.0);
  m.seesaw_mass = in.number("seesaw.mass", 0.0);
  if (!(m.seesaw_mass >= 0.0)) {
    in.fail("seesaw.mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.seesaw_mass)));
  }
  in.plausible("seesaw.mass", m.seesaw_mass, 0.0, kMaxMass);
  const bool bar = !in.find("seesaw.inertia") || !in.find("seesaw.com_offset");
  if (m.seesaw_mass > 0.0 && bar && !std::isfinite(m.seesaw_left_arm)) {
    in.fail("seesaw.mass", "needs seesaw.left_arm (a uniform bar) or both seesaw.inertia and seesaw.com_offset");
  }
  if ((in.find("seesaw.inertia") || in.find("seesaw.com_offset")) && !in.find("seesaw.mass")) {
    in.fail(in.find("seesaw.inertia") ? "seesaw.inertia" : "seesaw.com_offset",
            "needs seesaw.mass (the seesaw's weight acts at its centre of mass)");
  }
  if (m.seesaw_mass > 0.0) {
    // Uniform bar from -L to r_H: centre (r_H - L) / 2, I = m (L^3 + r_H^3) / (3 (L + r_H)).
    const double l = m.seesaw_left_arm, rh = m.seesaw_right_arm;
    const double bar_com = std::isfinite(l) ? 0.5 * (rh - l) : 0.0;
    const double bar_inertia = std::isfinite(l) ? m.seesaw_mass * (l * l * l + rh * rh * rh) / (3.0 * (l + rh)) : 0.0;
    m.seesaw_com_offset = in.offset("seesaw.com_offset", bar_com);
    m.seesaw_inertia = in.number("seesaw.inertia", bar_inertia);
    in.plausible("seesaw.inertia", m.seesaw_inertia, -kMaxInertia, kMaxInertia);
    const double least = m.seesaw_mass * m.seesaw_com_offset * m.seesaw_com_offset;
    if (!(m.seesaw_inertia > 0.0) || m.seesaw_inertia < least * (1.0 - 1e-12)) {
      in.fail("seesaw.inertia",
              fmt::format("must be > 0 and at least mass * com_offset^2 = {:.4g} kg m^2 (given {})", least,
                          fmt_num(m.seesaw_inertia)));
    }
  }
  if (m.pivot_damping > 0.0 && !m.heavy_seesaw()) {
    // A massless seesaw can only take the damper's torque from the sandbag pushing the arm, which
    // would have to pull whenever the seesaw turns back: no consistent motion (docs/extensions.md).
    in.fail("damping.pivot", "needs a seesaw with inertia: give seesaw.mass (and seesaw.left_arm) too");
  }
}

// Start conditions that only the extensions can violate.
void check_extension_start(const Reader& in, const Scenario& sc) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  const double c = std::cos(st.seesaw_angle), s = std::sin(st.seesaw_angle);
  const double along = -st.sandbag_x * c - st.sandbag_h * s;
  const double above = -st.sandbag_x * s + st.sandbag_h * c;
  if (std::isfinite(m.seesaw_left_arm) && std::fabs(above) <= 1e-9 && along > m.seesaw_left_arm) {
    in.fail("seesaw.left_arm", fmt::format("is shorter than the sandbag's start on the arm ({:.4g} m < {:.4g} m)",
                                           m.seesaw_left_arm, along));
  }
  if (m.radio) {
    const BalloonLimit limit{m.balloon_radius};
    const Vec2 balloon{m.hinge.x + m.lid_half_length, m.hinge.h + limit.height(st.lid_angle)};
    const double reach = norm(balloon - m.radio_switch);
    if (reach >= m.string_length) {
      in.fail("radio.string_length",
              fmt::format("is already straight at the start: the balloon is {:.4g} m from the switch (given {:.4g} m)",
                          reach, m.string_length));
    }
  }
}

}  // namespace

Scenario build_scenario(const Config& cfg) {
  const Reader in{cfg};
  Scenario sc;
  Machine& m = sc.machine;
  m.seesaw_right_arm = in.length("geometry.seesaw_right_arm", 0.6);
  m.lid_half_length = in.length("geometry.lid_half_length", 0.2);
  m.rope_length = in.length("geometry.rope_length", 1.0);
  if (cfg.has("geometry.hinge_offset")) {
    if (cfg.has("geometry.hinge_distance") || cfg.has("geometry.hinge_angle")) {
      in.fail("geometry.hinge_offset", "and geometry.hinge_distance/hinge_angle both given: use one form");
    }
    const Vec2 v = in.pair("geometry.hinge_offset");
    // Within rounding of the minimum counts as the minimum: a hinge given as distance and angle
    // at exactly kMinLength is written back by to_toml as an offset whose norm may be an ulp less.
    if (norm(v) < kMinLength * (1.0 - 1e-12)) {
      in.fail("geometry.hinge_offset", fmt::format("must put the hinge at least {} m from the pivot (given [{}, {}])",
                                                   fmt_num(kMinLength), fmt_num(v.x), fmt_num(v.h)));
    }
    m.hinge = {v.x, -v.h};
  } else {
    const double f = in.length("geometry.hinge_distance", 0.8);
    const double gamma = in.in_range("geometry.hinge_angle", 27.0, -180.0, true, 180.0, true) * kDeg;
    m.hinge = {f * std::cos(gamma), -f * std::sin(gamma)};
  }
  m.sandbag_mass = in.mass("masses.sandbag", 0.6);
  m.lid_mass = in.mass("masses.lid", 0.5);
  m.air_density = in.positive("air.density", 1.29);
  in.plausible("air.density", m.air_density, kMinDensity, kMaxDensity);
  m.helium_density = in.number("air.helium_density", 0.18);
  if (!(m.helium_density > 0.0 && m.helium_density < m.air_density)) {
    in.fail("air.helium_density",
            fmt::format("must be > 0 and below air.density ({} kg/m^3) so that the balloon rises (given {})",
                        fmt_num(m.air_density), fmt_num(m.helium_density)));
  }
  m.balloon_radius = in.length("balloon.radius", m.lid_half_length);
  const std::string bmodel = in.text("balloon.model", "program");
  if (!parse_balloon_model(bmodel, m.balloon_model)) {
    in.fail("balloon.model", fmt::format("must be program, lagrangian or added-mass (given '{}')", printable(bmodel)));
  }
  m.gravity = in.positive("run.gravity", 9.81);
  in.plausible("run.gravity", m.gravity, kMinGravity, kMaxGravity);
  build_extensions(in, m);
  if (m.balloon_acceleration() > kMaxBalloonG * m.gravity) {
    in.fail("air.helium_density",
            fmt::format("gives the free balloon an acceleration of {:.4g} g; at most {} g is within the range the "
                        "model is made for (given {} kg/m^3)", m.balloon_acceleration() / m.gravity,
                        fmt_num(kMaxBalloonG), fmt_num(m.helium_density)));
  }

  Start& st = sc.start;
  st.sandbag_x = in.number("start.sandbag_x", -0.3);
  st.sandbag_h = in.offset("start.sandbag_height", 1.0);
  st.seesaw_angle = in.in_range("start.seesaw_angle", -25.0, -90.0, false, 90.0, false) * kDeg;
  st.lid_angle = in.in_range("start.lid_angle", 5.0, 0.0, true, 90.0, false) * kDeg;

  RunSettings& run = sc.run;
  run.t_max = in.positive("run.t_max", 5.0);
  in.plausible("run.t_max", run.t_max, 0.0, kMaxTime);
  run.output_step = in.positive("run.output_step", 1e-3);
  run.step = in.positive("run.step", 1e-3);
  // Tighter than 1e-15 the error estimate is rounding noise and the steps shrink without end;
  // looser than 1e-3 events are located on a state that is wrong in the third digit.
  run.tolerance = in.in_range("run.tolerance", 1e-12, kMinTolerance, true, kMaxTolerance, true);
  run.vertical_margin = in.in_range("run.vertical_margin", 0.9, 0.0, true, 90.0, false) * kDeg;
  const std::string integ = in.text("run.integrator", "adaptive");
  if (!parse_integrator(integ, run.integrator)) {
    in.fail("run.integrator", fmt::format("must be adaptive, euler or rk4 (given '{}')", printable(integ)));
  }
  const std::string law = in.text("run.impact_law", "rope");
  if (!parse_impact_law(law, run.impact_law)) {
    in.fail("run.impact_law",
            fmt::format("must be rope, angular-momentum-sum, kinetic-energy or linear-momentum (given '{}')",
                        printable(law)));
  }
  if (run.integrator != IntegratorKind::adaptive && run.t_max / run.step > kMaxSteps) {
    in.fail("run.step", fmt::format("gives {:.3g} steps up to run.t_max = {} s; at most {:.0e} are allowed (given {})",
                                    run.t_max / run.step, fmt_num(run.t_max), kMaxSteps, fmt_num(run.step)));
  }
  if (run.integrator != IntegratorKind::adaptive) {
    // An explicit fixed step is unstable when a damper takes the motion's speed away within one
    // step: the lid then swings through its rest to -243 deg. Stay below the decay time I / c.
    const auto stable = [&](const char* damper, double c, double inertia) {
      if (c * run.step > inertia) {
        in.fail("run.step", fmt::format("is longer than the {:.3g} s in which {} = {} N m s/rad stops the part it "
                                        "damps: the fixed step is unstable (use a shorter step or the adaptive "
                                        "integrator; given {} s)", inertia / c, damper, fmt_num(c), fmt_num(run.step)));
      }
    };
    stable("damping.lid_hinge", m.lid_hinge_damping, m.lid_inertia());
    if (m.heavy_seesaw()) stable("damping.pivot", m.pivot_damping, m.seesaw_inertia);
  }
  if (run.t_max / run.output_step > kMaxSamples) {
    in.fail("run.output_step", fmt::format("gives {:.3g} rows up to run.t_max = {} s; at most {:.0e} are allowed (given {})",
                                           run.t_max / run.output_step, fmt_num(run.t_max), kMaxSamples,
                                           fmt_num(run.output_step)));
  }

  // Where the sandbag starts.
  if (!(st.sandbag_x < 0.0)) {
    in.fail("start.sandbag_x",
            fmt::format("must be < 0 m: the sandbag starts left of the pivot, above the left arm (given {})",
                        fmt_num(st.sandbag_x)));
  }
  in.plausible("start.sandbag_x", st.sandbag_x, -kMaxLength, -kMinLength);
  const double arm_h = st.sandbag_x * std::tan(st.seesaw_angle);
  const double above = -st.sandbag_x * std::sin(st.seesaw_angle) + st.sandbag_h * std::cos(st.seesaw_angle);
  if (above < -1e-9) {
    in.fail("start.sandbag_height",
            fmt::format("puts the sandbag under the seesaw's left arm, which is at {:.4g} m there (given {})",
                        arm_h, fmt_num(st.sandbag_h)));
  }
  // The rope at the start and over all reachable angles.
  const RopeGeometry rope(m);
  const double span0 = rope.span(st.seesaw_angle, st.lid_angle);
  if (span0 > m.rope_length + 1e-9) {
    in.fail("geometry.rope_length",
            fmt::format("is shorter than the distance from the seesaw's end to the lid's edge at the start "
                        "({:.4g} m < {:.4g} m)", m.rope_length, span0));
  }
  // A rope straight at the start must run above the hinge: with the lid above it, it would run
  // under the hinge, through the box (the closure's mirror branch).
  if (span0 >= m.rope_length - 1e-9 && !rope.lid_below_rope(st.seesaw_angle, st.lid_angle)) {
    in.fail("start.lid_angle",
            fmt::format("puts the lid above the rope, which is straight at the start (geometry.rope_length = {} m "
                        "at start.seesaw_angle = {} deg) and would run under the hinge, through the box (given {} deg)",
                        fmt_num(m.rope_length), fmt_num(st.seesaw_angle / kDeg), fmt_num(st.lid_angle / kDeg)));
  }
  const double reach = rope.max_span(st.lid_angle);
  if (m.rope_length > reach) {
    in.fail("geometry.rope_length",
            fmt::format("can never be straight: the seesaw's end and the lid's edge are never more than "
                        "{:.4g} m apart (given {:.4g} m)", reach, m.rope_length));
  }
  check_extension_start(in, sc);
  return sc;
}

namespace {
// The fewest decimal digits of `value` that `back` turns into exactly `want` again.
template <typename Back>
std::optional<double> fewest_digits(double value, double want, Back back) {
  for (int digits = 1; digits <= 17; ++digits) {
    const double d = std::strtod(fmt::format("{:.{}g}", value, digits).c_str(), nullptr);
    if (back(d) == want) return d;
  }
  return std::nullopt;
}
}  // namespace

std::string to_toml(const Scenario& sc, const Config* given) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  const RunSettings& r = sc.run;
  std::string out;
  auto line = [&](std::string_view key, double v) { out += fmt::format("{} = {}\n", key, shortest(v)); };
  out += "[geometry]\n";
  line("seesaw_right_arm", m.seesaw_right_arm);
  line("lid_half_length", m.lid_half_length);
  line("rope_length", m.rope_length);
  // An angle as input reads it (degrees times kDeg): the shortest degrees that give the same radians,
  // so that 27 stays 27 and not 27.000000000000004.
  auto angle_line = [&](std::string_view key, double radians) {
    const auto d = fewest_digits(radians / kDeg, radians, [](double deg) { return deg * kDeg; });
    line(key, d ? *d : radians / kDeg);
  };
  if (given && !given->has("geometry.hinge_offset")) {
    // As given: the same numbers make the same hinge.
    auto given_number = [&](const std::string& key, double fallback) {
      const auto it = given->values.find(key);
      return it == given->values.end() ? fallback : it->second.number;
    };
    line("hinge_distance", given_number("geometry.hinge_distance", 0.8));
    line("hinge_angle", given_number("geometry.hinge_angle", 27.0));
  } else {
    out += fmt::format("hinge_offset = [{}, {}]\n", shortest(m.hinge.x), shortest(-m.hinge.h));
  }

  out += "\n[masses]\n";
  line("sandbag", m.sandbag_mass);
  line("lid", m.lid_mass);
  out += "\n[air]\n";
  line("density", m.air_density);
  line("helium_density", m.helium_density);
  out += "\n[balloon]\n";
  line("radius", m.balloon_radius);
  out += fmt::format("model = \"{}\"\n", to_string(m.balloon_model));
  // The extensions are written only where they differ from the paper's model, so that a plain
  // machine stays a plain file.
  if (m.balloon_rubber_mass > 0.0) line("rubber_mass", m.balloon_rubber_mass);
  if (m.balloon_drag_coefficient > 0.0) line("drag_coefficient", m.balloon_drag_coefficient);
  if (m.radio) {
    const Vec2 offset = m.radio_switch - m.hinge - Vec2{2.0 * m.lid_half_length, 0.0};
    out += "\n[radio]\nenabled = true\n";
    out += fmt::format("switch_offset = [{}, {}]\n", shortest(offset.x), shortest(offset.h));
    line("string_length", m.string_length);
  }
  if (m.pivot_damping > 0.0 || m.lid_hinge_damping > 0.0) {
    out += "\n[damping]\n";
    line("pivot", m.pivot_damping);
    line("lid_hinge", m.lid_hinge_damping);
  }
  if (std::isfinite(m.seesaw_left_arm) || m.seesaw_mass > 0.0) {
    out += "\n[seesaw]\n";
    if (std::isfinite(m.seesaw_left_arm)) line("left_arm", m.seesaw_left_arm);
    if (m.seesaw_mass > 0.0) {
      line("mass", m.seesaw_mass);
      line("inertia", m.seesaw_inertia);
      line("com_offset", m.seesaw_com_offset);
    }
  }
  out += "\n[start]\n";
  line("sandbag_x", st.sandbag_x);
  line("sandbag_height", st.sandbag_h);
  angle_line("seesaw_angle", st.seesaw_angle);
  angle_line("lid_angle", st.lid_angle);
  out += "\n[run]\n";
  line("t_max", r.t_max);
  line("output_step", r.output_step);
  out += fmt::format("integrator = \"{}\"\n", to_string(r.integrator));
  line("step", r.step);
  line("tolerance", r.tolerance);
  out += fmt::format("impact_law = \"{}\"\n", to_string(r.impact_law));
  angle_line("vertical_margin", r.vertical_margin);
  line("gravity", m.gravity);
  return out;
}

}  // namespace whatnext
