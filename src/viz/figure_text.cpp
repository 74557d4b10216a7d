// Measuring PLplot's texts (in DejaVu Sans, through Cairo) and the boxes the figures' layout
// tests against each other and against the data.
#include <cairo.h>

#include <algorithm>
#include <cmath>

#include "figure.hpp"
#include "placement.hpp"

namespace whatnext::viz::figure {

namespace {

// Advance width of UTF-8 text in em of DejaVu Sans.
double text_em(const std::string& text) {
  if (text.empty()) return 0.0;
  static cairo_surface_t* const surface = cairo_image_surface_create(CAIRO_FORMAT_A8, 1, 1);
  static cairo_t* const cr = [] {
    cairo_t* c = cairo_create(surface);
    cairo_select_font_face(c, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(c, 100.0);
    return c;
  }();
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  return ext.x_advance / 100.0;
}

}  // namespace

bool has_subscript(const std::string& s) { return s.find("#d") != std::string::npos; }

// Width [mm] of a PLplot string (with #d/#u escapes) at character height h [mm], a little generous.
double text_width(const std::string& s, double h) {
  double em = 0.0, scale = 1.0;
  int level = 0;
  std::string run;
  auto flush = [&] {
    em += text_em(run) * scale;
    run.clear();
  };
  for (std::size_t i = 0; i < s.size(); ++i) {
    if (s[i] == '#' && i + 1 < s.size()) {
      const char c = s[i + 1];
      if (c == 'd' || c == 'u') {
        flush();
        level += c == 'd' ? -1 : 1;
        scale = std::pow(kSubScale, std::abs(level));
        ++i;
        continue;
      }
      if (c == '#') {
        run += '#';
        ++i;
        continue;
      }
    }
    run += s[i];
  }
  flush();
  return 1.03 * em * kEmPerHeight * h;
}

// plptex puts its reference point half a character height above the baseline. Box of a text at
// reference height y, horizontal position x with justification just (0 left, 0.5 centre, 1 right).
Box text_box(const std::string& s, double x, double y, double just, double h) {
  const double w = text_width(s, h);
  const double below = has_subscript(s) ? 1.4 : 0.85;
  return {x - just * w, y - below * h, x + (1.0 - just) * w, y + 0.55 * h};
}

bool overlap(const Box& a, const Box& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }
bool inside(const Box& in, const Box& out) {
  return in.x0 >= out.x0 && in.x1 <= out.x1 && in.y0 >= out.y0 && in.y1 <= out.y1;
}
Box grow(Box b, double d) { return {b.x0 - d, b.y0 - d, b.x1 + d, b.y1 + d}; }

using Point = std::pair<double, double>;
using Polyline = std::vector<Point>;

bool segment_hits(const Box& b, Point a, Point c) {
  return placement::segment_crosses_box(b.x0, b.y0, b.x1, b.y1, a.first, a.second, c.first, c.second);
}

bool hits_data(const Box& b, const std::vector<Polyline>& data) {
  for (const Polyline& line : data) {
    if (line.size() == 1 && segment_hits(b, line[0], line[0])) return true;
    for (std::size_t i = 1; i < line.size(); ++i) {
      if (segment_hits(b, line[i - 1], line[i])) return true;
    }
  }
  return false;
}

}  // namespace whatnext::viz::figure
