#include "whatnext/columns.hpp"

#include <iterator>

#include "whatnext/units.hpp"

namespace whatnext {

namespace {
using units::degrees;
constexpr StateColumn kColumns[] = {
    {"x_m", "m", "sandbag, horizontal from the pivot", [](const Snapshot& s) { return s.x; }},
    {"h_m", "m", "sandbag, height above the pivot", [](const Snapshot& s) { return s.h; }},
    {"r_m", "m", "sandbag's distance from the pivot", [](const Snapshot& s) { return s.r; }},
    {"dr_m_per_s", "m/s", "its rate", [](const Snapshot& s) { return s.dr; }},
    {"phi_s_deg", "deg", "seesaw angle, + = left arm down", [](const Snapshot& s) { return degrees(s.phi_s); }},
    {"dphi_s_deg_per_s", "deg/s", "its rate", [](const Snapshot& s) { return degrees(s.dphi_s); }},
    {"phi_l_deg", "deg", "lid angle, + = opening", [](const Snapshot& s) { return degrees(s.phi_l); }},
    {"dphi_l_deg_per_s", "deg/s", "its rate", [](const Snapshot& s) { return degrees(s.dphi_l); }},
    {"balloon_h_m", "m", "balloon centre above the box's top", [](const Snapshot& s) { return s.balloon_h; }},
    {"balloon_v_m_per_s", "m/s", "its rate", [](const Snapshot& s) { return s.balloon_v; }},
    {"balloon_limit_m", "m", "highest the balloon can be under the lid",
     [](const Snapshot& s) { return s.balloon_limit; }},
    {"tension_N", "N", "rope tension (a jerk is an impulse, not a tension)", [](const Snapshot& s) { return s.tension; }},
    {"energy_J", "J", "machine energy (potentials zero at the pivot and hinge levels)",
     [](const Snapshot& s) { return s.energy(); }},
    {"sandbag_kinetic_J", "J", "", [](const Snapshot& s) { return s.sandbag_kinetic; }},
    {"sandbag_potential_J", "J", "zero at the pivot's level", [](const Snapshot& s) { return s.sandbag_potential; }},
    {"lid_kinetic_J", "J", "", [](const Snapshot& s) { return s.lid_kinetic; }},
    {"lid_potential_J", "J", "zero with the lid horizontal", [](const Snapshot& s) { return s.lid_potential; }},
    {"seesaw_kinetic_J", "J", "", [](const Snapshot& s) { return s.seesaw_kinetic; }},
    {"seesaw_potential_J", "J", "", [](const Snapshot& s) { return s.seesaw_potential; }},
    {"balloon_kinetic_J", "J", "", [](const Snapshot& s) { return s.balloon_kinetic; }},
    {"balloon_potential_J", "J", "its net lift as a potential, zero at the box's top",
     [](const Snapshot& s) { return s.balloon_potential; }},
    {"lost_impacts_J", "J", "lost in impacts so far", [](const Snapshot& s) { return s.lost_impacts; }},
    {"lost_balloon_catch_J", "J", "lost when the lid catches the balloon",
     [](const Snapshot& s) { return s.lost_balloon_catch; }},
    {"dissipated_pivot_J", "J", "heat of the pivot's damper", [](const Snapshot& s) { return s.dissipated_pivot; }},
    {"dissipated_lid_hinge_J", "J", "heat of the lid hinge's damper",
     [](const Snapshot& s) { return s.dissipated_hinge; }},
    {"dissipated_drag_J", "J", "heat of the balloon's air drag", [](const Snapshot& s) { return s.dissipated_drag; }},
    {"lid_push_on_balloon_J", "J", "work of the lid on the balloon", [](const Snapshot& s) { return s.lid_push_work; }},
    {"ledger_residual_J", "J", "initial energy minus now, lost and dissipated (0 if the books close)",
     [](const Snapshot& s) { return s.ledger_residual(); }},
};
}  // namespace

StateColumns state_columns() { return {kColumns, std::size(kColumns)}; }

}  // namespace whatnext
