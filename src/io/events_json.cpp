// The events of a run as JSON (--events), with the energy ledger after each.
#include <string>

#include <nlohmann/json.hpp>

#include "finite.hpp"
#include "whatnext/columns.hpp"
#include "whatnext/writers.hpp"

namespace whatnext {

using namespace io;

namespace {
// The columns (columns.hpp, by their CSV names) an event's state shows, and its ledger: where the
// energy is and where it went (docs/extensions.md "Energy ledger"). Each under its json_key.
constexpr std::string_view kStateKeys[] = {"x_m",         "h_m",
                                           "r_m",         "dr_m_per_s",
                                           "phi_s_deg",   "dphi_s_deg_per_s",
                                           "phi_l_deg",   "dphi_l_deg_per_s",
                                           "balloon_h_m", "energy_J"};
constexpr std::string_view kLedgerKeys[] = {
    "sandbag_kinetic_J", "sandbag_potential_J",   "seesaw_kinetic_J",     "seesaw_potential_J",
    "lid_kinetic_J",     "lid_potential_J",       "balloon_kinetic_J",    "balloon_potential_J",
    "lost_impacts_J",    "lost_balloon_catch_J",  "dissipated_pivot_J",   "dissipated_lid_hinge_J",
    "dissipated_drag_J", "dissipated_friction_J", "lid_push_on_balloon_J"};

template <std::size_t N>
nlohmann::json columns_object(const Snapshot& s, const std::string_view (&names)[N]) {
  nlohmann::json j = nlohmann::json::object();
  for (std::string_view name : names) {
    const StateColumn& c = *find_state_column(name);
    j[std::string(json_key(c))] = clean(c.value(s));
  }
  return j;
}
static_assert(
    [] {
      for (std::string_view name : kStateKeys)
        if (!find_state_column(name)) return false;
      for (std::string_view name : kLedgerKeys)
        if (!find_state_column(name)) return false;
      return true;
    }(),
    "a key of the events JSON names no column of columns.hpp");

nlohmann::json ledger(const Snapshot& s) {
  nlohmann::json j = columns_object(s, kLedgerKeys);
  j["initial_total"] = clean(s.initial_total);  // not a column: the CSV has the residual instead
  j["residual"] = s.ledger_residual();
  return j;
}
}  // namespace

std::string events_json(const Result& result, const Scenario& sc, const std::string& source) {
  require_finite(result);
  using nlohmann::json;
  json events = json::array();
  for (const Event& e : result.events) {
    json j{{"type", std::string(to_string(e.type))},
           {"t", e.t},
           {"mode_before", std::string(to_string(e.mode_before))},
           {"mode_after", std::string(to_string(e.mode_after))},
           {"state", columns_object(e.after, kStateKeys)}};
    if (e.impact) {
      j["energy_before"] = clean(e.energy_before);
      j["energy_after"] = clean(e.energy_after);
      // Each contact's impulse (docs/model.md §7) and the law that set the velocities, with the
      // reason where it is not the run's impact_law.
      json impulses = json::object();
      for (std::size_t i = 0; i < impulse_columns(sc.machine); ++i)
        impulses[std::string(impulse_key(i))] = clean(e.impulse[i]);
      j["impulses"] = std::move(impulses);
      j["law_applied"] = std::string(to_string(e.law));
      if (!e.law_note.empty()) j["law_note"] = std::string(e.law_note);
    }
    j["ledger"] = ledger(e.after);
    events.push_back(std::move(j));
  }
  const Event& last = result.outcome();
  json doc{
      {"input", source},
      {"impact_law", std::string(to_string(sc.run.impact_law))},
      {"integrator", std::string(to_string(sc.run.integrator))},
      {"outcome",
       {{"type", std::string(to_string(last.type))}, {"t", last.t}, {"sentence", outcome_sentence(result)}}},
      {"events", std::move(events)}};
  return doc.dump(2) + "\n";
}

}  // namespace whatnext
