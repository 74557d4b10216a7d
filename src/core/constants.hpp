// The model's numbers, taken once from the scenario (constants_of, model.cpp): SI units, angles in
// radians. The Model holds one Constants and reads nothing else of the scenario while it runs.
//
// Design: grouped by how hot they are, as Box2D keeps a body's data (body.h): first what the flow
// and the guards read at every step of every machine (the weights, inertias, dampers, the
// balloon's lift and drag, friction and the stretchy rope, and the switches that say which of
// their terms exist), together in a few cache lines; then what only events read (the contact
// decision, the jumps, the ledger). The geometry with a shape (the rope's linkage, the balloon's
// limit) stays in its own classes (geometry.hpp), held by the Model beside this.
#pragma once

#include <array>

#include "contact_table.hpp"
#include "whatnext/params.hpp"
#include "whatnext/vec2.hpp"

namespace whatnext {

struct Constants {
  // --- hot: the flow and the guards, every step ---
  double g;             // [m/s^2] gravity
  double m_s;           // [kg] the sandbag
  double m_l;           // [kg] the lid
  double i_l;           // [kg m^2] the lid about its hinge
  double r_l;           // [m] the lid's half length (its centre of mass from the hinge)
  double i_s;           // [kg m^2] the seesaw about its pivot (0: the paper's massless seesaw)
  double w_s;           // [kg m] the seesaw's mass times its centre of mass's offset along the arm
  double c_p;           // [N m s] the pivot's damper
  double c_l;           // [N m s] the lid hinge's damper
  double a_b;           // [m/s^2] the balloon's net upward acceleration at rest
  double drag;          // [1/m] the balloon's quadratic air drag: a = a_b - drag v |v|
  double phi_l0;        // [rad] the lid's angle resting on the box
  double cos_vertical;  // cos of `vertical` (the seesaw's vertical guard reads cos phiS alone)
  double mu;            // [1] Coulomb friction of the sandbag on the arm (0: none)
  double t_p, t_h;      // [N m] Coulomb torques of the pivot and the lid's hinge (0: none)
  double k_rope;        // [N/m] a stretchy rope's stiffness (0: the rope does not stretch)
  double c_rope;        // [N s/m] its damper
  bool heavy;           // the seesaw has inertia (i_s > 0)
  bool small;           // the balloon is smaller than the box (its radius < r_l): it moves in the plane
  bool radio;           // the radio switch closes the story
  bool friction;        // some Coulomb friction (mu, t_p or t_h)
  bool stretchy;        // the rope stretches (k_rope > 0)
  bool pulls_heavy;     // a stretchy rope on a seesaw with inertia (its pull joins the swings)
  bool built;           // an end stop or a floor (contacts 3-6)
  int contacts;         // how many contacts the contact problem has (3 without stop, floor, friction)

  // --- warm: the events (contact decision, jumps, ledger) ---
  double vertical;      // [rad] |phiS| beyond which the seesaw has swung too far (pi/2 less a margin)
  double arm;           // [m] the seesaw's left arm (infinite: the paper's endless arm)
  double m_b;           // [kg] the balloon's inertia in its motion (with added mass, by balloon model)
  Vec2 radio_switch;    // [m] where the radio's switch is, from the hinge
  double string;        // [m] the balloon's string
  double balloon_x;     // [m] the paper's balloon's centre's x from the pivot: hinge.x + r_l
  double length_scale;  // [m] the machine's size, for the contact problem's tolerances
  bool stop, floor;     // the built machine's end stop and floor
  double h_floor;       // [m] the floor's height from the pivot
  // [rad] the seesaw's angle with its left or right end on the floor (NaN: that arm cannot reach it)
  double grounded_left, grounded_right;
  std::array<double, kContactCount> e;  // [1] Newton's restitution per contact (kContacts; 0: inelastic)
  bool restitution;                     // some contact has a restitution above 0
};

Constants constants_of(const Scenario& scenario);

}  // namespace whatnext
