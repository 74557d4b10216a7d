// The machine's contacts, one row each: what is a fact of the contact itself (its name, whether it
// is friction, the guard that watches it, the events its closing and opening are reported as, the
// restitution of its impacts), read by the contact decision, the jumps and the guards instead of a
// switch per fact. What a contact does in the contact problem (its gap, the gap's gradient in the
// coordinates (x, h, phiS, phiL) and its curvature) depends on the state and stays code:
// contact_problem.cpp (Model::contact_system, built_contacts, friction_contacts), with the
// guards' gaps and forces in guards.cpp. Which contacts the problem has: Constants::contacts.
#pragma once

#include <array>
#include <string_view>

#include "whatnext/events.hpp"
#include "whatnext/params.hpp"

namespace whatnext {

// Guard functions: each fires when its value crosses from negative to >= 0. Inactive guards read
// -infinity. A contact's guard is its gap while it is open (it fires on touching) and minus its
// force while it is closed (it fires when the force would change sign); which contacts change is
// then decided by the contact problem, not by the guard. The order is the priority for events
// found at the same instant.
enum Guard : int {
  kGuardBag,       // sandbag: height above the arm's line, or minus the arm's push on it
  kGuardRope,      // rope: |R - E| - l_R, or minus its tension
  kGuardLid,       // lid: phiL0 - phiL, or minus the box's push on it
  kGuardStop,      // sandbag against the end stop: r - left_arm, or minus the stop's push
  kGuardFloor,     // seesaw's ends: minus the nearer one's height above the floor, or minus its push
  kGuardBagFloor,  // sandbag off the arm: the floor's height minus its own
  // Coulomb friction on the arm: minus the slip's speed while it slips (it fires when the slip
  // stops), or the friction force's excess over mu times the arm's push while it sticks.
  kGuardBagSlip,
  kGuardPivotSlip,  // the same for the seesaw's pivot (a Coulomb torque) ...
  kGuardHingeSlip,  // ... and the lid's hinge
  kGuardArmEnd,     // sandbag on a finite arm reaches its end
  kGuardBalloon,    // free balloon reaches the lid, or the lid pulls away faster than it can follow
  // A balloon smaller than the box (docs/extensions.md): sliding along the lid it reaches the far
  // wall or its top corner; it gets out of the box.
  kGuardBalloonCorner,
  kGuardBalloonEscape,
  kGuardLidOpen,
  kGuardSeesawVertical,
  kGuardAtPivot,
  kGuardRopeLocked,  // the linkage's dead centre: the lid along the rope, or R on the line P-E
  kGuardRadioOn,
  // A rope that stretches, slack but still longer than l_R, reaches l_R: its spring's energy is
  // spent there (no event; the piece ends so that the books' loss, -k s s' until then, is not
  // integrated across its corner).
  kGuardRopeRelaxed,
  kGuardChart,  // on the rope's closure: time to integrate the other angle (no event)
  kGuardCount
};
// The guards that end a smooth piece without an event of their own.
constexpr bool reports_no_event(Guard g) { return g == kGuardRopeRelaxed || g == kGuardChart; }

// The contacts of the contact problem, and its coordinates (x, h of the sandbag, phiS, phiL).
// The built machine adds the end stop, the floor under either end of the seesaw and under the
// sandbag (contacts 3-6, present only when the machine has them); Coulomb friction the sandbag's
// slip along the arm (contact 7, the tangent of contact 0, closed while it sticks) and the
// seesaw's and the lid's turning on their pivot and hinge (8 and 9, bounded by Coulomb torques).
enum ContactIndex : int {
  kBag = 0,
  kRope = 1,
  kLid = 2,
  kStop = 3,
  kFloorLeft = 4,
  kFloorRight = 5,
  kBagFloor = 6,
  kBagSlip = 7,
  kPivotSlip = 8,
  kHingeSlip = 9,
  kContactCount = 10
};

struct ContactRow {
  ContactIndex index;
  std::string_view name;  // what touches what, in the paper's words
  // Friction: the tangent of a normal contact (or a Coulomb torque), closed while it sticks; its
  // multiplier and impulse may have either sign.
  bool friction;
  Guard guard;                            // the guard that watches it (both floor contacts share one)
  EventType closes, opens;                // how its closing and its opening are reported
  double (*restitution)(const Machine&);  // Newton's restitution of its impacts (0: inelastic)
  // Which of an event's impulses (Event::impulse) its impulse adds to: either end of the seesaw
  // on the floor is the floor's impulse on the seesaw; -1: not reported (friction's impulse is
  // in the velocities after).
  int impulse;
};

// Each contact's restitution (its row's last column).
namespace contact_rows {
constexpr double e_none(const Machine&) { return 0.0; }  // friction: no impact of its own
constexpr double e_sandbag(const Machine& m) { return m.restitution.sandbag; }
constexpr double e_rope(const Machine& m) { return m.restitution.rope; }
constexpr double e_lid(const Machine& m) { return m.restitution.lid; }
constexpr double e_stop(const Machine& m) { return m.restitution.stop; }
constexpr double e_floor(const Machine& m) { return m.floor_restitution; }

using ET = EventType;
inline constexpr std::array<ContactRow, kContactCount> kContacts{{
    {kBag, "sandbag on the arm", false, kGuardBag, ET::sandbag_lands, ET::sandbag_leaves, e_sandbag, 0},
    {kRope, "rope straight", false, kGuardRope, ET::rope_taut, ET::rope_slack, e_rope, 1},
    {kLid, "lid on the box", false, kGuardLid, ET::lid_rests, ET::lid_lifts, e_lid, 2},
    {kStop, "sandbag at the end stop", false, kGuardStop, ET::sandbag_at_stop, ET::sandbag_leaves_stop,
     e_stop, 3},
    {kFloorLeft, "seesaw's left end on the floor", false, kGuardFloor, ET::seesaw_on_floor, ET::seesaw_lifts,
     e_floor, 4},
    {kFloorRight, "seesaw's right end on the floor", false, kGuardFloor, ET::seesaw_on_floor,
     ET::seesaw_lifts, e_floor, 4},
    {kBagFloor, "sandbag on the floor", false, kGuardBagFloor, ET::sandbag_on_floor, ET::sandbag_bounces,
     e_floor, 5},
    {kBagSlip, "sandbag sticking on the arm", true, kGuardBagSlip, ET::sandbag_sticks, ET::sandbag_slips,
     e_none, -1},
    {kPivotSlip, "seesaw held by its pivot", true, kGuardPivotSlip, ET::seesaw_sticks, ET::seesaw_slips,
     e_none, -1},
    {kHingeSlip, "lid held by its hinge", true, kGuardHingeSlip, ET::lid_sticks, ET::lid_slips, e_none, -1},
}};
}  // namespace contact_rows
using contact_rows::kContacts;

constexpr bool rows_in_order() {
  for (int i = 0; i < kContactCount; ++i)
    if (kContacts[i].index != i) return false;
  return true;
}
static_assert(rows_in_order(), "kContacts has the row of contact i at i");

constexpr bool is_friction(int contact) { return kContacts[contact].friction; }
constexpr Guard guard_of(int contact) { return kContacts[contact].guard; }
constexpr EventType change_event(int contact, bool closes) {
  return closes ? kContacts[contact].closes : kContacts[contact].opens;
}
// Whether g watches a contact (then a value at zero where a piece starts is a contact that
// touches, decided there, not an event that happens at once).
constexpr bool is_contact_guard(Guard g) {
  for (const ContactRow& c : kContacts)
    if (c.guard == g) return true;
  return false;
}

}  // namespace whatnext
