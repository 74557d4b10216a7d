#pragma once

#include <array>
#include <string_view>

#include "whatnext/params.hpp"

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
  balloon_escapes,    // extensions: a balloon smaller than the box gets past the far wall's top
  sandbag_falls_off,  // extensions: slides off the end of a finite left arm
  sandbag_leaves,     // extensions: the arm's normal force on the sandbag reaches zero (heavy seesaw)
  sandbag_at_stop,    // built machine: the sandbag reaches the end stop and rides there
  sandbag_leaves_stop,
  seesaw_on_floor,   // built machine: an end of the seesaw reaches the floor and stays there
  seesaw_lifts,      // ... and leaves it
  sandbag_on_floor,  // built machine: the sandbag lands on the floor
  sandbag_bounces,   // ... and leaves it again (floor.restitution > 0)
  sandbag_sticks,    // friction: the sandbag stops sliding on the arm and sticks there
  sandbag_slips,     // ... and starts sliding again
  seesaw_sticks,     // friction: the seesaw stops turning and its pivot holds it
  seesaw_slips,      // ... and turns again
  lid_sticks,        // friction: the lid stops turning and its hinge holds it
  lid_slips,         // ... and turns again
  lid_open,
  seesaw_vertical,
  sandbag_at_pivot,
  rope_locked,       // the lid lies along the rope: the linkage cannot move on (not in the paper)
  radio_on,          // extensions: the balloon's string is straight and switches the radio on
  switch_stays_off,  // built machine: the string is straight but pulls less than the switch needs
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
  Snapshot after;  // state right after the event
  // How far t may be off for the integrator's tolerance alone [s] (adaptive runs; 0 where the
  // event is not found on a crossing): a slow crossing is an uncertain one. See Crossing.
  double time_uncertainty = 0.0;
  // Impacts only (impact == true): the impulse each contact gave, from the velocity jump
  // (docs/model.md §7): the arm on the sandbag [N s], the rope [N s], the box on the lid [N m s];
  // the built machine's end stop, the floor on the seesaw's end, the floor on the sandbag [N s]
  // (the order of columns.hpp's kImpulseColumns).
  std::array<double, 6> impulse{};
  // The law that set the velocities after a rope's jerk, and why it is not the run's impact_law
  // where it is not (empty otherwise): a law that cannot be applied is never replaced silently.
  ImpactLaw law = ImpactLaw::rope;
  std::string_view law_note;
};

}  // namespace whatnext
