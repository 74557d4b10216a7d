// Checks shared by the fuzz harnesses: what whatnext promises for any input (docs/inputs.md).
// A broken promise aborts, which libFuzzer reports as a crash with the input that did it.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>

#include "whatnext/config.hpp"

namespace whatnext::fuzz {

[[noreturn]] inline void broken(const char* promise, const std::string& detail) {
  std::fprintf(stderr, "broken promise: %s: %s\n", promise, printable(detail, 300).c_str());
  std::abort();
}

// Bad input is reported in one printable line of sane length.
inline void check_message(const InputError& e) {
  const std::string msg = e.what();
  for (const char c : msg) {
    if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) broken("one printable line", msg);
  }
  if (msg.empty() || msg.size() > 600) broken("a message of sane length", msg);
}

// A machine the validation accepted is written back by to_toml as a file it accepts again, with
// the same numbers.
inline void check_round_trip(const Scenario& a) {
  const std::string text = to_toml(a);
  Scenario b;
  try {
    b = build_scenario(parse_toml(text, "round-trip.toml"));
  } catch (const InputError& e) {
    broken("to_toml writes what build_scenario accepts", std::string(e.what()) + "\n" + text);
  }
  const auto same = [&](double x, double y, const char* what) {
    if (!(x == y || std::fabs(x - y) <= 1e-12 * (std::fabs(x) + std::fabs(y)))) {
      broken("to_toml keeps every number", std::string(what) + "\n" + text);
    }
  };
  same(a.machine.rope_length, b.machine.rope_length, "rope_length");
  same(a.machine.hinge.x, b.machine.hinge.x, "hinge.x");
  same(a.machine.hinge.h, b.machine.hinge.h, "hinge.h");
  same(a.machine.sandbag_mass, b.machine.sandbag_mass, "sandbag");
  same(a.start.seesaw_angle, b.start.seesaw_angle, "seesaw_angle");
  same(a.run.t_max, b.run.t_max, "t_max");
  if (a.run.integrator != b.run.integrator || a.run.impact_law != b.run.impact_law ||
      a.machine.radio != b.machine.radio) {
    broken("to_toml keeps every choice", text);
  }
}

}  // namespace whatnext::fuzz
