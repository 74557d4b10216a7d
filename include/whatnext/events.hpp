#pragma once

#include <string_view>

#include "whatnext/state.hpp"

namespace whatnext {

// The event names of docs/model.md §6. The last group ends a run.
enum class EventType {
  sandbag_lands,
  rope_taut,
  rope_slack,
  lid_rests,
  lid_lifts,
  balloon_caught,
  balloon_free,
  sandbag_falls_off,  // extensions: slides off the end of a finite left arm
  sandbag_leaves,     // extensions: the arm's normal force on the sandbag reaches zero (heavy seesaw)
  lid_open,
  seesaw_vertical,
  sandbag_at_pivot,
  rope_locked,  // the lid lies along the rope: the linkage cannot move on (not in the paper)
  radio_on,     // extensions: the balloon's string is straight and switches the radio on
  timeout,
  event_limit,  // safety stop against endless event chains at one instant
};

std::string_view to_string(EventType type);
bool is_stop(EventType type);

struct Event {
  EventType type = EventType::timeout;
  double t = 0.0;
  Mode mode_before = Mode::M1;
  Mode mode_after = Mode::M1;
  bool impact = false;         // velocities jumped under the impact law
  double energy_before = 0.0;  // machine energy just before and after the jump [J]
  double energy_after = 0.0;
  Snapshot after;              // state right after the event
  // How far t may be off for the integrator's tolerance alone [s] (adaptive runs; 0 where the
  // event is not found on a crossing): a slow crossing is an uncertain one. See Crossing.
  double time_uncertainty = 0.0;
};

}  // namespace whatnext
