// The state's columns: one table of what a sample reports, with its name, unit and meaning, and
// how it follows from a Snapshot. The CSV's header and rows, the Python module's sample arrays
// and the page's columns are all made from it, so that a column is defined exactly once.
#pragma once

#include <cstddef>
#include <string_view>

#include <iterator>

#include "whatnext/params.hpp"
#include "whatnext/state.hpp"
#include "whatnext/units.hpp"

namespace whatnext {

struct StateColumn {
  std::string_view name;             // as in the CSV header and Python: quantity, then unit (phi_l_deg)
  std::string_view unit;             // "m", "deg/s", "J", ...; empty for pure numbers
  std::string_view meaning;          // one line for docs and tooltips
  double (*value)(const Snapshot&);  // in that unit (angles in degrees)
};

// The numeric columns of a sample in the CSV's order. They follow the CSV's four leading columns
// t_s, event, mode and rope_taut (text and flags, kLeadingColumns). A constant table, so that the
// writers' loops over it compile to the plain expressions.
inline constexpr StateColumn kStateColumns[] = {
    {"x_m", "m", "sandbag, horizontal from the pivot", [](const Snapshot& s) { return s.x; }},
    {"h_m", "m", "sandbag, height above the pivot", [](const Snapshot& s) { return s.h; }},
    {"r_m", "m", "sandbag's distance from the pivot", [](const Snapshot& s) { return s.r; }},
    {"dr_m_per_s", "m/s", "its rate", [](const Snapshot& s) { return s.dr; }},
    {"phi_s_deg", "deg", "seesaw angle, + = left arm down",
     [](const Snapshot& s) { return units::degrees(s.phi_s); }},
    {"dphi_s_deg_per_s", "deg/s", "its rate", [](const Snapshot& s) { return units::degrees(s.dphi_s); }},
    {"phi_l_deg", "deg", "lid angle, + = opening", [](const Snapshot& s) { return units::degrees(s.phi_l); }},
    {"dphi_l_deg_per_s", "deg/s", "its rate", [](const Snapshot& s) { return units::degrees(s.dphi_l); }},
    {"balloon_h_m", "m", "balloon centre above the box's top", [](const Snapshot& s) { return s.balloon_h; }},
    {"balloon_v_m_per_s", "m/s", "its rate", [](const Snapshot& s) { return s.balloon_v; }},
    {"balloon_limit_m", "m", "highest the balloon can be under the lid",
     [](const Snapshot& s) { return s.balloon_limit; }},
    {"tension_N", "N", "rope tension (a jerk is an impulse, not a tension)",
     [](const Snapshot& s) { return s.tension; }},
    {"energy_J", "J", "machine energy (potentials zero at the pivot and hinge levels)",
     [](const Snapshot& s) { return s.energy(); }},
    {"sandbag_kinetic_J", "J", "", [](const Snapshot& s) { return s.sandbag_kinetic; }},
    {"sandbag_potential_J", "J", "zero at the pivot's level",
     [](const Snapshot& s) { return s.sandbag_potential; }},
    {"lid_kinetic_J", "J", "", [](const Snapshot& s) { return s.lid_kinetic; }},
    {"lid_potential_J", "J", "zero with the lid horizontal",
     [](const Snapshot& s) { return s.lid_potential; }},
    {"seesaw_kinetic_J", "J", "", [](const Snapshot& s) { return s.seesaw_kinetic; }},
    {"seesaw_potential_J", "J", "", [](const Snapshot& s) { return s.seesaw_potential; }},
    {"balloon_kinetic_J", "J", "", [](const Snapshot& s) { return s.balloon_kinetic; }},
    {"balloon_potential_J", "J", "its net lift as a potential, zero at the box's top",
     [](const Snapshot& s) { return s.balloon_potential; }},
    {"lost_impacts_J", "J", "lost in impacts so far", [](const Snapshot& s) { return s.lost_impacts; }},
    {"lost_balloon_catch_J", "J", "lost when the lid catches the balloon",
     [](const Snapshot& s) { return s.lost_balloon_catch; }},
    {"dissipated_pivot_J", "J", "heat of the pivot's damper",
     [](const Snapshot& s) { return s.dissipated_pivot; }},
    {"dissipated_lid_hinge_J", "J", "heat of the lid hinge's damper",
     [](const Snapshot& s) { return s.dissipated_hinge; }},
    {"dissipated_drag_J", "J", "heat of the balloon's air drag",
     [](const Snapshot& s) { return s.dissipated_drag; }},
    {"dissipated_friction_J", "J", "heat of Coulomb friction (the sandbag on the arm, the pivot, the hinge)",
     [](const Snapshot& s) { return s.dissipated_friction; }},
    {"lid_push_on_balloon_J", "J", "work of the lid on the balloon",
     [](const Snapshot& s) { return s.lid_push_work; }},
    {"ledger_residual_J", "J", "initial energy minus now, lost and dissipated (0 if the books close)",
     [](const Snapshot& s) { return s.ledger_residual(); }},
};

// A column's key in the events JSON (an event's state and ledger): SI quantities by their bare
// name (x, balloon_h, energy, lost_impacts), the others with their unit (phi_s_deg), as docs/inputs.md
// lists them.
inline constexpr std::string_view kSiSuffixes[][2] = {
    {"m", "_m"}, {"m/s", "_m_per_s"}, {"J", "_J"}, {"N", "_N"}};
constexpr std::string_view json_key(const StateColumn& c) {
  for (const auto& [unit, suffix] : kSiSuffixes) {
    if (c.unit == unit && c.name.size() > suffix.size() &&
        c.name.substr(c.name.size() - suffix.size()) == suffix) {
      return c.name.substr(0, c.name.size() - suffix.size());
    }
  }
  return c.name;
}

struct StateColumns {
  const StateColumn* data;
  std::size_t count;
  const StateColumn* begin() const { return data; }
  const StateColumn* end() const { return data + count; }
  std::size_t size() const { return count; }
  const StateColumn& operator[](std::size_t i) const { return data[i]; }
};
StateColumns state_columns();
// The column named `name` (the CSV's name); nullptr if there is none.
constexpr const StateColumn* find_state_column(std::string_view name) {
  for (const StateColumn& c : kStateColumns) {
    if (c.name == name) return &c;
  }
  return nullptr;
}

constexpr std::string_view kLeadingColumns[] = {"t_s", "event", "mode", "rope_taut"};

// After the state's columns, an event row's impacts: each contact's impulse (docs/model.md §7),
// 0 on sample rows and on events without an impact. The paper's machine has the first three
// contacts; the built machine's end stop and floor (docs/extensions.md) add the others, and only
// its outputs have their columns (impulse_columns).
inline constexpr std::string_view kImpulseColumns[] = {
    "impulse_sandbag_N_s", "impulse_rope_N_s",         "impulse_lid_N_m_s",
    "impulse_stop_N_s",    "impulse_floor_seesaw_N_s", "impulse_floor_sandbag_N_s"};
constexpr std::size_t kPaperImpulses = 3;
inline std::size_t impulse_columns(const Machine& m) {
  return m.built_contacts() ? std::size(kImpulseColumns) : kPaperImpulses;
}
// The same per contact i without the prefix: the key in the events JSON, Python and the page.
constexpr std::string_view impulse_key(std::size_t i) { return kImpulseColumns[i].substr(8); }  // "impulse_"

}  // namespace whatnext
