#include <iostream>

#include "whatnext/config.hpp"
#include "whatnext/output.hpp"
#include "whatnext/simulate.hpp"

int main() {
  whatnext::Config cfg = whatnext::example_config(2);  // or load_config_file("m.toml")
  whatnext::set_number(cfg, "geometry.rope_length", 0.7);
  const whatnext::Scenario machine = whatnext::build_scenario(cfg);  // validated; throws InputError
  const whatnext::Result run = whatnext::simulate(machine);          // pass an Observer* for samples
  for (const whatnext::Event& e : run.events) {                      // e.type, e.t, e.after (a Snapshot)
    std::cout << e.t << " s  " << whatnext::to_string(e.type) << "\n";
  }
  std::cout << whatnext::outcome_sentence(run) << "\n";
}
