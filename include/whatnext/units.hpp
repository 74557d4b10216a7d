// The one place that converts units. SI units and radians inside; degrees only at the edges
// (inputs, CSV, plots, the page), each conversion through these names.
#pragma once

namespace whatnext::units {

constexpr double kPi = 3.14159265358979323846;
constexpr double kDegreesPerRadian = 180.0 / kPi;
constexpr double kRadiansPerDegree = kPi / 180.0;

constexpr double degrees(double radians) { return radians * kDegreesPerRadian; }
constexpr double radians(double degrees) { return degrees * kRadiansPerDegree; }

}  // namespace whatnext::units
