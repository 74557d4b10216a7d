// A sweep's outcome over two keys as a PNG (PLplot's pngcairo driver). In viz with the other
// pictures, so that the sweeps themselves (whatnext::explore) do not need PLplot.
#pragma once

#include <string>
#include <string_view>

#include "whatnext/explore/sweep.hpp"

namespace whatnext::viz {

// Throws InputError (naming option) unless the plan is a grid over exactly two keys.
void check_heatmap_plan(const explore::Plan& plan, std::string_view option);

// Draws `value` (see value_names()) over the plan's two keys: one cell per machine, coloured by
// the value; machines where it never happened in grey, machines that never open the lid hatched
// (when the value is not lid_open itself), invalid machines and failed runs in black, machines not
// run (an interrupted sweep) left white. Writes path as it draws: give it an AtomicFile's
// temp_path() for a file that appears only when complete.
void draw_heatmap(const std::string& path, const explore::Machines& machines,
                  const explore::SweepResult& result, std::string_view value);

}  // namespace whatnext::viz
