// Figures with PLplot (C API): PNG and PDF through its Cairo drivers, SVG through its svg driver,
// which writes text as <text> (Cairo's SVG surface turns every glyph into an outline).
//
// Every page is laid out first, in millimetres, and then drawn from that layout in each format.
// Legends, event numbers and the event key sit outside the axes; the few texts inside the axes
// (event numbers on the trajectory, the 90° line's name) are placed by a collision test against
// the curves and the other texts. Text widths are measured with Cairo in DejaVu Sans, the font
// PLplot's drivers use here.
#include "whatnext/units.hpp"
#include "whatnext/viz/plots.hpp"

#include <cairo.h>
#include <plplot/plplot.h>

#include <algorithm>
#include <array>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <optional>
#include <sstream>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/output.hpp"
#include "placement.hpp"

namespace whatnext::viz {

namespace fs = std::filesystem;

namespace {

constexpr double kMmPerPt = 25.4 / 72.0;  // the Cairo drivers map one pixel to one point

// Colour map 0 (PLplot's indexed colours).
enum Colour : int {
  kWhite,
  kBlack,
  kGrey,
  kBlue,
  kOrange,
  kGreen,
  kRed,
  kPurple,
  kBrown,
  kLightGrey,
  kModeFirst,  // five pastel colours for M1..M5
  kColourCount = kModeFirst + 5
};
constexpr std::array<std::array<int, 3>, kColourCount> kPalette{{
    {255, 255, 255},
    {0, 0, 0},
    {110, 110, 110},
    {31, 119, 180},
    {230, 120, 20},
    {44, 160, 44},
    {214, 39, 40},
    {148, 103, 189},
    {140, 86, 75},
    {215, 215, 215},
    {255, 236, 179},
    {255, 205, 210},
    {200, 230, 201},
    {187, 222, 251},
    {225, 200, 240},
}};

struct Curve {
  std::vector<double> x, y;
  std::string label;
  int colour = kBlack;
  int style = 1;  // PLplot line style: 1 solid, 2 and up dashed
  double width = 2.0;
  bool dots = false;  // point markers (no line)
};

struct Mark {  // a numbered point (events on the trajectory)
  double x, y;
  int number;
};

struct ModeSpan {
  double t0, t1;
  Mode mode;
};

struct Panel {
  std::string title, xlabel, ylabel;
  std::vector<Curve> curves;
  std::vector<Mark> marks;
  std::vector<EventGroup> events;                      // vertical lines on a time axis, numbered 1, 2, ...
  std::vector<ModeSpan> modes;                         // strip above the plot
  std::vector<std::pair<double, std::string>> hlines;  // reference levels
  double x0 = 0.0, x1 = 1.0;
  bool fixed_x = false;
  bool to_scale = false;           // same metres per millimetre on both axes, or say in the title
  bool show_legend = true;         // false: another panel of the page shows the same legend
  std::size_t legend_columns = 0;  // 0: as many as fit
};

// A page: panels in a grid and, under them, the key to the numbered events.
struct Page {
  std::string name;
  int width = 1000, height = 650;  // pixels of the PNG (points of SVG and PDF)
  int nx = 1, ny = 1;
  double text_scale = 1.0;
  std::vector<Panel> panels;
  std::vector<EventGroup> key;
};

// ---- text measurement ----

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

// PLplot's character height h [mm] is 3/4 of the font size; #d and #u shift to 3/4 size.
constexpr double kEmPerHeight = 1.0 / 0.75;
constexpr double kSubScale = 0.75;

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

// ---- layout ----

struct Text {
  PlacedText::Kind kind;
  std::string text;
  double x, y, just, h;  // reference point [mm], justification, character height [mm]
  int colour = kBlack;
  Box box;
};
Text make_text(PlacedText::Kind kind, std::string s, double x, double y, double just, double h,
               int colour = kBlack) {
  Text t{kind, std::move(s), x, y, just, h, colour, {}};
  t.box = text_box(t.text, x, y, just, h);
  return t;
}

struct Segment {
  double x0, y0, x1, y1;
  int colour;
  int style;
  double width;
};

struct PanelGeometry {
  Box axes, strip;
  double wx0 = 0, wx1 = 1, wy0 = 0, wy1 = 1;  // the data window
  std::vector<Text> texts;
  std::vector<Segment> strokes;  // legend samples and leader lines, in mm
  std::vector<Box> samples;
  std::vector<Polyline> data;    // curves and dots in mm
  std::vector<Box> reserved;     // tick numbers and axis titles
  double h = 1.0;                // base character height [mm]
  double bands = 0.0;            // height of the bands above the axes [mm]
  double ylabel_h = 1.0;         // character height of the y axis' title [mm]
  double ytick = 0.0;            // spacing of the y axis' numbered ticks (data units)
  double ylabel_at = 0.0;        // the y axis' title: its reference point left of the axes [mm]
  double left_needed = 0.0;      // room the tick numbers and the y title need left of the axes [mm]
  std::vector<Text> axis_texts;  // where PLplot will write the y tick numbers and the y title
  double title_h = 0.0;          // the title's character height [mm] (shrunk to fit the panel)
};

struct PageGeometry {
  double w = 0, h = 0, ch = 1.0;  // page [mm], base character height [mm]
  std::vector<PanelGeometry> panels;
  std::vector<Text> texts;
};

void data_range(const Panel& p, bool along_x, double& lo, double& hi) {
  lo = std::numeric_limits<double>::infinity();
  hi = -lo;
  for (const Curve& c : p.curves) {
    for (double v : along_x ? c.x : c.y) {
      if (std::isfinite(v)) lo = std::min(lo, v), hi = std::max(hi, v);
    }
  }
  for (const Mark& m : p.marks) {
    const double v = along_x ? m.x : m.y;
    lo = std::min(lo, v), hi = std::max(hi, v);
  }
  if (!along_x) {
    for (const auto& l : p.hlines) lo = std::min(lo, l.first), hi = std::max(hi, l.first);
  }
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-9 * std::max(1.0, std::fabs(hi))) lo -= 0.5, hi += 0.5;
}

// Entries of the given widths in a table as wide as fits between x0 and x1: row by row, in as many
// columns as fit (each column as wide as its widest entry).
struct Grid {
  std::vector<std::vector<std::size_t>> rows;
  std::vector<double> column_x;  // left edge of each column
  double x(std::size_t i) const { return column_x[i % column_x.size()]; }
};
Grid grid(const std::vector<double>& widths, double x0, double x1, double spacing,
          std::size_t max_columns = 0) {
  Grid g;
  const std::size_t n = widths.size();
  if (n == 0) return g;
  for (std::size_t k = max_columns ? std::min(n, max_columns) : n; k >= 1; --k) {
    std::vector<double> col(k, 0.0);
    for (std::size_t i = 0; i < n; ++i) col[i % k] = std::max(col[i % k], widths[i]);
    double total = spacing * static_cast<double>(k - 1);
    for (double c : col) total += c;
    if (total <= x1 - x0 || k == 1) {
      double x = x0;
      for (double c : col) g.column_x.push_back(x), x += c + spacing;
      for (std::size_t i = 0; i < n; ++i) {
        if (i % k == 0) g.rows.emplace_back();
        g.rows.back().push_back(i);
      }
      return g;
    }
  }
  return g;
}

// PLplot's own choice of the spacing of numbered ticks over [lo, hi] (pldtik, not exported): 1, 2
// or 5 times a power of ten, three to eight ticks. The axes are drawn with this spacing, so the
// numbers are the ones measured here.
double tick_spacing(double lo, double hi) {
  const double span = std::fabs(hi - lo);
  if (!(span > 0.0) || !std::isfinite(span)) return 1.0;
  double t1 = std::log10(span);
  int np = static_cast<int>(std::floor(t1));
  t1 -= np;
  double t2 = 2.0;
  if (t1 > 0.7781512503) {
    t2 = 2.0;
  } else if (t1 > 0.4771212549) {
    t2 = 1.0;
  } else if (t1 > 0.1760912591) {
    t2 = 5.0, np -= 1;
  } else {
    t2 = 2.0, np -= 1;
  }
  return t2 * std::pow(10.0, np);
}

// The numbers PLplot writes at the ticks of [lo, hi] (fixed point with as many decimals as the
// spacing needs, as plsyax(12, 0) asks: pldprec's mode 0).
std::vector<std::pair<double, std::string>> tick_numbers(double lo, double hi, double tick) {
  std::vector<std::pair<double, std::string>> out;
  if (!(tick > 0.0)) return out;
  const int prec = std::max(0, -static_cast<int>(std::floor(std::log10(tick))));
  const double first = std::ceil(std::min(lo, hi) / tick - 1e-6);
  for (int k = 0; k < 100; ++k) {
    double v = (first + k) * tick;
    if (v > std::max(lo, hi) + 1e-6 * tick) break;
    if (std::fabs(v) < 1e-6 * tick) v = 0.0;  // no "-0.0"
    out.emplace_back(v, fmt::format("{:.{}f}", v, prec));
  }
  return out;
}

// The panel in rect r with base character height ch; the bands above the axes (title, legend, mode
// strip, event numbers) take at least min_bands, so that panels side by side line up.
// `left` is the room left of the axes for the tick numbers and the y axis' title (at least 6 ch;
// layout_page widens it to what the panels of a column need, g.left_needed).
// `title_cap` (if > 0) is the largest title height, so that the panels of a page share one.
PanelGeometry layout_panel(const Panel& p, const Box& r, double ch, double min_bands = 0.0, double left = 0.0,
                           double title_cap = 0.0) {
  PanelGeometry g;
  g.h = ch;
  const double pad = 0.5 * ch;
  g.axes.x0 = r.x0 + std::max(6.0 * ch, left);
  g.axes.x1 = r.x1 - 1.5 * ch;
  g.axes.y0 = r.y0 + 4.4 * ch;
  const double aw = g.axes.x1 - g.axes.x0;
  double y = r.y1 - 0.8 * ch;

  // Title, shrunk to the panel's width if need be (the scale note is added below, when known).
  std::string title = p.title;
  double wx0, wx1, wy0, wy1;
  if (p.fixed_x) {
    wx0 = p.x0, wx1 = p.x1;
  } else {
    data_range(p, true, wx0, wx1);
    const double pad_x = 0.04 * (wx1 - wx0);
    wx0 -= pad_x, wx1 += pad_x;
  }
  data_range(p, false, wy0, wy1);
  const double pad_y = 0.06 * (wy1 - wy0);
  wy0 -= pad_y, wy1 += pad_y;

  // Heights of the bands above the axes, to know the axes' height for the scale note.
  std::vector<const Curve*> entries;
  if (p.show_legend) {
    for (const Curve& c : p.curves) {
      if (!c.label.empty()) entries.push_back(&c);
    }
  }
  const double title_h = 1.1 * ch;
  double legend_h = 0.8 * ch;
  const double sample = 2.2 * ch, sample_gap = 0.6 * ch, entry_gap = 1.6 * ch;
  std::vector<double> entry_w;
  auto measure_entries = [&] {
    entry_w.clear();
    for (const Curve* c : entries) entry_w.push_back(sample + sample_gap + text_width(c->label, legend_h));
  };
  measure_entries();
  const double widest = entry_w.empty() ? 0.0 : *std::max_element(entry_w.begin(), entry_w.end());
  if (widest > aw) {
    legend_h *= aw / widest;
    measure_entries();
  }
  const Grid legend = grid(entry_w, g.axes.x0, g.axes.x1, entry_gap, p.legend_columns);
  const auto& legend_lines = legend.rows;
  bool legend_sub = false;
  for (const Curve* c : entries) legend_sub = legend_sub || has_subscript(c->label);
  const double legend_line = (legend_sub ? 2.0 : 1.7) * legend_h;

  const double tag_h = 0.75 * ch;
  const double tag_row = 1.5 * tag_h, leader = 0.8 * ch;
  // Event numbers: one row if they fit, otherwise alternate between more rows.
  std::vector<double> tag_w;
  for (std::size_t i = 0; i < p.events.size(); ++i) {
    tag_w.push_back(text_width(std::to_string(i + 1), tag_h));
  }
  int tag_rows = p.events.empty() ? 0 : 1;
  std::vector<std::vector<double>> tag_pos;  // per row
  std::vector<std::vector<std::size_t>> tag_members;
  const double tag_lo = g.axes.x0, tag_hi = g.axes.x1 + 1.2 * ch;
  auto tag_centre = [&](double t) { return g.axes.x0 + (t - wx0) / (wx1 - wx0) * aw; };
  for (; tag_rows > 0 && tag_rows <= 6; ++tag_rows) {
    tag_pos.assign(tag_rows, {});
    tag_members.assign(tag_rows, {});
    bool ok = true;
    for (int row = 0; row < tag_rows && ok; ++row) {
      std::vector<double> c, w;
      for (std::size_t i = row; i < p.events.size(); i += tag_rows) {
        c.push_back(tag_centre(p.events[i].t));
        w.push_back(tag_w[i]);
        tag_members[row].push_back(i);
      }
      ok = placement::pack_row(c, w, tag_lo, tag_hi, 0.5 * tag_h, tag_pos[row]);
    }
    if (ok) break;
  }
  tag_rows = std::min(tag_rows, 6);

  const double tag_band = tag_rows ? tag_rows * tag_row + leader : 0.3 * ch;
  g.bands = 0.8 * ch + title_h * 1.45 + 0.3 * ch +
            (legend_lines.empty() ? 0.0 : legend_lines.size() * legend_line + 0.3 * ch) +
            (p.modes.empty() ? 0.0 : 1.25 * ch) + tag_band;
  g.axes.y1 = r.y1 - std::max(g.bands, min_bands);
  const double ah = g.axes.y1 - g.axes.y0;

  if (p.to_scale) {
    // Same data units per millimetre on both axes, as long as that leaves a readable plot;
    // otherwise the title says how much one axis is stretched.
    const double sx = (wx1 - wx0) / aw, sy = (wy1 - wy0) / ah;
    const double stretch = std::max(sx, sy) / std::min(sx, sy);
    if (stretch <= 8.0) {
      if (sx > sy) {
        const double c = 0.5 * (wy0 + wy1), half = 0.5 * sx * ah;
        wy0 = c - half, wy1 = c + half;
      } else {
        const double c = 0.5 * (wx0 + wx1), half = 0.5 * sy * aw;
        wx0 = c - half, wx1 = c + half;
      }
      title += " (to scale)";
    } else {
      title += fmt::format(" (not to scale: {} stretched {:.0f}×)", sx > sy ? "h" : "x", stretch);
    }
  }
  // Room above the highest reference level for its name.
  const double line_h = 0.7 * ch;
  for (const auto& l : p.hlines) {
    const double k = (1.6 * line_h + 0.7 * ch) / ah;
    if (wy1 - l.first < k * (wy1 - wy0)) wy1 = (l.first - k * wy0) / (1.0 - k);
  }
  g.wx0 = wx0, g.wx1 = wx1, g.wy0 = wy0, g.wy1 = wy1;

  // Title.
  double th = title_cap > 0.0 ? std::min(title_h, title_cap) : title_h;
  const double tw = text_width(title, th);
  if (tw > r.x1 - r.x0 - 2.0 * pad) th *= (r.x1 - r.x0 - 2.0 * pad) / tw;
  g.title_h = th;
  y -= 0.55 * title_h;
  const double title_x = std::clamp(0.5 * (g.axes.x0 + g.axes.x1), r.x0 + pad + 0.5 * text_width(title, th),
                                    r.x1 - pad - 0.5 * text_width(title, th));
  g.texts.push_back(make_text(PlacedText::title, title, title_x, y, 0.5, th));
  y -= 0.9 * title_h + 0.3 * ch;

  // Legend rows, left-aligned with the axes.
  for (const auto& line : legend_lines) {
    const double ty = y - 0.55 * legend_h;
    for (std::size_t i : line) {
      const double x = legend.x(i);
      const Curve& c = *entries[i];
      const Box sb{x, ty - 0.35 * legend_h, x + sample, ty + 0.35 * legend_h};
      if (c.dots) {
        g.strokes.push_back({x + 0.5 * sample, ty, x + 0.5 * sample, ty, c.colour, 0, c.width});
      } else {
        g.strokes.push_back({x, ty, x + sample, ty, c.colour, c.style, c.width});
      }
      g.samples.push_back(sb);
      g.texts.push_back(make_text(PlacedText::legend, c.label, x + sample + sample_gap, ty, 0.0, legend_h));
    }
    y -= legend_line;
  }
  if (!legend_lines.empty()) y -= 0.3 * ch;

  if (!p.modes.empty()) {
    g.strip = {g.axes.x0, g.axes.y1 + tag_band, g.axes.x1, g.axes.y1 + tag_band + 1.0 * ch};
  }

  // Event numbers above the axes, with a leader down to the event's line where they had to move.
  for (int row = 0; row < tag_rows; ++row) {
    const double ty = g.axes.y1 + leader + (row + 0.5) * tag_row;
    for (std::size_t k = 0; k < tag_members[row].size(); ++k) {
      const std::size_t i = tag_members[row][k];
      const double cx = tag_centre(p.events[i].t), tx = tag_pos[row][k];
      Text t = make_text(PlacedText::event_number, std::to_string(i + 1), tx, ty, 0.5, tag_h);
      g.strokes.push_back({cx, g.axes.y1, tx, t.box.y0 - 0.1 * ch, kGrey, 1, 0.8});
      g.texts.push_back(std::move(t));
    }
  }

  // The y axis' title, smaller if it is longer than the axes are high, and clear of the widest
  // tick number: PLplot writes those 0.5 ch left of the axes, right-aligned; the title, turned
  // upright, reaches 0.85 of its height (1.4 with a subscript) from its reference point towards
  // the axes and 0.55 away from them.
  g.ylabel_h = std::min(ch, ch * 0.97 * (g.axes.y1 - g.axes.y0) / std::max(1e-9, text_width(p.ylabel, ch)));
  g.ytick = tick_spacing(wy0, wy1);
  double widest_tick = 0.0;
  const auto numbers = tick_numbers(wy0, wy1, g.ytick);
  for (const auto& n : numbers) widest_tick = std::max(widest_tick, text_width(n.second, ch));
  const double inward = (has_subscript(p.ylabel) ? 1.4 : 0.85) * g.ylabel_h;
  g.ylabel_at = std::max(4.6 * ch, 0.5 * ch + widest_tick + 0.4 * ch + inward);
  g.left_needed = g.ylabel_at + 0.55 * g.ylabel_h + 0.4 * ch;
  for (const auto& [v, text] : numbers) {
    const double y = g.axes.y0 + (v - wy0) / (wy1 - wy0) * (g.axes.y1 - g.axes.y0);
    g.axis_texts.push_back(make_text(PlacedText::label, text, g.axes.x0 - 0.5 * ch, y, 1.0, ch));
  }
  {
    // The title turned upright: its box is a text box turned by 90 degrees.
    const double half = 0.5 * text_width(p.ylabel, g.ylabel_h), x = g.axes.x0 - g.ylabel_at;
    const double ym = 0.5 * (g.axes.y0 + g.axes.y1);
    Text t = make_text(PlacedText::label, p.ylabel, x, ym, 0.5, g.ylabel_h);
    t.box = {x - 0.55 * g.ylabel_h, ym - half, x + inward, ym + half};
    g.axis_texts.push_back(std::move(t));
  }

  // Where PLplot writes tick numbers and axis titles.
  g.reserved.push_back({r.x0, g.axes.y0 - 0.6 * ch, g.axes.x0, g.axes.y1 + 0.6 * ch});
  g.reserved.push_back({g.axes.x0 - 2.0 * ch, r.y0, g.axes.x1 + 2.0 * ch, g.axes.y0});

  // Data in millimetres, for the collision tests and the layout's users.
  auto to_mm = [&](double x, double yv) {
    return Point{g.axes.x0 + (x - wx0) / (wx1 - wx0) * aw, g.axes.y0 + (yv - wy0) / (wy1 - wy0) * ah};
  };
  for (const Curve& c : p.curves) {
    if (c.dots) {
      for (std::size_t i = 0; i < c.x.size(); ++i) g.data.push_back({to_mm(c.x[i], c.y[i])});
      continue;
    }
    Polyline line;
    for (std::size_t i = 0; i < c.x.size(); ++i) line.push_back(to_mm(c.x[i], c.y[i]));
    g.data.push_back(std::move(line));
  }
  for (const Mark& m : p.marks) g.data.push_back({to_mm(m.x, m.y)});
  std::vector<Polyline> obstacles = g.data;
  const std::vector<Polyline> curves_only = g.data;
  for (const EventGroup& e : p.events) {
    obstacles.push_back({to_mm(e.t, wy0), to_mm(e.t, wy1)});
  }
  auto free_spot = [&](const Box& b, const std::vector<Polyline>& avoid) {
    if (!inside(b, grow(g.axes, -0.6 * ch))) return false;  // clear of the tick marks
    if (hits_data(grow(b, 0.15 * ch), avoid)) return false;
    for (const Text& t : g.texts) {
      if (overlap(grow(b, 0.15 * ch), t.box)) return false;
    }
    return true;
  };

  // Numbers of the events on the trajectory: near their dot, away from the curves and each other.
  const double mark_h = 0.8 * ch;
  for (const Mark& m : p.marks) {
    const Point at = to_mm(m.x, m.y);
    const std::string s = std::to_string(m.number);
    const double w = text_width(s, mark_h);
    bool placed = false;
    for (int ring = 1; ring <= 8 && !placed; ++ring) {
      const double d = 0.5 * ch + (ring - 1) * 1.1 * ch;
      for (int k = 0; k < 16 && !placed; ++k) {
        if (ring == 1 && k % 2) continue;  // the first ring: 8 directions
        const double a = k * 3.14159265358979323846 / 8.0;
        const double ux = std::cos(a), uy = std::sin(a);
        const double cx = at.first + ux * (d + 0.5 * w), cy = at.second + uy * (d + 0.6 * mark_h);
        Text t = make_text(PlacedText::event_number, s, cx, cy + 0.15 * mark_h, 0.5, mark_h);
        if (!free_spot(t.box, obstacles)) continue;
        if (ring > 1) {
          // The leader must not cross a curve either.
          const Point end{std::clamp(at.first, t.box.x0, t.box.x1),
                          std::clamp(at.second, t.box.y0, t.box.y1)};
          const Point from{at.first + 0.35 * ch * ux, at.second + 0.35 * ch * uy};
          bool crosses = false;
          for (const Polyline& line : curves_only) {
            if (line.size() == 1) continue;
            for (std::size_t i = 1; i < line.size() && !crosses; ++i) {
              const double d1x = end.first - from.first, d1y = end.second - from.second;
              const double d2x = line[i].first - line[i - 1].first, d2y = line[i].second - line[i - 1].second;
              const double den = d1x * d2y - d1y * d2x;
              if (den == 0.0) continue;
              const double ex = line[i - 1].first - from.first, ey = line[i - 1].second - from.second;
              const double s1 = (ex * d2y - ey * d2x) / den, s2 = (ex * d1y - ey * d1x) / den;
              crosses = s1 > 0.0 && s1 < 1.0 && s2 >= 0.0 && s2 <= 1.0;
            }
          }
          if (crosses) continue;
          g.strokes.push_back({from.first, from.second, end.first, end.second, kGrey, 1, 0.8});
        }
        g.texts.push_back(std::move(t));
        placed = true;
      }
    }
  }

  // Names of reference levels: on a free stretch of their line (crossing an event line if needed).
  for (const auto& [level, name] : p.hlines) {
    const Point at = to_mm(wx0, level);
    bool placed = false;
    for (int pass = 0; pass < 2 && !placed; ++pass) {
      const std::vector<Polyline>& avoid = pass == 0 ? obstacles : curves_only;
      for (double fx : {0.0, 1.0, 0.25, 0.5, 0.75}) {
        for (double side : {1.0, -1.0}) {
          const double just = fx == 1.0 ? 1.0 : fx == 0.0 ? 0.0 : 0.5;
          const double x = g.axes.x0 + 0.8 * ch + fx * (aw - 1.6 * ch);
          const double ty = at.second + (side > 0 ? 0.95 * line_h : -0.65 * line_h);
          Text t = make_text(PlacedText::label, name, x, ty, just, line_h, kGrey);
          if (!free_spot(t.box, avoid)) continue;
          g.texts.push_back(std::move(t));
          placed = true;
          break;
        }
        if (placed) break;
      }
    }
  }
  return g;
}

PageGeometry layout_page(const Page& page) {
  PageGeometry pg;
  pg.w = page.width * kMmPerPt;
  pg.h = page.height * kMmPerPt;
  // PLplot's default for a 1000 x 650 page, scaled with the size of one panel.
  pg.ch = 5.82 * std::sqrt(page.width * static_cast<double>(page.height) / (page.nx * page.ny) / 650000.0) *
          page.text_scale;
  const double ch = pg.ch;

  // The key to the event numbers, under everything; shrunk if it would take too much room.
  double key_top = 0.0;
  if (!page.key.empty()) {
    std::vector<std::string> items;
    for (std::size_t i = 0; i < page.key.size(); ++i) {
      items.push_back(fmt::format("{}: {}", i + 1, page.key[i].label));
    }
    const double x0 = 1.2 * ch, x1 = pg.w - 1.2 * ch;
    double kh = 0.8 * ch;
    Grid key;
    std::vector<double> widths;
    for (int attempt = 0; attempt < 8; ++attempt) {
      widths.clear();
      for (const std::string& s : items) widths.push_back(std::min(text_width(s, kh), x1 - x0));
      key = grid(widths, x0, x1, 2.0 * kh);
      if (key.rows.size() * 1.7 * kh <= 0.3 * pg.h || kh < 0.5 * ch) break;
      kh *= 0.85;
    }
    const double line_h = 1.7 * kh;
    double y = 0.6 * ch + (key.rows.size() - 1) * line_h + 0.85 * kh;
    key_top = y + 0.55 * kh + 0.6 * ch;
    for (const auto& line : key.rows) {
      for (std::size_t i : line)
        pg.texts.push_back(make_text(PlacedText::key, items[i], key.x(i), y, 0.0, kh));
      y -= line_h;
    }
  }
  const double cell_w = pg.w / page.nx, cell_h = (pg.h - key_top) / page.ny;
  auto cell = [&](std::size_t i) {
    const int col = static_cast<int>(i) % page.nx, row = static_cast<int>(i) / page.nx;
    return Box{col * cell_w, pg.h - (row + 1) * cell_h, (col + 1) * cell_w, pg.h - row * cell_h};
  };
  // Panels side by side share the height of their bands, panels above each other the room left of
  // their axes (so that their axes line up); that room is what the widest tick numbers and the y
  // title need. The data window can change with the room (a trajectory to scale), hence the rounds.
  // Titles share one size, the smallest any of them needs to fit its panel (a long input name
  // shrinks one title; the page's titles should not then differ in size).
  std::vector<double> row_bands(page.ny, 0.0), col_left(page.nx, 0.0);
  double title_cap = 0.0;
  for (int round = 0; round < 4; ++round) {
    std::vector<double> bands(page.ny, 0.0), left = col_left;
    pg.panels.clear();
    for (std::size_t i = 0; i < page.panels.size(); ++i) {
      pg.panels.push_back(layout_panel(page.panels[i], cell(i), ch, row_bands[i / page.nx],
                                       col_left[i % page.nx], title_cap));
      double& b = bands[i / page.nx];
      b = std::max(b, pg.panels.back().bands);
      double& l = left[i % page.nx];
      l = std::max(l, pg.panels.back().left_needed);
    }
    double smallest = 0.0;
    for (const PanelGeometry& g : pg.panels)
      smallest = smallest > 0.0 ? std::min(smallest, g.title_h) : g.title_h;
    if (bands == row_bands && left == col_left && (title_cap > 0.0 || pg.panels.size() < 2)) break;
    title_cap = smallest;
    for (std::size_t r = 0; r < bands.size(); ++r) row_bands[r] = std::max(row_bands[r], bands[r]);
    for (std::size_t c = 0; c < left.size(); ++c) col_left[c] = std::max(col_left[c], left[c]);
  }
  return pg;
}

PageLayout public_layout(const Page& page, const PageGeometry& pg) {
  PageLayout out;
  out.name = page.name;
  out.width = pg.w;
  out.height = pg.h;
  auto add = [&](const Text& t) { out.texts.push_back({t.kind, t.text, t.box}); };
  for (const PanelGeometry& g : pg.panels) {
    out.axes.push_back(g.axes);
    out.windows.push_back({g.wx0, g.wy0, g.wx1, g.wy1});
    out.axis_labels.insert(out.axis_labels.end(), g.reserved.begin(), g.reserved.end());
    for (const Text& t : g.texts) add(t);
    for (const Text& t : g.axis_texts) out.axis_texts.push_back({t.kind, t.text, t.box});
    out.legend_samples.insert(out.legend_samples.end(), g.samples.begin(), g.samples.end());
    out.data.insert(out.data.end(), g.data.begin(), g.data.end());
  }
  for (const Text& t : pg.texts) add(t);
  return out;
}

// ---- drawing ----

// Cairo's PDF surface stamps the wall-clock time, in local time with its offset from UTC. Drawn
// with the clock in UTC (UtcClock) the date has the "...Z" form, which a fixed date of the same
// length replaces: the byte offsets of the cross-reference table stay valid and the file is the
// same whatever the date and the time zone.
void pin_pdf_date(const std::string& path, const std::string& shown) {
  const auto failed = [&] {
    return OutputError(
        fmt::format("--out {}: writing failed: {}", printable(shown, 96), std::strerror(errno)));
  };
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (in.bad()) throw failed();
  in.close();
  const std::string key = "/CreationDate (D:";
  auto pos = data.find(key);
  if (pos == std::string::npos) return;
  pos += key.size();
  const std::string fixed = "19700101000000Z";
  if (data.compare(pos + fixed.size(), 1, ")") != 0) return;
  data.replace(pos, fixed.size(), fixed);
  std::ofstream out(path, std::ios::binary | std::ios::trunc);
  out << data;
  out.close();
  if (!out) throw failed();
}

// The process's clock in UTC while it lives (for Cairo's PDF date); the time zone as it was after.
class UtcClock {
 public:
  UtcClock() {
    const char* tz = std::getenv("TZ");
    had_ = tz != nullptr;
    if (had_) old_ = tz;
    ::setenv("TZ", "UTC0", 1);
    ::tzset();
  }
  ~UtcClock() {
    if (had_) {
      ::setenv("TZ", old_.c_str(), 1);
    } else {
      ::unsetenv("TZ");
    }
    ::tzset();
  }
  UtcClock(const UtcClock&) = delete;
  UtcClock& operator=(const UtcClock&) = delete;

 private:
  bool had_ = false;
  std::string old_;
};

const char* device(Format f) {
  switch (f) {
    case Format::png: return "pngcairo";
    case Format::svg: return "svg";
    case Format::pdf: return "pdfcairo";
  }
  return "pngcairo";
}

void set_palette() {
  std::array<PLINT, kColourCount> r{}, g{}, b{};
  for (int i = 0; i < kColourCount; ++i) {
    r[i] = kPalette[i][0], g[i] = kPalette[i][1], b[i] = kPalette[i][2];
  }
  plscmap0(r.data(), g.data(), b.data(), kColourCount);
}

void viewport(const PageGeometry& pg, const Box& b) {
  plvpor(b.x0 / pg.w, b.x1 / pg.w, b.y0 / pg.h, b.y1 / pg.h);
}
void mm_space(const PageGeometry& pg) {
  plvpor(0.0, 1.0, 0.0, 1.0);
  plwind(0.0, pg.w, 0.0, pg.h);
}

void draw_text(const Text& t) {
  plschr(t.h, 1.0);
  plcol0(t.colour);
  plptex(t.x, t.y, 1.0, 0.0, t.just, t.text.c_str());
}

void draw_mode_strip(const Panel& p, const PanelGeometry& g, const PageGeometry& pg) {
  viewport(pg, g.strip);
  plwind(g.wx0, g.wx1, 0.0, 1.0);
  plschr(0.7 * g.h, 1.0);
  for (const ModeSpan& m : p.modes) {
    const double a = std::max(g.wx0, m.t0), b = std::min(g.wx1, m.t1);
    if (b <= a) continue;
    plcol0(kModeFirst + static_cast<int>(m.mode) - 1);
    const PLFLT xs[4] = {a, b, b, a}, ys[4] = {0, 0, 1, 1};
    plfill(4, xs, ys);
    plcol0(kBlack);
    // Only where there is room for the two characters.
    const std::string name(to_string(m.mode));
    if ((b - a) / (g.wx1 - g.wx0) * (g.strip.x1 - g.strip.x0) > 1.3 * text_width(name, 0.7 * g.h)) {
      plptex(0.5 * (a + b), 0.5, 1.0, 0.0, 0.5, name.c_str());
    }
  }
  plcol0(kBlack);
  plwidth(1.0);
  plbox("bc", 0.0, 0, "bc", 0.0, 0);
}

void draw_panel(const Panel& p, const PanelGeometry& g, const PageGeometry& pg) {
  const double ch = g.h;
  if (!p.modes.empty()) draw_mode_strip(p, g, pg);

  viewport(pg, g.axes);
  plwind(g.wx0, g.wx1, g.wy0, g.wy1);
  plschr(ch, 1.0);
  plsmaj(0.5 * ch, 1.0);  // tick lengths [mm], short enough to stay clear of texts inside the axes
  plsmin(0.3 * ch, 1.0);
  plcol0(kLightGrey);
  plwidth(0.5);
  plbox("g", 0.0, 0, "g", g.ytick, 0);
  plcol0(kBlack);
  plwidth(1.0);
  // Plain numbers on the axes: no "(x10^3)" above the axis where the title and legend are.
  plsxax(12, 0);
  plsyax(12, 0);
  plbox("bcnst", 0.0, 0, "bcnstv", g.ytick, 0);
  plmtex("b", 3.0, 0.5, 0.5, p.xlabel.c_str());
  plschr(g.ylabel_h, 1.0);
  plmtex("l", g.ylabel_at / g.ylabel_h, 0.5, 0.5, p.ylabel.c_str());
  plschr(ch, 1.0);

  for (const auto& l : p.hlines) {
    plcol0(kGrey);
    pllsty(3);
    plwidth(1.0);
    const PLFLT xs[2] = {g.wx0, g.wx1}, ys[2] = {l.first, l.first};
    plline(2, xs, ys);
    pllsty(1);
  }
  pllsty(2);
  plwidth(1.0);
  plcol0(kGrey);
  for (const EventGroup& e : p.events) {
    const PLFLT xs[2] = {e.t, e.t}, ys[2] = {g.wy0, g.wy1};
    plline(2, xs, ys);
  }
  pllsty(1);

  plschr(ch, 1.0);
  for (const Curve& c : p.curves) {
    if (c.x.empty()) continue;
    plcol0(c.colour);
    if (c.dots) {
      for (std::size_t i = 0; i < c.x.size(); ++i) plptex(c.x[i], c.y[i], 1.0, 0.0, 0.5, "•");
      continue;
    }
    pllsty(c.style);
    plwidth(c.width);
    plline(static_cast<PLINT>(c.x.size()), c.x.data(), c.y.data());
    pllsty(1);
  }
  plcol0(kRed);
  for (const Mark& m : p.marks) plptex(m.x, m.y, 1.0, 0.0, 0.5, "•");
  plwidth(1.0);

  // Everything placed in millimetres: legends, event numbers, leaders, labels, the title.
  mm_space(pg);
  for (const Segment& s : g.strokes) {
    plcol0(s.colour);
    if (s.style == 0) {
      plschr(ch, 1.0);
      plptex(s.x0, s.y0, 1.0, 0.0, 0.5, "•");
      continue;
    }
    pllsty(s.style);
    plwidth(s.width);
    const PLFLT xs[2] = {s.x0, s.x1}, ys[2] = {s.y0, s.y1};
    plline(2, xs, ys);
  }
  pllsty(1);
  plwidth(1.0);
  for (const Text& t : g.texts) draw_text(t);
}

// Draws one page in every requested format; files appear only when complete.
std::vector<std::string> write_page(const std::string& dir, const Page& page, const FigureOptions& opts,
                                    std::vector<PageLayout>* layouts) {
  const PageGeometry pg = layout_page(page);
  if (layouts) layouts->push_back(public_layout(page, pg));
  std::vector<std::string> written;
  for (Format f : opts.formats) {
    const std::string path = (fs::path(dir) / (page.name + "." + std::string(extension(f)))).string();
    // PLplot writes the temporary by name and says nothing of failed writes: commit() checks that
    // the file is complete before it takes the name.
    const auto file = AtomicFile::during_work(path, "--out");
    std::optional<UtcClock> utc;
    if (f == Format::pdf) utc.emplace();
    plsdev(device(f));
    plsfnam(file->temp_path().c_str());
    plsetopt("geometry", fmt::format("{}x{}", page.width, page.height).c_str());
    set_palette();
    plsfam(0, 0, 0);
    plssub(1, 1);
    plinit();
    pladv(0);
    for (std::size_t i = 0; i < page.panels.size(); ++i) draw_panel(page.panels[i], pg.panels[i], pg);
    mm_space(pg);
    for (const Text& t : pg.texts) draw_text(t);
    plend1();
    utc.reset();
    if (f == Format::pdf) pin_pdf_date(file->temp_path(), path);
    file->commit();
    written.push_back(path);
  }
  return written;
}

// Indices of the states to draw: every event state and at most about `limit` plain samples.
std::vector<std::size_t> thin(const Recording& rec, std::size_t limit = 4000) {
  const std::size_t n = rec.states.size();
  const std::size_t stride = std::max<std::size_t>(1, n / limit);
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < n; ++i) {
    if (rec.event_index[i] >= 0 || i % stride == 0 || i + 1 == n) idx.push_back(i);
  }
  return idx;
}

// An empty curve with its legend label and pen.
Curve styled(std::string label, int colour, int style, double width) {
  Curve c;
  c.label = std::move(label);
  c.colour = colour;
  c.style = style;
  c.width = width;
  return c;
}

Curve series(const Recording& rec, const std::function<double(const Snapshot&)>& x,
             const std::function<double(const Snapshot&)>& y, std::string label, int colour, int style = 1,
             double width = 2.0) {
  Curve c = styled(std::move(label), colour, style, width);
  for (std::size_t i : thin(rec)) {
    c.x.push_back(x(rec.states[i]));
    c.y.push_back(y(rec.states[i]));
  }
  return c;
}

double time_of(const Snapshot& s) { return s.t; }

std::vector<ModeSpan> mode_spans(const Recording& rec) {
  std::vector<ModeSpan> spans;
  for (const Snapshot& s : rec.states) {
    if (spans.empty() || spans.back().mode != s.mode) {
      if (!spans.empty()) spans.back().t1 = s.t;
      // A mode held for no time (M4 for the instant of an impact) gets no band of its own.
      if (!spans.empty() && spans.back().t1 <= spans.back().t0) spans.pop_back();
      if (!spans.empty() && spans.back().mode == s.mode) continue;
      spans.push_back({s.t, s.t, s.mode});
    }
    spans.back().t1 = s.t;
  }
  return spans;
}

Panel time_panel(const Recording& rec, std::string title, std::string ylabel) {
  Panel p;
  p.title = std::move(title);
  p.xlabel = "time t [s]";
  p.ylabel = std::move(ylabel);
  p.events = group_events(rec.result);
  p.modes = mode_spans(rec);
  p.fixed_x = true;
  p.x0 = 0.0;
  p.x1 = rec.t_end() > 0.0 ? rec.t_end() * 1.04 : 1.0;
  return p;
}

// Total energy with its jumps at impacts drawn as vertical steps.
Curve total_energy(const Recording& rec, std::string label, int colour, int style = 1, double width = 2.5) {
  Curve c = styled(std::move(label), colour, style, width);
  for (std::size_t i : thin(rec)) {
    const Snapshot& s = rec.states[i];
    const int e = rec.event_index[i];
    if (e >= 0 && rec.result.events[e].impact) {
      c.x.push_back(s.t);
      c.y.push_back(rec.result.events[e].energy_before);
    }
    c.x.push_back(s.t);
    c.y.push_back(s.energy());
  }
  return c;
}

std::vector<Panel> run_panels(const Recording& rec, const std::string& title) {
  const std::string pre = title.empty() ? "" : title + ": ";
  std::vector<Panel> panels;

  Panel x = time_panel(rec, pre + "sandbag, horizontal position", "x [m] (from the pivot)");
  x.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.x; }, "", kBlue));
  panels.push_back(x);

  Panel h = time_panel(rec, pre + "sandbag, height", "h [m] (above the pivot)");
  h.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.h; }, "", kBlue));
  panels.push_back(h);

  Panel tr;
  tr.title = pre + "sandbag, trajectory";
  tr.xlabel = "x [m] (from the pivot)";
  tr.ylabel = "h [m] (above the pivot)";
  tr.to_scale = true;
  tr.curves.push_back(series(
      rec, [](const Snapshot& s) { return s.x; }, [](const Snapshot& s) { return s.h; }, "sandbag", kBlue));
  {
    // The seesaw at the start, for orientation.
    const Snapshot& s0 = rec.states.front();
    const double right = rec.scenario.machine.seesaw_right_arm;
    const double len = std::max(right, 1.2 * std::fabs(s0.x) / std::max(0.2, std::cos(s0.phi_s)));
    Curve arm = styled("seesaw at t = 0", kBrown, 2, 1.5);
    arm.x = {-len * std::cos(s0.phi_s), right * std::cos(s0.phi_s)};
    arm.y = {-len * std::sin(s0.phi_s), right * std::sin(s0.phi_s)};
    tr.curves.push_back(arm);
  }
  const std::vector<EventGroup> groups = group_events(rec.result);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const Snapshot& s = rec.result.events[groups[i].events.back()].after;
    tr.marks.push_back({s.x, s.h, static_cast<int>(i) + 1});
  }
  panels.push_back(tr);

  Panel ang = time_panel(rec, pre + "seesaw and lid angles", "angle [deg]");
  ang.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; },
      "φ#dS#u seesaw (+ = left arm down)", kBlue));
  ang.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; }, "φ#dL#u lid",
      kOrange));
  ang.hlines.push_back({90.0, "90°: vertical"});
  panels.push_back(ang);

  Panel bal = time_panel(rec, pre + "balloon", "height [m] (from the box top)");
  bal.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.balloon_h; }, "balloon h#dB#u", kBlue));
  bal.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.balloon_limit; }, "limit under the lid h#dlim#u",
      kOrange, 2, 2.0));
  panels.push_back(bal);

  Panel en = time_panel(rec, pre + "mechanical energy", "energy [J]");
  en.curves.push_back(total_energy(rec, "total", kBlack));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.sandbag_kinetic + s.sandbag_potential; },
      "sandbag (zero: at rest at the pivot's height)", kGreen, 1, 1.5));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.lid_kinetic + s.lid_potential; },
      "lid (zero: at rest, horizontal)", kPurple, 1, 1.5));
  panels.push_back(en);
  return panels;
}

std::string law_words(ImpactLaw law) {
  switch (law) {
    case ImpactLaw::rope: return "rope impulse (eq. 7)";
    case ImpactLaw::angular_momentum_sum: return "sum of angular momenta";
    case ImpactLaw::kinetic_energy: return "kinetic energy";
    case ImpactLaw::linear_momentum: return "linear momentum (unphysical)";
  }
  return "";
}

std::string outcome_words(const Result& r) {
  return fmt::format("{} {:.3f} s", event_words(r.outcome(), false), r.outcome().t);
}

// Event points on a curve of angle over time.
Curve event_points(const Recording& rec, bool lid, int colour) {
  Curve c;
  c.colour = colour;
  c.dots = true;
  for (const Event& e : rec.result.events) {
    c.x.push_back(e.t);
    c.y.push_back((lid ? e.after.phi_l : e.after.phi_s) * units::kDegreesPerRadian);
  }
  return c;
}

Page make_page(std::string name, int width, int height, int nx, int ny, std::vector<Panel> panels,
               std::vector<EventGroup> key = {}) {
  Page page;
  page.name = std::move(name);
  page.width = width;
  page.height = height;
  page.nx = nx;
  page.ny = ny;
  page.panels = std::move(panels);
  page.key = std::move(key);
  return page;
}

}  // namespace

std::string_view extension(Format f) {
  switch (f) {
    case Format::png: return "png";
    case Format::svg: return "svg";
    case Format::pdf: return "pdf";
  }
  return "png";
}

bool parse_formats(std::string_view text, std::vector<Format>& out) {
  std::vector<Format> formats;
  std::stringstream ss{std::string(text)};
  std::string item;
  while (std::getline(ss, item, ',')) {
    Format f;
    if (item == "png")
      f = Format::png;
    else if (item == "svg")
      f = Format::svg;
    else if (item == "pdf")
      f = Format::pdf;
    else
      return false;
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  }
  if (formats.empty()) return false;
  out = formats;
  return true;
}

void prepare_output_dir(const std::string& dir, std::string_view option) {
  if (dir.empty()) throw InputError(fmt::format("{}: give a directory", option));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError(fmt::format("{}: cannot create directory '{}'{}{}", option, dir, ec ? ": " : "",
                                 ec ? ec.message() : ""));
  }
  if (can_create_in(dir) != 0)
    throw InputError(fmt::format("{}: cannot write into directory '{}'", option, dir));
}

std::vector<std::string> write_run_figures(const Recording& rec, const std::string& dir,
                                           const FigureOptions& opts, std::vector<PageLayout>* layouts) {
  prepare_output_dir(dir, "--out");
  const std::vector<Panel> panels = run_panels(rec, opts.title);
  const std::vector<EventGroup> key = group_events(rec.result);
  static const char* const names[] = {"sandbag_x", "sandbag_h", "trajectory", "angles", "balloon", "energy"};
  std::vector<std::string> written;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    auto w =
        write_page(dir, make_page(names[i], opts.width, opts.height, 1, 1, {panels[i]}, key), opts, layouts);
    written.insert(written.end(), w.begin(), w.end());
  }
  Page overview = make_page("overview", opts.width * 9 / 5, opts.height * 3 / 2, 3, 2, panels, key);
  overview.text_scale = 1.35;
  auto w = write_page(dir, overview, opts, layouts);
  written.insert(written.end(), w.begin(), w.end());
  return written;
}

std::vector<std::string> write_law_comparison(const Scenario& scenario, const std::string& dir,
                                              const FigureOptions& opts, std::vector<PageLayout>* layouts) {
  prepare_output_dir(dir, "--out");
  const std::string pre = opts.title.empty() ? "" : opts.title + ": ";
  Panel ps, pl;
  ps.title = pre + "seesaw angle for the four impact laws (dots: events)";
  pl.title = pre + "lid angle for the four impact laws";
  for (Panel* p : {&ps, &pl}) {
    p->xlabel = "time t [s]";
    p->fixed_x = true;
    p->hlines.push_back({90.0, "90°: vertical"});
  }
  ps.ylabel = "φ#dS#u [deg]";
  pl.ylabel = "φ#dL#u [deg]";
  pl.show_legend = false;  // the same four laws as above
  const int colours[] = {kBlue, kOrange, kGreen, kRed};
  const int styles[] = {1, 2, 3, 4};
  double t_end = 0.0;
  int i = 0;
  for (ImpactLaw law : {ImpactLaw::rope, ImpactLaw::angular_momentum_sum, ImpactLaw::kinetic_energy,
                        ImpactLaw::linear_momentum}) {
    Scenario sc = scenario;
    sc.run.impact_law = law;
    const Recording rec = record(sc);
    t_end = std::max(t_end, rec.t_end());
    const std::string label = fmt::format("{}: {}", law_words(law), outcome_words(rec.result));
    ps.curves.push_back(series(
        rec, time_of, [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; }, label, colours[i],
        styles[i]));
    pl.curves.push_back(series(
        rec, time_of, [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; }, label, colours[i],
        styles[i]));
    ps.curves.push_back(event_points(rec, false, colours[i]));
    pl.curves.push_back(event_points(rec, true, colours[i]));
    ++i;
  }
  for (Panel* p : {&ps, &pl}) p->x1 = t_end * 1.04;
  return write_page(dir, make_page("compare_laws", opts.width, opts.height * 8 / 5, 1, 2, {ps, pl}), opts,
                    layouts);
}

std::vector<std::string> write_integrator_comparison(const Scenario& scenario, IntegratorKind fixed,
                                                     double step, const std::string& dir,
                                                     const FigureOptions& opts,
                                                     std::vector<PageLayout>* layouts) {
  if (fixed == IntegratorKind::adaptive) {
    throw InputError("--integrator: compare the adaptive integrator with euler or rk4, not with itself");
  }
  if (!(step > 0.0)) throw InputError(fmt::format("--step: must be > 0 s, got {}", step));
  prepare_output_dir(dir, "--out");
  Scenario sa = scenario, sf = scenario;
  sa.run.integrator = IntegratorKind::adaptive;
  sf.run.integrator = fixed;
  sf.run.step = step;
  const Recording ra = record(sa), rf = record(sf);
  const std::string pre = opts.title.empty() ? "" : opts.title + ": ";
  const std::string fixed_name = fmt::format("{}, dt = {:g} ms", to_string(fixed), step * 1e3);

  Panel ang;
  ang.title = pre + fmt::format("angles: adaptive (solid) against {} (dashed)", fixed_name);
  ang.xlabel = "time t [s]";
  ang.ylabel = "angle [deg]";
  ang.fixed_x = true;
  ang.x1 = std::max(ra.t_end(), rf.t_end()) * 1.04;
  ang.hlines.push_back({90.0, "90°: vertical"});
  ang.legend_columns = 2;  // a row per integrator
  ang.events = group_events(ra.result);
  auto phs = [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; };
  auto phl = [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; };
  ang.curves.push_back(series(ra, time_of, phs, "φ#dS#u adaptive: " + outcome_words(ra.result), kBlue));
  ang.curves.push_back(series(ra, time_of, phl, "φ#dL#u adaptive", kOrange));
  ang.curves.push_back(
      series(rf, time_of, phs, "φ#dS#u " + fixed_name + ": " + outcome_words(rf.result), kBlue, 2));
  ang.curves.push_back(series(rf, time_of, phl, "φ#dL#u " + fixed_name, kOrange, 2));
  ang.curves.push_back(event_points(rf, false, kBlue));
  ang.curves.push_back(event_points(rf, true, kOrange));

  Panel en = ang;
  en.title = pre + "total mechanical energy (drops only at impacts; drift is integration error)";
  en.ylabel = "energy [J]";
  en.hlines.clear();
  en.curves.clear();
  en.curves.push_back(total_energy(ra, "adaptive", kBlack));
  en.curves.push_back(total_energy(rf, fixed_name, kRed, 2, 2.0));
  return write_page(
      dir, make_page("compare_integrator", opts.width, opts.height * 8 / 5, 1, 2, {ang, en}, ang.events),
      opts, layouts);
}

}  // namespace whatnext::viz
