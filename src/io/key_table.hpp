// The table of every key an input may set (docs/inputs.md), in documentation order, and Key: a
// key of it found by name when validation is compiled, so that reading a machine's values (per
// machine of a sweep) looks nothing up by name.
#pragma once

#include <cstddef>
#include <iterator>
#include <string_view>

#include "whatnext/config.hpp"

namespace whatnext::io {

inline constexpr KeySpec kKeys[] = {
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
constexpr std::size_t kKeyCount = std::size(kKeys);

// The key's place in kKeys; kKeyCount for a key not in it.
constexpr std::size_t key_index(std::string_view key) {
  std::size_t i = 0;
  while (i < kKeyCount && kKeys[i].key != key) ++i;
  return i;
}

// A key of the table, written as a literal: a key that is not in it does not compile.
class Key {
 public:
  template <std::size_t N>
  consteval Key(const char (&name)[N]) : index_(key_index(std::string_view(name, N - 1))) {
    if (index_ == kKeyCount) throw "not a key of the table (kKeys)";
  }
  constexpr std::size_t index() const { return index_; }
  constexpr std::string_view name() const { return kKeys[index_].key; }
  constexpr const KeySpec& spec() const { return kKeys[index_]; }

 private:
  std::size_t index_;
};

// The key's default as a number (key_default) by its place in kKeys.
double key_default_at(std::size_t index);
// The key's place in kKeys found by name at run time (kKeyCount for an unknown key).
std::size_t find_key_index(std::string_view key);

}  // namespace whatnext::io
