// Machines the tests share: an example with changes, a TOML text with changes, and the seesaw
// that stands on the floor (a fixed incline for the sandbag); and finding an event in a run.
#pragma once

#include <string>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/params.hpp"

namespace whatnext::testing {

// The first event of this type after t = after, or nullptr.
inline const Event* find(const std::vector<Event>& ev, EventType type, double after = -1.0) {
  for (const Event& e : ev)
    if (e.type == type && e.t > after) return &e;
  return nullptr;
}

inline Scenario example(int n, const std::vector<std::string>& sets = {}) {
  Config cfg = example_config(n);
  for (const std::string& s : sets) apply_set(cfg, s);
  return build_scenario(cfg);
}

inline Scenario from_toml(const std::string& text, const std::vector<std::string>& sets = {}) {
  Config cfg = parse_toml(text, "t.toml");
  for (const std::string& s : sets) apply_set(cfg, s);
  return build_scenario(cfg);
}

// A seesaw with mass standing on the floor with its left end: the floor is 0.4 m below the pivot,
// the left arm 0.8 m long, so sin(phiS) = 0.4 / 0.8 and phiS = 30 deg; a uniform board (its centre
// at the pivot), so only the sandbag's weight presses the end onto the floor. `more` is appended.
inline std::string standing_seesaw(const std::string& more = "") {
  return R"(
[geometry]
seesaw_right_arm = 0.8
lid_half_length = 0.12
rope_length = 1.0
hinge_offset = [0.75, 0.16]
[masses]
sandbag = 0.7
lid = 0.1
[seesaw]
left_arm = 0.8
mass = 0.3
[floor]
enabled = true
[start]
seesaw_angle = 30.0
lid_angle = 0.0
[run]
t_max = 1.5
)" + more;
}

}  // namespace whatnext::testing
