// Validated, immutable description of one machine and one run.
// SI units and radians throughout; degrees exist only in the input layer (config.hpp).
#pragma once

#include <cmath>
#include <limits>
#include <string>
#include <string_view>

#include "whatnext/units.hpp"
#include "whatnext/vec2.hpp"

namespace whatnext {

enum class ImpactLaw { rope, angular_momentum_sum, kinetic_energy, linear_momentum };
enum class IntegratorKind { adaptive, euler, rk4 };
// How the balloon's upward acceleration follows from the densities (docs/model.md §8).
// program and lagrangian are the paper's two readings; added_mass also accelerates half the displaced air.
enum class BalloonModel { program, lagrangian, added_mass };

std::string_view to_string(ImpactLaw law);
std::string_view to_string(IntegratorKind kind);
std::string_view to_string(BalloonModel model);
bool parse_impact_law(std::string_view text, ImpactLaw& out);
bool parse_integrator(std::string_view text, IntegratorKind& out);
bool parse_balloon_model(std::string_view text, BalloonModel& out);

// The lid's hinge from the pivot, given as distance f and angle gamma below the horizontal.
inline Vec2 hinge_from(double distance, double angle) {
  return {distance * std::cos(angle), -distance * std::sin(angle)};
}

// The fixed parts of the machine. Built only by validation (src/io/build_scenario.cpp; or by hand in
// tests that know what they do); every field is checked there, so the physics code never re-checks.
// A field an input key sets starts at that key's default (the key table, src/io/keys.cpp, and
// docs/inputs.md), so that a Scenario{} is the machine of an input that gives no key at all (test
// Keys.NoKeysGivenIsScenarioDefault holds them equal).
struct Machine {
  double seesaw_right_arm = 0.6;  // r_H, pivot to rope end [m]
  double lid_half_length = 0.2;   // r_L; the lid is 2 r_L long [m]
  double rope_length = 1.0;       // l_R [m]
  // The lid's hinge H from the pivot [m] (h < 0: below it).
  Vec2 hinge = hinge_from(0.8, 27.0 * units::kRadiansPerDegree);
  double sandbag_mass = 0.6;     // m_S [kg]
  double lid_mass = 0.5;         // m_L [kg]
  double air_density = 1.29;     // [kg/m^3]
  double helium_density = 0.18;  // [kg/m^3]
  double balloon_radius = 0.2;   // r_B [m]
  BalloonModel balloon_model = BalloonModel::program;
  double gravity = 9.81;  // [m/s^2]
  // The radio: its switch (relative to the pivot) and the balloon's string, tied to the switch.
  // The balloon rises from the box's centre, (hinge.x + r_L, hinge.h + balloon height).
  Vec2 radio_switch = switch_at(hinge, lid_half_length, {0.5, 0.0});
  double string_length = 1.0;  // [m]

  // Extensions beyond the paper (docs/extensions.md). Every default is the paper's machine.
  bool radio = false;                     // run on after lid_open until the radio switches on
  double balloon_rubber_mass = 0.0;       // [kg]
  double balloon_drag_coefficient = 0.0;  // Cd of quadratic air drag; 0: no drag
  double pivot_damping = 0.0;             // viscous torque -c phiS' at the pivot [N m s/rad]
  double lid_hinge_damping = 0.0;         // viscous torque -c phiL' at the lid hinge [N m s/rad]
  double seesaw_left_arm = std::numeric_limits<double>::infinity();  // pivot to left end [m]
  double seesaw_mass = 0.0;                                          // [kg]
  double seesaw_inertia = 0.0;     // about the pivot [kg m^2]; > 0 makes the seesaw "heavy"
  double seesaw_com_offset = 0.0;  // centre of mass along the bar, + towards r_H [m]
  double rope_on_lid = 0.0;        // the rope's knot, from the hinge along the lid [m]; 0: the free edge
  // A rope that stretches (docs/impact.md): a one-sided spring-damper; 0 stiffness: inextensible.
  double rope_stiffness = 0.0;  // [N/m]
  double rope_damping = 0.0;    // [N s/m]
  // The built machine (docs/extensions.md "The machine students build").
  bool end_stop = false;           // an edge at the left arm's end: the sandbag rides there
  bool floor = false;              // the floor through the box's bottom: arm ends and sandbag stand on it
  double floor_restitution = 0.0;  // Newton's coefficient of impacts on the floor (0: inelastic)
  double switch_force = 0.0;       // the radio's switch needs the string to pull this hard [N]; 0: any
  // Newton's restitution of each contact's impacts (docs/extensions.md): 0 perfectly inelastic, the
  // paper's; the floor's is floor_restitution.
  struct Restitution {
    double sandbag = 0.0;  // the sandbag landing on the arm
    double rope = 0.0;     // the rope's jerk (the rope law's impact)
    double lid = 0.0;      // the lid landing on the box
    double stop = 0.0;     // the sandbag reaching the end stop
  } restitution;
  // Coulomb friction (docs/extensions.md "Friction"): 0 is the paper's frictionless machine.
  struct Friction {
    double sandbag = 0.0;    // mu between the sandbag and the arm
    double pivot = 0.0;      // Coulomb torque at the seesaw's pivot [N m]
    double lid_hinge = 0.0;  // Coulomb torque at the lid's hinge [N m]
  } friction;

  // The radio's switch, given offset from the box's top right corner.
  static Vec2 switch_at(Vec2 hinge, double lid_half_length, Vec2 offset) {
    return hinge + Vec2{2.0 * lid_half_length, 0.0} + offset;
  }

  // Where the rope is tied to the lid, from the hinge: a = 2 r_L at the free edge (the paper's).
  double rope_knot() const { return rope_on_lid > 0.0 ? rope_on_lid : 2.0 * lid_half_length; }

  // The floor's height relative to the pivot: the box (a cube of edge 2 r_L) stands on it.
  double floor_height() const { return hinge.h - 2.0 * lid_half_length; }
  // What the balloon's string pulls with once straight and holding the balloon still: its net lift.
  double balloon_pull() const { return balloon_inertia() * balloon_acceleration(); }
  bool built_contacts() const { return end_stop || floor; }
  bool stretchy_rope() const { return rope_stiffness > 0.0; }
  bool has_friction() const {
    return friction.sandbag > 0.0 || friction.pivot > 0.0 || friction.lid_hinge > 0.0;
  }

  // Uniform plate hinged at one edge: I = m (2 r_L)^2 / 3.
  double lid_inertia() const { return lid_mass * 4.0 * lid_half_length * lid_half_length / 3.0; }
  // Free balloon's upward acceleration at rest, a_B = net lift / balloon_inertia().
  double balloon_acceleration() const;
  double balloon_volume() const;
  // The mass the net force accelerates (by balloon_model, plus the rubber).
  double balloon_inertia() const;
  // Air drag per unit of balloon_inertia(): a = a_B - drag_rate * v |v|.
  double balloon_drag_rate() const;
  bool heavy_seesaw() const { return seesaw_inertia > 0.0; }
};

// Where everything starts, at the keys' defaults too. The lid and the sandbag start at rest.
struct Start {
  double sandbag_x = -0.3;  // [m], left of the pivot
  double sandbag_h = 1.0;   // [m], above the left arm
  // phiS0 [rad], positive = left arm down; phiL0 [rad], also the lid's lowest angle.
  double seesaw_angle = -25.0 * units::kRadiansPerDegree;
  double lid_angle = 5.0 * units::kRadiansPerDegree;
};

// The tightest tolerance a run is integrated again at, where an event's time is uncertain (a
// piece in simulate(), a machine in a sweep): about where a double's state stops improving.
constexpr double kTightestTolerance = 1e-14;

struct RunSettings {
  IntegratorKind integrator = IntegratorKind::adaptive;
  double step = 1e-3;                   // fixed step for euler/rk4 [s]
  double tolerance = 1e-12;             // adaptive: absolute and relative error per step
  double event_time_tolerance = 1e-12;  // adaptive: events are located to this [s] (not an input key)
  double t_max = 5.0;                   // [s]
  double output_step = 1e-3;            // sampling of CSV/.dat rows [s]
  ImpactLaw impact_law = ImpactLaw::rope;
  double vertical_margin = 0.9 * units::kRadiansPerDegree;  // [rad], pi/200 like the paper
};

struct Scenario {
  Machine machine;
  Start start;
  RunSettings run;
};

}  // namespace whatnext
