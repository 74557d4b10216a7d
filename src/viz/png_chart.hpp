// What the sweep's two PNG charts (heat map, histogram) share: opening a PLplot pngcairo page
// with its colours, filling a box, and a value range that a flat set of values cannot collapse.
#pragma once

#include <string>
#include <vector>

#include <plplot/plplot.h>

namespace whatnext::viz::png_chart {

// Colour map 0 slots: 0 is the white background, 1 the black ink; a chart's own colours follow.
constexpr PLINT kInk = 1, kFirstColour = 2;

struct Rgb {
  int red, green, blue;
};

// A control point of colour map 1 (a continuous ramp), components from 0 to 1.
struct RampPoint {
  PLFLT position, red, green, blue;
};

struct Page {
  PLINT width, height;          // pixels
  std::vector<Rgb> colours;     // slots kFirstColour, kFirstColour + 1, ...
  std::vector<RampPoint> ramp;  // empty: no colour map 1
};

// Throws std::runtime_error naming path unless it can be written: PLplot ends the process when it
// cannot open its file, so this is found out before it is asked to.
void check_writable(const std::string& path);

// Starts PLplot on a PNG page at path and advances to it, with small characters.
void begin(const std::string& path, const Page& page);

// Fills the box [x0, x1] x [y0, y1] (world coordinates) in the current colour and pattern.
void fill_rect(double x0, double x1, double y0, double y1);

// [lo, hi] as an axis can show it: [0, 1] when there is no value, widened a little when it is one
// value (PLplot cannot draw an axis of zero length).
void usable_range(double& lo, double& hi);

}  // namespace whatnext::viz::png_chart
