// The events of a run as JSON (--events), with the energy ledger after each.
#include <string>

#include <nlohmann/json.hpp>

#include "finite.hpp"
#include "whatnext/columns.hpp"
#include "whatnext/output.hpp"

namespace whatnext {

using namespace io;

namespace {
// Where the energy is and where it went (docs/extensions.md "Energy ledger").
nlohmann::json ledger(const Snapshot& s) {
  return nlohmann::json{
      {"sandbag_kinetic", clean(s.sandbag_kinetic)},   {"sandbag_potential", clean(s.sandbag_potential)},
      {"seesaw_kinetic", clean(s.seesaw_kinetic)},     {"seesaw_potential", clean(s.seesaw_potential)},
      {"lid_kinetic", clean(s.lid_kinetic)},           {"lid_potential", clean(s.lid_potential)},
      {"balloon_kinetic", clean(s.balloon_kinetic)},   {"balloon_potential", clean(s.balloon_potential)},
      {"lost_impacts", clean(s.lost_impacts)},         {"lost_balloon_catch", clean(s.lost_balloon_catch)},
      {"dissipated_pivot", clean(s.dissipated_pivot)}, {"dissipated_lid_hinge", clean(s.dissipated_hinge)},
      {"dissipated_drag", clean(s.dissipated_drag)},
      {"dissipated_friction", clean(s.dissipated_friction)},   {"lid_push_on_balloon", clean(s.lid_push_work)},
      {"initial_total", clean(s.initial_total)},       {"residual", s.ledger_residual()}};
}
}  // namespace

std::string events_json(const Result& result, const Scenario& sc, const std::string& source) {
  require_finite(result);
  using nlohmann::json;
  auto state = [](const Snapshot& s) {
    return json{{"x", clean(s.x)},
                {"h", clean(s.h)},
                {"r", clean(s.r)},
                {"dr", clean(s.dr)},
                {"phi_s_deg", clean(s.phi_s * units::kDegreesPerRadian)},
                {"dphi_s_deg_per_s", clean(s.dphi_s * units::kDegreesPerRadian)},
                {"phi_l_deg", clean(s.phi_l * units::kDegreesPerRadian)},
                {"dphi_l_deg_per_s", clean(s.dphi_l * units::kDegreesPerRadian)},
                {"balloon_h", clean(s.balloon_h)},
                {"energy", clean(s.energy())}};
  };
  json events = json::array();
  for (const Event& e : result.events) {
    json j{{"type", std::string(to_string(e.type))},
           {"t", e.t},
           {"mode_before", std::string(to_string(e.mode_before))},
           {"mode_after", std::string(to_string(e.mode_after))},
           {"state", state(e.after)}};
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
