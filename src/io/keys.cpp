// The input keys: the table of every key with its unit, default and meaning (docs/inputs.md), and
// the suggestions for a misspelt key or word.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "input_common.hpp"

namespace whatnext {

namespace {

const std::vector<KeySpec> kKeys = {
    {"geometry.seesaw_right_arm", KeyKind::length, "m", "r_H: pivot to the rope's end of the seesaw", "0.6"},
    {"geometry.lid_half_length", KeyKind::length, "m", "r_L: half the lid (and box) edge", "0.2"},
    {"geometry.rope_length", KeyKind::length, "m", "l_R: rope between seesaw end and lid edge", "1.0"},
    {"geometry.hinge_distance", KeyKind::length, "m", "f: pivot to lid hinge", "0.8"},
    {"geometry.hinge_angle", KeyKind::angle, "deg", "gamma: hinge below the pivot's horizontal", "27"},
    {"geometry.hinge_offset", KeyKind::pair, "m",
     "[dx, dh]: hinge dx right of and dh below the pivot (instead of distance + angle)", "none"},
    {"geometry.rope_on_lid", KeyKind::length, "m",
     "where the rope is tied: from the hinge along the lid (Fig. 3: r_L, the lid's middle)", "2 r_L"},
    {"masses.sandbag", KeyKind::mass, "kg", "m_S: the sandbag (a point mass)", "0.6"},
    {"masses.lid", KeyKind::mass, "kg", "m_L: the lid (a uniform plate)", "0.5"},
    {"air.density", KeyKind::density, "kg/m^3", "density of air", "1.29"},
    {"air.helium_density", KeyKind::density, "kg/m^3", "density of the balloon's helium", "0.18"},
    {"balloon.radius", KeyKind::length, "m", "r_B", "r_L"},
    {"balloon.model", KeyKind::text, "",
     "program (a = g (rho_air - rho_He) / rho_air), lagrangian (/ rho_He) or added-mass "
     "(/ (rho_He + rho_air / 2))",
     "program"},
    {"balloon.rubber_mass", KeyKind::mass, "kg", "the balloon's rubber: weight and inertia", "0"},
    {"balloon.drag", KeyKind::flag, "", "true: quadratic air drag 1/2 rho_air Cd pi r_B^2 v|v|", "false"},
    {"balloon.drag_coefficient", KeyKind::positive, "",
     "Cd of the air drag (a sphere); giving it turns drag on", "0.47"},
    {"radio.enabled", KeyKind::flag, "",
     "true: after lid_open run on until the balloon's string switches the radio on (any other radio key "
     "turns it on too)",
     "false"},
    {"radio.switch_offset", KeyKind::pair, "m",
     "[dx, dh]: the radio's switch dx right of and dh above the box's top-right corner", "[0.5, 0]"},
    {"radio.string_length", KeyKind::length, "m", "the balloon's string, centre to switch", "1.0"},
    {"radio.switch_force", KeyKind::positive, "N",
     "the force the string must pull with to flip the radio's switch (a rocker switch); 0: any pull", "0"},
    {"damping.pivot", KeyKind::positive, "N m s/rad", "viscous torque -c phiS' at the seesaw's pivot", "0"},
    {"damping.lid_hinge", KeyKind::positive, "N m s/rad", "viscous torque -c phiL' at the lid's hinge", "0"},
    {"seesaw.left_arm", KeyKind::length, "m", "pivot to the left arm's end", "endless"},
    {"seesaw.mass", KeyKind::mass, "kg",
     "a seesaw with mass: a uniform bar from -left_arm to r_H unless inertia/com_offset are given", "0"},
    {"seesaw.inertia", KeyKind::positive, "kg m^2", "the seesaw's moment of inertia about the pivot", "bar"},
    {"seesaw.com_offset", KeyKind::length, "m",
     "the seesaw's centre of mass along the bar from the pivot, + towards the rope's end", "bar"},
    {"seesaw.end_stop", KeyKind::flag, "",
     "true: an edge at the left arm's end stops the sandbag, which then rides there (needs seesaw.left_arm)",
     "false"},
    {"floor.enabled", KeyKind::flag, "",
     "true: the floor through the box's bottom; the seesaw's ends and the sandbag stand on it (needs "
     "seesaw.left_arm)",
     "false"},
    {"floor.restitution", KeyKind::positive, "",
     "Newton's coefficient of impacts on the floor, 0 (they stay) to 1 (they bounce back as fast); giving "
     "it turns the floor on",
     "0"},
    {"restitution.sandbag", KeyKind::positive, "",
     "Newton's coefficient of the sandbag landing on the arm: 0 (it stays) to 1", "0"},
    {"restitution.rope", KeyKind::positive, "",
     "Newton's coefficient of the rope's jerk: 0 (the rope law) to 1 (the rope bounces back as fast)", "0"},
    {"restitution.lid", KeyKind::positive, "", "Newton's coefficient of the lid landing on the box: 0 to 1",
     "0"},
    {"friction.sandbag", KeyKind::positive, "",
     "Coulomb's mu between the sandbag and the arm: it sticks while the pull along the arm is at most mu "
     "times the arm's push, else slides against mu times it; 0: it slides freely (the paper's)",
     "0"},
    {"friction.pivot", KeyKind::positive, "N m",
     "Coulomb torque at the seesaw's pivot: it turns only while the other torques on it exceed this, "
     "against it (needs a seesaw with mass)",
     "0"},
    {"friction.lid_hinge", KeyKind::positive, "N m",
     "Coulomb torque at the lid's hinge: the lid turns only while the other torques on it exceed this, "
     "against it",
     "0"},
    {"restitution.stop", KeyKind::positive, "",
     "Newton's coefficient of the sandbag reaching the end stop: 0 to 1 (needs seesaw.end_stop)", "0"},
    {"rope.stiffness", KeyKind::positive, "N/m",
     "a rope that stretches: a one-sided spring-damper pulling k (span - l_R) + c span', never pushing; "
     "no impact law (docs/impact.md)",
     "inextensible"},
    {"rope.damping", KeyKind::positive, "N s/m", "c of the rope that stretches (needs rope.stiffness)", "0"},
    {"start.sandbag_x", KeyKind::length, "m", "sandbag's start, horizontal from the pivot (< 0)", "-0.3"},
    {"start.sandbag_height", KeyKind::length, "m", "sandbag's start height above the pivot", "1.0"},
    {"start.seesaw_angle", KeyKind::angle, "deg", "phiS0, positive = left arm down", "-25"},
    {"start.lid_angle", KeyKind::angle, "deg", "phiL0, the lid's resting (lowest) angle", "5"},
    {"run.t_max", KeyKind::time, "s", "end of the simulated time", "5"},
    {"run.output_step", KeyKind::time, "s", "spacing of CSV/.dat rows", "0.001"},
    {"run.integrator", KeyKind::text, "", "adaptive, euler or rk4", "adaptive"},
    {"run.step", KeyKind::time, "s", "time step of euler and rk4", "0.001"},
    {"run.tolerance", KeyKind::positive, "",
     "adaptive: error tolerance per step (abs. and rel.), 1e-15 to 1e-3", "1e-12"},
    {"run.impact_law", KeyKind::text, "", "rope, angular-momentum-sum, kinetic-energy or linear-momentum",
     "rope"},
    {"run.vertical_margin", KeyKind::angle, "deg", "stop this far before 90 deg", "0.9"},
    {"run.gravity", KeyKind::acceleration, "m/s^2", "g", "9.81"},
};

// Where the model is made for (docs/inputs.md "Limits"): a tabletop machine. Far outside, lengths

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

}  // namespace

namespace io {
[[noreturn]] void unknown_key(const std::string& where, std::string_view key) {
  const std::string near = nearest_key(key);
  if (near.empty() || near == key)
    throw InputError(fmt::format("{}: unknown key '{}'", where, printable(key)));
  throw InputError(fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, printable(key), near));
}
}  // namespace io

const std::vector<KeySpec>& known_keys() { return kKeys; }

double key_default(std::string_view key) {
  // Read once: validation asks for the defaults of every key a machine leaves out, per machine of
  // a sweep.
  static const std::unordered_map<std::string_view, double> table = [] {
    std::unordered_map<std::string_view, double> t;
    for (const KeySpec& k : kKeys) {
      const std::string text(k.default_text);
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      if (!text.empty() && end == text.c_str() + text.size() && std::isfinite(v)) t.emplace(k.key, v);
    }
    return t;
  }();
  const auto it = table.find(key);
  return it == table.end() ? std::numeric_limits<double>::quiet_NaN() : it->second;
}

Vec2 key_default_pair(std::string_view key) {
  // Read once, as --set reads a pair ("[0.5, 0]"; a word such as "none" is the key left out):
  // validation asks for it per machine of a sweep.
  static const std::unordered_map<std::string_view, Vec2> table = [] {
    std::unordered_map<std::string_view, Vec2> t;
    for (const KeySpec& k : kKeys) {
      if (k.kind != KeyKind::pair) continue;
      Config c;
      apply_set(c, std::string(k.key) + "=" + std::string(k.default_text));
      const auto it = c.values.find(k.key);
      if (it != c.values.end()) t.emplace(k.key, Vec2{it->second.pair[0], it->second.pair[1]});
    }
    return t;
  }();
  const auto it = table.find(key);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return it == table.end() ? Vec2{nan, nan} : it->second;
}

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

}  // namespace whatnext
