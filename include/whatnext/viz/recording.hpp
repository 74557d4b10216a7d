// A run kept in memory for pictures: the output samples and the state right after every event,
// merged in time order, so that plots show every kink and the animation can hold every event.
#pragma once

#include <string>
#include <vector>

#include "whatnext/params.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext::viz {

struct Recording {
  Scenario scenario;
  Result result;
  // Chronological: samples on run.output_step and, at its time, each event's `after` state.
  std::vector<Snapshot> states;
  // For each state: the index of its event in result.events, or -1 for a plain sample.
  std::vector<int> event_index;

  double t_end() const { return result.outcome().t; }
  // The state at time t: continuous quantities interpolated linearly between the recorded states
  // around t; the discrete ones (mode, contacts) from the last recorded state at or before t.
  Snapshot at(double t) const;
};

// Simulates the scenario and keeps everything.
Recording record(const Scenario& scenario);

// Events that happen at the same instant (an impact and the rope going slack at once, say).
struct EventGroup {
  double t = 0.0;
  std::vector<int> events;  // indices into Result::events
  std::string label;        // "0.511 s rope taut (impact) + rope slack + balloon free"
};
std::vector<EventGroup> group_events(const Result& result);

// "rope taut (impact, 5.97 J -> 4.03 J)": an event in words for labels.
std::string event_words(const Event& e, bool with_energy);

// "M3: sandbag on the seesaw, rope slack"; with the built machine's contacts of a state, the words
// that fit it: "M3: sandbag at the stop, seesaw on the floor, rope let go".
std::string mode_words(Mode mode);
std::string mode_words(const Snapshot& s);

}  // namespace whatnext::viz
