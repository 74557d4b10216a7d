// The readable outcome and timeline of a run, as `whatnext run` prints them.
#include <algorithm>
#include <array>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "finite.hpp"
#include "whatnext/writers.hpp"

namespace whatnext {

using namespace io;

void require_finite(const Result& result) {
  for (const Event& e : result.events) require_finite(e.after);
}

std::string outcome_sentence(const Result& result) {
  require_finite(result);
  const Event& e = result.outcome();
  const Snapshot& s = e.after;
  switch (e.type) {
    case EventType::lid_open: return fmt::format("lid open at {:.3f} s", e.t);
    case EventType::seesaw_vertical:
      // With the radio the lid may have opened (and latched) before: say so.
      for (const Event& open : result.events) {
        if (open.type == EventType::lid_open) {
          return fmt::format(
              "seesaw vertical at {:.3f} s, after the lid opened at {:.3f} s; the radio is not on", e.t,
              open.t);
        }
      }
      if (!s.on_seesaw) {  // a seesaw with mass that lost its sandbag (no somersaults, docs/model.md §6)
        return fmt::format(
            "seesaw vertical at {:.3f} s without the sandbag (it is {:.4g} m from the pivot); the "
            "lid never opens (it is at {:.1f} deg)",
            e.t, s.r, s.phi_l * units::kDegreesPerRadian);
      }
      return fmt::format(
          "seesaw vertical at {:.3f} s with the sandbag {:.4g} m out; the lid never "
          "opens (it is at {:.1f} deg)",
          e.t, s.r, s.phi_l * units::kDegreesPerRadian);
    case EventType::sandbag_at_pivot:
      return fmt::format(
          "sandbag reaches the pivot at {:.3f} s; the lid has not opened (it is at "
          "{:.1f} deg)",
          e.t, s.phi_l * units::kDegreesPerRadian);
    case EventType::rope_locked:
      // Either the lid or the seesaw's arm has come in line with the straight rope (docs/model.md):
      // the linkage cannot move on; which of the two is not in the result, so the line names both.
      return fmt::format(
          "linkage locked at {:.3f} s: the straight rope is in line with the lid or the seesaw's "
          "arm; the lid is at {:.1f} deg",
          e.t, s.phi_l * units::kDegreesPerRadian);
    case EventType::radio_on: return fmt::format("radio on at t = {:.3f} s", e.t);
    case EventType::switch_stays_off:
      return fmt::format(
          "the balloon's string is straight at {:.3f} s but pulls less than radio.switch_force: the radio "
          "stays off",
          e.t);
    case EventType::timeout:
      // With the radio the lid may have opened (and latched) before: say so, not "no outcome".
      for (const Event& open : result.events) {
        if (open.type == EventType::lid_open) {
          return fmt::format("lid open at {:.3f} s; the radio is not on by t_max = {:.3f} s", open.t, e.t);
        }
      }
      return fmt::format("no outcome by t_max = {:.3f} s: the lid is at {:.1f} deg", e.t,
                         s.phi_l * units::kDegreesPerRadian);
    case EventType::event_limit:
      return fmt::format("stopped after {} events at {:.3f} s", result.events.size(), e.t);
    default: return fmt::format("{} at {:.3f} s", to_string(e.type), e.t);
  }
}

std::string impulse_text(const Event& e) {
  // Each contact's impulse (docs/model.md §7): N s, the lid's a torque's, N m s.
  static constexpr const char* kName[6] = {"sandbag",         "rope", "lid", "stop", "floor on seesaw",
                                           "floor on sandbag"};
  static constexpr const char* kUnit[6] = {"N s", "N s", "N m s", "N s", "N s", "N s"};
  std::string out;
  for (int i = 0; i < 6; ++i) {
    if (e.impulse[i] == 0.0) continue;
    out += fmt::format("{}{} {:.4f} {}", out.empty() ? "" : ", ", kName[i], clean(e.impulse[i]), kUnit[i]);
  }
  return out;
}

namespace {
std::string impact_text(const Event& e, const Scenario& sc) {
  std::string out = fmt::format("energy {:.4f} J -> {:.4f} J", e.energy_before, e.energy_after);
  const std::string impulses = impulse_text(e);
  if (!impulses.empty()) out += "; impulse " + impulses;
  if (!e.law_note.empty())
    out += fmt::format("; not the {} law: {}", to_string(sc.run.impact_law), e.law_note);
  return out;
}
}  // namespace

std::string timeline_text(const Result& result, const Scenario& sc, const std::string& source) {
  // Every cell is formatted first and the columns are as wide as their widest cell, so long event
  // names (sandbag_falls_off) and large values (r = 1929.5922 m) never shift a column.
  std::vector<std::array<std::string, 7>> rows;
  rows.push_back({"t [s]", "event", "mode", "phiS[deg]", "phiL[deg]", "r [m]", ""});
  for (const Event& e : result.events) {
    const Snapshot& s = e.after;
    rows.push_back({fmt::format("{:.6f}", e.t), std::string(to_string(e.type)),
                    e.mode_before == e.mode_after
                        ? std::string(to_string(e.mode_after))
                        : fmt::format("{}>{}", to_string(e.mode_before), to_string(e.mode_after)),
                    fmt::format("{:.3f}", s.phi_s * units::kDegreesPerRadian),
                    fmt::format("{:.3f}", s.phi_l * units::kDegreesPerRadian), fmt::format("{:.4f}", s.r),
                    e.impact ? impact_text(e, sc) : ""});
  }
  std::array<std::size_t, 7> width{12, 16, 7, 9, 9, 9, 0};
  for (const auto& row : rows) {
    for (std::size_t c = 0; c < row.size(); ++c) width[c] = std::max(width[c], row[c].size());
  }
  std::string out = fmt::format("whatnext: {} (impact law {}, integrator {})\n", source,
                                to_string(sc.run.impact_law), to_string(sc.run.integrator));
  for (const auto& row : rows) {
    std::string line =
        fmt::format("{:>{}}  {:<{}} {:<{}} {:>{}} {:>{}} {:>{}}", row[0], width[0], row[1], width[1], row[2],
                    width[2], row[3], width[3], row[4], width[4], row[5], width[5]);
    if (!row[6].empty()) line += "  " + row[6];
    out += line + "\n";
  }
  out += fmt::format("Outcome: {}.\n", outcome_sentence(result));
  return out;
}

}  // namespace whatnext
