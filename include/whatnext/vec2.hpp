#pragma once

#include <cmath>

namespace whatnext {

// A point or vector in the machine's plane: x to the right, h up, origin at the seesaw pivot.
struct Vec2 {
  double x = 0.0;
  double h = 0.0;
};

inline Vec2 operator+(Vec2 a, Vec2 b) { return {a.x + b.x, a.h + b.h}; }
inline Vec2 operator-(Vec2 a, Vec2 b) { return {a.x - b.x, a.h - b.h}; }
inline Vec2 operator*(double s, Vec2 a) { return {s * a.x, s * a.h}; }
inline double dot(Vec2 a, Vec2 b) { return a.x * b.x + a.h * b.h; }
inline double cross(Vec2 a, Vec2 b) { return a.x * b.h - a.h * b.x; }
// Not hypot: several times slower, and the machine's lengths (validated) are far from overflow.
inline double norm(Vec2 a) { return std::sqrt(a.x * a.x + a.h * a.h); }
inline Vec2 polar(double length, double angle) {
  return {length * std::cos(angle), length * std::sin(angle)};
}

}  // namespace whatnext
