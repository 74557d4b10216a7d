#include "whatnext/config.hpp"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdlib>
#include <fstream>
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
    {"geometry.seesaw_right_arm", KeyKind::length, "m", "r_H: pivot to the rope's end of the seesaw"},
    {"geometry.lid_half_length", KeyKind::length, "m", "r_L: half the lid (and box) edge"},
    {"geometry.rope_length", KeyKind::length, "m", "l_R: rope between seesaw end and lid edge"},
    {"geometry.hinge_distance", KeyKind::length, "m", "f: pivot to lid hinge"},
    {"geometry.hinge_angle", KeyKind::angle, "deg", "gamma: hinge below the pivot's horizontal"},
    {"geometry.hinge_offset", KeyKind::pair, "m",
     "[dx, dh]: hinge dx right of and dh below the pivot (instead of distance + angle)"},
    {"masses.sandbag", KeyKind::mass, "kg", "m_S: the sandbag (a point mass)"},
    {"masses.lid", KeyKind::mass, "kg", "m_L: the lid (a uniform plate)"},
    {"air.density", KeyKind::density, "kg/m^3", "density of air"},
    {"air.helium_density", KeyKind::density, "kg/m^3", "density of the balloon's helium"},
    {"balloon.radius", KeyKind::length, "m", "r_B (default: geometry.lid_half_length)"},
    {"balloon.model", KeyKind::text, "",
     "program (a = g (rho_air - rho_He) / rho_air), lagrangian (/ rho_He) or added-mass "
     "(/ (rho_He + rho_air / 2))"},
    {"balloon.rubber_mass", KeyKind::mass, "kg", "the balloon's rubber: weight and inertia (default 0)"},
    {"balloon.drag", KeyKind::flag, "", "true: quadratic air drag 1/2 rho_air Cd pi r_B^2 v|v| (default false)"},
    {"balloon.drag_coefficient", KeyKind::positive, "",
     "Cd of the air drag (default 0.47, a sphere); giving it turns drag on"},
    {"radio.enabled", KeyKind::flag, "",
     "true: after lid_open run on until the balloon's string switches the radio on (default false; "
     "any other radio key turns it on too)"},
    {"radio.switch_offset", KeyKind::pair, "m",
     "[dx, dh]: the radio's switch dx right of and dh above the box's top-right corner (default [0.5, 0])"},
    {"radio.string_length", KeyKind::length, "m", "the balloon's string, centre to switch (default 1.0)"},
    {"damping.pivot", KeyKind::positive, "N m s/rad", "viscous torque -c phiS' at the seesaw's pivot (default 0)"},
    {"damping.lid_hinge", KeyKind::positive, "N m s/rad", "viscous torque -c phiL' at the lid's hinge (default 0)"},
    {"seesaw.left_arm", KeyKind::length, "m", "pivot to the left arm's end (default: endless, as the paper)"},
    {"seesaw.mass", KeyKind::mass, "kg",
     "a seesaw with mass: a uniform bar from -left_arm to r_H unless inertia/com_offset are given (default 0)"},
    {"seesaw.inertia", KeyKind::positive, "kg m^2", "the seesaw's moment of inertia about the pivot"},
    {"seesaw.com_offset", KeyKind::length, "m",
     "the seesaw's centre of mass along the bar from the pivot, + towards the rope's end"},
    {"start.sandbag_x", KeyKind::length, "m", "sandbag's start, horizontal from the pivot (< 0)"},
    {"start.sandbag_height", KeyKind::length, "m", "sandbag's start height above the pivot"},
    {"start.seesaw_angle", KeyKind::angle, "deg", "phiS0, positive = left arm down"},
    {"start.lid_angle", KeyKind::angle, "deg", "phiL0, the lid's resting (lowest) angle"},
    {"run.t_max", KeyKind::time, "s", "end of the simulated time"},
    {"run.output_step", KeyKind::time, "s", "spacing of CSV/.dat rows"},
    {"run.integrator", KeyKind::text, "", "adaptive, euler or rk4"},
    {"run.step", KeyKind::time, "s", "time step of euler and rk4"},
    {"run.tolerance", KeyKind::positive, "", "adaptive: error tolerance per step (abs. and rel.)"},
    {"run.impact_law", KeyKind::text, "",
     "rope, angular-momentum-sum, kinetic-energy or linear-momentum"},
    {"run.vertical_margin", KeyKind::angle, "deg", "stop this far before 90 deg"},
    {"run.gravity", KeyKind::acceleration, "m/s^2", "g"},
};

std::string fmt_num(double v) { return fmt::format("{:g}", v); }

std::string read_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(fmt::format("{}: cannot read the input file", path));
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
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
  if (near.empty()) throw InputError(fmt::format("{}: unknown key '{}'", where, key));
  throw InputError(fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, key, near));
}

// Stores one TOML node under key, checking its type against the key's kind.
void store(Config& cfg, const std::string& key, const toml::node& node, const std::string& origin) {
  const KeySpec* spec = find_key(key);
  if (!spec) unknown_key(origin, key);
  ConfigValue v;
  v.origin = origin;
  if (spec->kind == KeyKind::flag) {
    if (!node.is_boolean()) {
      throw InputError(fmt::format("{}: {} must be true or false", origin, key));
    }
    v.number = node.as_boolean()->get() ? 1.0 : 0.0;
  } else if (spec->kind == KeyKind::text) {
    if (!node.is_string()) {
      throw InputError(fmt::format("{}: {} must be a text value (one of: {})", origin, key, spec->help));
    }
    v.type = ConfigValue::Type::text;
    v.text = node.as_string()->get();
  } else if (spec->kind == KeyKind::pair) {
    const toml::array* arr = node.as_array();
    if (!arr || arr->size() != 2 || !(*arr)[0].is_number() || !(*arr)[1].is_number()) {
      throw InputError(fmt::format("{}: {} must be a pair of numbers [dx, dh] in {}", origin, key, spec->unit));
    }
    v.type = ConfigValue::Type::pair;
    v.pair[0] = (*arr)[0].value<double>().value();
    v.pair[1] = (*arr)[1].value<double>().value();
  } else {
    if (!node.is_number()) {
      std::ostringstream given;
      node.visit([&](const auto& n) { given << n; });
      throw InputError(fmt::format("{}: {} must be a number in {} (given {})", origin, key,
                                   spec->unit.empty() ? "plain units" : spec->unit, given.str()));
    }
    v.number = node.value<double>().value();
  }
  cfg.values[key] = v;
}

std::string line_origin(const std::string& source, const toml::node& node) {
  return fmt::format("{}:{}", source, node.source().begin.line);
}

// --- validation helpers ---------------------------------------------------------------------

struct Reader {
  const Config& cfg;

  const ConfigValue* find(const std::string& key) const {
    auto it = cfg.values.find(key);
    return it == cfg.values.end() ? nullptr : &it->second;
  }
  std::string where(const std::string& key) const {
    const ConfigValue* v = find(key);
    return v ? v->origin : cfg.source;
  }
  [[noreturn]] void fail(const std::string& key, const std::string& rule) const {
    throw InputError(fmt::format("{}: {} {}", where(key), key, rule));
  }
  double number(const std::string& key, double fallback) const {
    const ConfigValue* v = find(key);
    if (!v) return fallback;
    if (!std::isfinite(v->number)) fail(key, fmt::format("must be a finite number (given {})", fmt_num(v->number)));
    return v->number;
  }
  double positive(const std::string& key, double fallback) const {
    const double x = number(key, fallback);
    const KeySpec* spec = find_key(key);
    if (!(x > 0.0)) fail(key, fmt::format("must be > 0 {} (given {})", spec->unit, fmt_num(x)));
    return x;
  }
  double in_range(const std::string& key, double fallback, double lo, bool lo_closed, double hi,
                  bool hi_closed) const {
    const double x = number(key, fallback);
    const bool ok = (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    if (!ok) {
      const KeySpec* spec = find_key(key);
      fail(key, fmt::format("must be in {}{}, {}{} {} (given {})", lo_closed ? "[" : "(", fmt_num(lo),
                            fmt_num(hi), hi_closed ? "]" : ")", spec->unit, fmt_num(x)));
    }
    return x;
  }
  std::string text(const std::string& key, const std::string& fallback) const {
    const ConfigValue* v = find(key);
    return v ? v->text : fallback;
  }
};

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

Config parse_toml(std::string_view text, const std::string& source) {
  Config cfg;
  cfg.source = source;
  toml::table root;
  try {
    root = toml::parse(text, source);
  } catch (const toml::parse_error& err) {
    throw InputError(fmt::format("{}:{}:{}: not valid TOML: {}", source, err.source().begin.line,
                                 err.source().begin.column, err.description()));
  }
  for (const auto& [section, node] : root) {
    const std::string sect(section.str());
    const toml::table* table = node.as_table();
    if (!table) unknown_key(line_origin(source, node), sect);
    for (const auto& [name, value] : *table) {
      store(cfg, sect + "." + std::string(name.str()), value, line_origin(source, value));
    }
  }
  return cfg;
}

Config parse_inp(std::string_view text, const std::string& source) {
  // The paper's whatnext.inp: one number per line in this order, anything after it a comment.
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
  cfg.source = source;
  std::istringstream in{std::string(text)};
  std::string line;
  int line_no = 0, field = 0;
  while (field < 15 && std::getline(in, line)) {
    ++line_no;
    const auto first = line.find_first_not_of(" \t\r");
    if (first == std::string::npos) continue;  // blank lines are skipped, as Fortran's read does
    std::string token = line.substr(first, line.find_first_of(" \t\r;,!", first) - first);
    std::replace(token.begin(), token.end(), 'd', 'e');  // Fortran's 1.0d0
    std::replace(token.begin(), token.end(), 'D', 'e');
    const std::string origin = fmt::format("{} line {}", source, line_no);
    char* end = nullptr;
    const double v = std::strtod(token.c_str(), &end);
    if (token.empty() || end != token.c_str() + token.size()) {
      throw InputError(fmt::format("{}: expected a number for {} ({}), got '{}'", origin,
                                   kFields[field][1], kFields[field][0], line.substr(first)));
    }
    ConfigValue cv;
    cv.number = v;
    cv.origin = fmt::format("{} ({})", origin, kFields[field][1]);
    cfg.values[kFields[field][0]] = cv;
    ++field;
  }
  if (field < 15) {
    throw InputError(fmt::format("{}: a whatnext.inp needs 15 numbers, one per line; found {} (next: {})",
                                 source, field, kFields[field][1]));
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

Config example_config(int n) {
  if (n < 1 || n > 4) {
    throw InputError(fmt::format("--example: the paper has examples 1 to 4 (given {})", n));
  }
  return parse_toml(example_toml(n), fmt::format("example{}.toml", n));
}

void apply_set(Config& cfg, std::string_view assignment) {
  const auto eq = assignment.find('=');
  const std::string origin = fmt::format("--set {}", assignment);
  if (eq == std::string_view::npos || eq == 0) {
    throw InputError(fmt::format("{}: expected KEY=VALUE", origin));
  }
  auto trim = [](std::string_view s) {
    const auto a = s.find_first_not_of(" \t");
    const auto b = s.find_last_not_of(" \t");
    return a == std::string_view::npos ? std::string_view() : s.substr(a, b - a + 1);
  };
  const std::string key(trim(assignment.substr(0, eq)));
  const std::string value(trim(assignment.substr(eq + 1)));
  const KeySpec* spec = find_key(key);
  if (!spec) unknown_key("--set", key);
  toml::table parsed;
  bool ok = true;
  try {
    parsed = toml::parse("v = " + value);
  } catch (const toml::parse_error&) {
    ok = false;
  }
  if (ok) {
    store(cfg, key, *parsed.get("v"), origin);
  } else if (spec->kind == KeyKind::text) {
    store(cfg, key, toml::value<std::string>(value), origin);
  } else {
    throw InputError(fmt::format("{}: {} must be a number in {} (given '{}')", origin, key,
                                 spec->unit.empty() ? "plain units" : spec->unit, value));
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
  v.origin = fmt::format("{} = {}", key, fmt_num(value));
  cfg.values[key] = v;
  if (key == "geometry.hinge_distance" || key == "geometry.hinge_angle") {
    cfg.values.erase("geometry.hinge_offset");
  }
}

namespace {

bool flag(const Reader& in, const std::string& key, bool fallback) {
  const ConfigValue* v = in.find(key);
  return v ? v->number != 0.0 : fallback;
}

// The switches beyond the paper (docs/extensions.md); with none of their keys given the machine
// is MODEL.md's.
void build_extensions(const Reader& in, Machine& m) {
  // Kermit's radio stands 0.5 m right of the box, its switch level with the box's top. The radio is
  // opt-in: radio.enabled, or any other radio key, turns it on.
  Vec2 offset{0.5, 0.0};
  if (in.find("radio.switch_offset")) {
    const ConfigValue& v = *in.find("radio.switch_offset");
    if (!std::isfinite(v.pair[0]) || !std::isfinite(v.pair[1])) {
      in.fail("radio.switch_offset", "must hold finite numbers");
    }
    offset = {v.pair[0], v.pair[1]};
  }
  m.radio_switch = m.hinge + Vec2{2.0 * m.lid_half_length, 0.0} + offset;
  m.string_length = in.positive("radio.string_length", 1.0);
  const bool any_radio = in.find("radio.switch_offset") || in.find("radio.string_length");
  m.radio = flag(in, "radio.enabled", any_radio);
  if (!m.radio && any_radio && in.find("radio.enabled")) {
    in.fail("radio.enabled", "is false but other radio keys are given: remove them or enable the radio");
  }

  m.balloon_rubber_mass = in.number("balloon.rubber_mass", 0.0);
  if (!(m.balloon_rubber_mass >= 0.0)) {
    in.fail("balloon.rubber_mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.balloon_rubber_mass)));
  }
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

  m.pivot_damping = in.in_range("damping.pivot", 0.0, 0.0, true, 1e6, true);
  m.lid_hinge_damping = in.in_range("damping.lid_hinge", 0.0, 0.0, true, 1e6, true);

  if (in.find("seesaw.left_arm")) m.seesaw_left_arm = in.positive("seesaw.left_arm", 1.0);
  m.seesaw_mass = in.number("seesaw.mass", 0.0);
  if (!(m.seesaw_mass >= 0.0)) {
    in.fail("seesaw.mass", fmt::format("must be >= 0 kg (given {})", fmt_num(m.seesaw_mass)));
  }
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
    m.seesaw_com_offset = in.number("seesaw.com_offset", bar_com);
    m.seesaw_inertia = in.number("seesaw.inertia", bar_inertia);
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
  m.seesaw_right_arm = in.positive("geometry.seesaw_right_arm", 0.6);
  m.lid_half_length = in.positive("geometry.lid_half_length", 0.2);
  m.rope_length = in.positive("geometry.rope_length", 1.0);
  if (cfg.has("geometry.hinge_offset")) {
    if (cfg.has("geometry.hinge_distance") || cfg.has("geometry.hinge_angle")) {
      in.fail("geometry.hinge_offset", "and geometry.hinge_distance/hinge_angle both given: use one form");
    }
    const ConfigValue& v = cfg.values.at("geometry.hinge_offset");
    if (!std::isfinite(v.pair[0]) || !std::isfinite(v.pair[1])) {
      in.fail("geometry.hinge_offset", "must hold finite numbers");
    }
    if (v.pair[0] == 0.0 && v.pair[1] == 0.0) {
      in.fail("geometry.hinge_offset", "must not put the hinge on the pivot (given [0, 0])");
    }
    m.hinge = {v.pair[0], -v.pair[1]};
  } else {
    const double f = in.positive("geometry.hinge_distance", 0.8);
    const double gamma = in.in_range("geometry.hinge_angle", 27.0, -180.0, true, 180.0, true) * kDeg;
    m.hinge = {f * std::cos(gamma), -f * std::sin(gamma)};
  }
  m.sandbag_mass = in.positive("masses.sandbag", 0.6);
  m.lid_mass = in.positive("masses.lid", 0.5);
  m.air_density = in.positive("air.density", 1.29);
  m.helium_density = in.number("air.helium_density", 0.18);
  if (!(m.helium_density > 0.0 && m.helium_density < m.air_density)) {
    in.fail("air.helium_density",
            fmt::format("must be > 0 and below air.density ({} kg/m^3) so that the balloon rises (given {})",
                        fmt_num(m.air_density), fmt_num(m.helium_density)));
  }
  m.balloon_radius = in.positive("balloon.radius", m.lid_half_length);
  const std::string bmodel = in.text("balloon.model", "program");
  if (!parse_balloon_model(bmodel, m.balloon_model)) {
    in.fail("balloon.model", fmt::format("must be program, lagrangian or added-mass (given '{}')", bmodel));
  }
  m.gravity = in.positive("run.gravity", 9.81);
  build_extensions(in, m);

  Start& st = sc.start;
  st.sandbag_x = in.number("start.sandbag_x", -0.3);
  st.sandbag_h = in.number("start.sandbag_height", 1.0);
  st.seesaw_angle = in.in_range("start.seesaw_angle", -25.0, -90.0, false, 90.0, false) * kDeg;
  st.lid_angle = in.in_range("start.lid_angle", 5.0, 0.0, true, 90.0, false) * kDeg;

  RunSettings& run = sc.run;
  run.t_max = in.positive("run.t_max", 5.0);
  run.output_step = in.positive("run.output_step", 1e-3);
  run.step = in.positive("run.step", 1e-3);
  run.tolerance = in.in_range("run.tolerance", 1e-12, 0.0, false, 1e-2, true);
  run.vertical_margin = in.in_range("run.vertical_margin", 0.9, 0.0, true, 90.0, false) * kDeg;
  const std::string integ = in.text("run.integrator", "adaptive");
  if (!parse_integrator(integ, run.integrator)) {
    in.fail("run.integrator", fmt::format("must be adaptive, euler or rk4 (given '{}')", integ));
  }
  const std::string law = in.text("run.impact_law", "rope");
  if (!parse_impact_law(law, run.impact_law)) {
    in.fail("run.impact_law",
            fmt::format("must be rope, angular-momentum-sum, kinetic-energy or linear-momentum (given '{}')", law));
  }
  if (run.integrator != IntegratorKind::adaptive && run.t_max / run.step > kMaxSteps) {
    in.fail("run.step", fmt::format("gives {:.3g} steps up to run.t_max = {} s; at most {:.0e} are allowed (given {})",
                                    run.t_max / run.step, fmt_num(run.t_max), kMaxSteps, fmt_num(run.step)));
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

std::string to_toml(const Scenario& sc) {
  const Machine& m = sc.machine;
  const Start& st = sc.start;
  const RunSettings& r = sc.run;
  std::string out;
  auto line = [&](std::string_view key, double v) { out += fmt::format("{} = {:.17g}\n", key, v); };
  out += "[geometry]\n";
  line("seesaw_right_arm", m.seesaw_right_arm);
  line("lid_half_length", m.lid_half_length);
  line("rope_length", m.rope_length);
  out += fmt::format("hinge_offset = [{:.17g}, {:.17g}]\n", m.hinge.x, -m.hinge.h);
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
    out += fmt::format("switch_offset = [{:.17g}, {:.17g}]\n", offset.x, offset.h);
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
  line("seesaw_angle", st.seesaw_angle / kDeg);
  line("lid_angle", st.lid_angle / kDeg);
  out += "\n[run]\n";
  line("t_max", r.t_max);
  line("output_step", r.output_step);
  out += fmt::format("integrator = \"{}\"\n", to_string(r.integrator));
  line("step", r.step);
  line("tolerance", r.tolerance);
  out += fmt::format("impact_law = \"{}\"\n", to_string(r.impact_law));
  line("vertical_margin", r.vertical_margin / kDeg);
  line("gravity", m.gravity);
  return out;
}

}  // namespace whatnext
