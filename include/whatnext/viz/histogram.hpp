// A histogram of one value over many machines as a PNG (PLplot's pngcairo driver): the Monte
// Carlo over tolerances of `whatnext sweep --spread` (docs/explore.md).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace whatnext::viz {

struct HistogramText {
  std::string title;    // above the plot
  std::string x_label;  // the value with its unit
  std::string note;     // below the plot: what is not counted (machines where it never happened)
};

// Draws the values (finite, any order) in bins of equal width, the count on the y axis, with a
// vertical line at `mark` (the machine as designed; NaN: none). Writes path as it draws: give it
// an AtomicFile's temp_path() for a file that appears only when complete. Throws
// std::runtime_error if path cannot be written.
void draw_histogram(const std::string& path, const std::vector<double>& values, double mark,
                    const HistogramText& text);

}  // namespace whatnext::viz
