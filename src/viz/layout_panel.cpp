// One panel laid out in millimetres, in stages: the data window, the legend and the event numbers
// measured, the bands above the axes and with them the axes, the window made to scale, then the
// texts placed (title, legend, event numbers, the y axis), the data mapped into millimetres and
// the texts inside the axes placed where they touch no curve.
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "figure.hpp"
#include "placement.hpp"
#include "whatnext/units.hpp"

namespace whatnext::viz::figure {

namespace {

// The data window: the data's range, padded by 4% along x (unless the panel fixes it) and 6%
// along y.
void data_window(const Panel& p, PanelGeometry& g) {
  if (p.fixed_x) {
    g.wx0 = p.x0, g.wx1 = p.x1;
  } else {
    data_range(p, true, g.wx0, g.wx1);
    const double pad_x = 0.04 * (g.wx1 - g.wx0);
    g.wx0 -= pad_x, g.wx1 += pad_x;
  }
  data_range(p, false, g.wy0, g.wy1);
  const double pad_y = 0.06 * (g.wy1 - g.wy0);
  g.wy0 -= pad_y, g.wy1 += pad_y;
}

// The legend above the axes: its entries in as many columns as fit, smaller if the widest entry
// is wider than the axes.
struct Legend {
  std::vector<const Curve*> entries;
  double h = 0.0;                         // character height [mm]
  double sample = 0.0, sample_gap = 0.0;  // a line's sample and the gap after it [mm]
  Grid grid;
  double line = 0.0;  // the rows' spacing [mm]
};
Legend measure_legend(const Panel& p, const PanelGeometry& g, double ch) {
  Legend l;
  if (p.show_legend) {
    for (const Curve& c : p.curves) {
      if (!c.label.empty()) l.entries.push_back(&c);
    }
  }
  const double aw = g.axes.x1 - g.axes.x0;
  l.h = 0.8 * ch;
  l.sample = 2.2 * ch, l.sample_gap = 0.6 * ch;
  const double entry_gap = 1.6 * ch;
  std::vector<double> entry_w;
  auto measure_entries = [&] {
    entry_w.clear();
    for (const Curve* c : l.entries) entry_w.push_back(l.sample + l.sample_gap + text_width(c->label, l.h));
  };
  measure_entries();
  const double widest = entry_w.empty() ? 0.0 : *std::max_element(entry_w.begin(), entry_w.end());
  if (widest > aw) {
    l.h *= aw / widest;
    measure_entries();
  }
  l.grid = grid(entry_w, g.axes.x0, g.axes.x1, entry_gap, p.legend_columns);
  bool legend_sub = false;
  for (const Curve* c : l.entries) legend_sub = legend_sub || has_subscript(c->label);
  l.line = (legend_sub ? 2.0 : 1.7) * l.h;
  return l;
}

// Where an instant of a time axis is, in millimetres.
double time_x(const PanelGeometry& g, double t) {
  const double aw = g.axes.x1 - g.axes.x0;
  return g.axes.x0 + (t - g.wx0) / (g.wx1 - g.wx0) * aw;
}

// The events' numbers above the axes: one row if they fit, otherwise alternating between more
// rows (at most six).
struct EventNumbers {
  int rows = 0;
  std::vector<std::vector<double>> pos;  // per row: each number's centre [mm]
  std::vector<std::vector<std::size_t>> members;
  double h = 0.0, row = 0.0, leader = 0.0;  // character height, row height, leader's room [mm]
  double band(double ch) const { return rows ? rows * row + leader : 0.3 * ch; }
};
EventNumbers pack_event_numbers(const Panel& p, const PanelGeometry& g, double ch) {
  EventNumbers n;
  n.h = 0.75 * ch;
  n.row = 1.5 * n.h, n.leader = 0.8 * ch;
  std::vector<double> tag_w;
  for (std::size_t i = 0; i < p.events.size(); ++i) {
    tag_w.push_back(text_width(std::to_string(i + 1), n.h));
  }
  n.rows = p.events.empty() ? 0 : 1;
  const double tag_lo = g.axes.x0, tag_hi = g.axes.x1 + 1.2 * ch;
  for (; n.rows > 0 && n.rows <= 6; ++n.rows) {
    n.pos.assign(n.rows, {});
    n.members.assign(n.rows, {});
    bool ok = true;
    for (int row = 0; row < n.rows && ok; ++row) {
      std::vector<double> c, w;
      for (std::size_t i = row; i < p.events.size(); i += n.rows) {
        c.push_back(time_x(g, p.events[i].t));
        w.push_back(tag_w[i]);
        n.members[row].push_back(i);
      }
      ok = placement::pack_row(c, w, tag_lo, tag_hi, 0.5 * n.h, n.pos[row]);
    }
    if (ok) break;
  }
  n.rows = std::min(n.rows, 6);
  return n;
}

// Same data units per millimetre on both axes, as long as that leaves a readable plot; otherwise
// the title says how much one axis is stretched. Returns what the title gets added.
std::string make_to_scale(PanelGeometry& g) {
  const double aw = g.axes.x1 - g.axes.x0, ah = g.axes.y1 - g.axes.y0;
  const double sx = (g.wx1 - g.wx0) / aw, sy = (g.wy1 - g.wy0) / ah;
  const double stretch = std::max(sx, sy) / std::min(sx, sy);
  if (!(stretch <= 8.0))
    return fmt::format(" (not to scale: {} stretched {:.0f}×)", sx > sy ? "h" : "x", stretch);
  if (sx > sy) {
    const double c = 0.5 * (g.wy0 + g.wy1), half = 0.5 * sx * ah;
    g.wy0 = c - half, g.wy1 = c + half;
  } else {
    const double c = 0.5 * (g.wx0 + g.wx1), half = 0.5 * sy * aw;
    g.wx0 = c - half, g.wx1 = c + half;
  }
  return " (to scale)";
}

// The title at the top of rect r, shrunk to the panel's width if need be (and to title_cap, the
// page's shared size, if given). Returns the height below it where the legend starts.
double place_title(PanelGeometry& g, const std::string& title, const Box& r, double ch, double title_cap) {
  const double pad = 0.5 * ch;
  const double title_h = 1.1 * ch;
  double y = r.y1 - 0.8 * ch;
  double th = title_cap > 0.0 ? std::min(title_h, title_cap) : title_h;
  const double tw = text_width(title, th);
  if (tw > r.x1 - r.x0 - 2.0 * pad) th *= (r.x1 - r.x0 - 2.0 * pad) / tw;
  g.title_h = th;
  y -= 0.55 * title_h;
  const double title_x = std::clamp(0.5 * (g.axes.x0 + g.axes.x1), r.x0 + pad + 0.5 * text_width(title, th),
                                    r.x1 - pad - 0.5 * text_width(title, th));
  g.texts.push_back(make_text(PlacedText::title, title, title_x, y, 0.5, th));
  return y - (0.9 * title_h + 0.3 * ch);
}

// The legend's rows from height y down, left-aligned with the axes.
void place_legend(PanelGeometry& g, const Legend& legend, double y) {
  for (const auto& line : legend.grid.rows) {
    const double ty = y - 0.55 * legend.h;
    for (std::size_t i : line) {
      const double x = legend.grid.x(i);
      const Curve& c = *legend.entries[i];
      const double sample = legend.sample;
      const Box sb{x, ty - 0.35 * legend.h, x + sample, ty + 0.35 * legend.h};
      if (c.dots) {
        g.strokes.push_back({x + 0.5 * sample, ty, x + 0.5 * sample, ty, c.colour, 0, c.width});
      } else {
        g.strokes.push_back({x, ty, x + sample, ty, c.colour, c.style, c.width});
      }
      g.samples.push_back(sb);
      g.texts.push_back(
          make_text(PlacedText::legend, c.label, x + sample + legend.sample_gap, ty, 0.0, legend.h));
    }
    y -= legend.line;
  }
}

// The event numbers above the axes, with a leader down to the event's line where they had to move.
void place_event_numbers(PanelGeometry& g, const Panel& p, const EventNumbers& n, double ch) {
  for (int row = 0; row < n.rows; ++row) {
    const double ty = g.axes.y1 + n.leader + (row + 0.5) * n.row;
    for (std::size_t k = 0; k < n.members[row].size(); ++k) {
      const std::size_t i = n.members[row][k];
      const double cx = time_x(g, p.events[i].t), tx = n.pos[row][k];
      Text t = make_text(PlacedText::event_number, std::to_string(i + 1), tx, ty, 0.5, n.h);
      g.strokes.push_back({cx, g.axes.y1, tx, t.box.y0 - 0.1 * ch, kGrey, 1, 0.8});
      g.texts.push_back(std::move(t));
    }
  }
}

// The y axis' tick numbers and title, where PLplot will write them. The title is smaller if it is
// longer than the axes are high, and clear of the widest tick number: PLplot writes those 0.5 ch
// left of the axes, right-aligned; the title, turned upright, reaches 0.85 of its height (1.4
// with a subscript) from its reference point towards the axes and 0.55 away from them.
void place_y_axis(PanelGeometry& g, const Panel& p, double ch) {
  g.ylabel_h = std::min(ch, ch * 0.97 * (g.axes.y1 - g.axes.y0) / std::max(1e-9, text_width(p.ylabel, ch)));
  g.ytick = tick_spacing(g.wy0, g.wy1);
  double widest_tick = 0.0;
  const auto numbers = tick_numbers(g.wy0, g.wy1, g.ytick);
  for (const auto& n : numbers) widest_tick = std::max(widest_tick, text_width(n.second, ch));
  const double inward = (has_subscript(p.ylabel) ? 1.4 : 0.85) * g.ylabel_h;
  g.ylabel_at = std::max(4.6 * ch, 0.5 * ch + widest_tick + 0.4 * ch + inward);
  g.left_needed = g.ylabel_at + 0.55 * g.ylabel_h + 0.4 * ch;
  for (const auto& [v, text] : numbers) {
    const double y = g.axes.y0 + (v - g.wy0) / (g.wy1 - g.wy0) * (g.axes.y1 - g.axes.y0);
    g.axis_texts.push_back(make_text(PlacedText::label, text, g.axes.x0 - 0.5 * ch, y, 1.0, ch));
  }
  // The title turned upright: its box is a text box turned by 90 degrees.
  const double half = 0.5 * text_width(p.ylabel, g.ylabel_h), x = g.axes.x0 - g.ylabel_at;
  const double ym = 0.5 * (g.axes.y0 + g.axes.y1);
  Text t = make_text(PlacedText::label, p.ylabel, x, ym, 0.5, g.ylabel_h);
  t.box = {x - 0.55 * g.ylabel_h, ym - half, x + inward, ym + half};
  g.axis_texts.push_back(std::move(t));
}

// Data units to millimetres on the page, through the panel's final window.
Point to_mm(const PanelGeometry& g, double x, double y) {
  const double aw = g.axes.x1 - g.axes.x0, ah = g.axes.y1 - g.axes.y0;
  return Point{g.axes.x0 + (x - g.wx0) / (g.wx1 - g.wx0) * aw,
               g.axes.y0 + (y - g.wy0) / (g.wy1 - g.wy0) * ah};
}

// The curves, the dots and the marks in millimetres, for the collision tests and the layout's users.
void map_data(PanelGeometry& g, const Panel& p) {
  for (const Curve& c : p.curves) {
    if (c.dots) {
      for (std::size_t i = 0; i < c.x.size(); ++i) g.data.push_back({to_mm(g, c.x[i], c.y[i])});
      continue;
    }
    Polyline line;
    for (std::size_t i = 0; i < c.x.size(); ++i) line.push_back(to_mm(g, c.x[i], c.y[i]));
    g.data.push_back(std::move(line));
  }
  for (const Mark& m : p.marks) g.data.push_back({to_mm(g, m.x, m.y)});
}

// Is box b a free spot inside the axes: clear of the tick marks, of the polylines to avoid and of
// every text placed so far?
bool free_spot(const PanelGeometry& g, const Box& b, const std::vector<Polyline>& avoid, double ch) {
  if (!inside(b, grow(g.axes, -0.6 * ch))) return false;
  if (hits_data(grow(b, 0.15 * ch), avoid)) return false;
  for (const Text& t : g.texts) {
    if (overlap(grow(b, 0.15 * ch), t.box)) return false;
  }
  return true;
}

// Does the segment from `from` to `end` cross one of the curves (not counting dots)?
bool crosses_curve(Point from, Point end, const std::vector<Polyline>& curves) {
  for (const Polyline& line : curves) {
    if (line.size() == 1) continue;
    for (std::size_t i = 1; i < line.size(); ++i) {
      const double d1x = end.first - from.first, d1y = end.second - from.second;
      const double d2x = line[i].first - line[i - 1].first, d2y = line[i].second - line[i - 1].second;
      const double den = d1x * d2y - d1y * d2x;
      if (den == 0.0) continue;
      const double ex = line[i - 1].first - from.first, ey = line[i - 1].second - from.second;
      const double s1 = (ex * d2y - ey * d2x) / den, s2 = (ex * d1y - ey * d1x) / den;
      if (s1 > 0.0 && s1 < 1.0 && s2 >= 0.0 && s2 <= 1.0) return true;
    }
  }
  return false;
}

// Numbers of the events on the trajectory: near their dot, away from the curves and each other;
// on rings farther out with a leader that crosses no curve either.
void place_marks(PanelGeometry& g, const Panel& p, const std::vector<Polyline>& obstacles,
                 const std::vector<Polyline>& curves_only, double ch) {
  const double mark_h = 0.8 * ch;
  for (const Mark& m : p.marks) {
    const Point at = to_mm(g, m.x, m.y);
    const std::string s = std::to_string(m.number);
    const double w = text_width(s, mark_h);
    bool placed = false;
    for (int ring = 1; ring <= 8 && !placed; ++ring) {
      const double d = 0.5 * ch + (ring - 1) * 1.1 * ch;
      for (int k = 0; k < 16 && !placed; ++k) {
        if (ring == 1 && k % 2) continue;  // the first ring: 8 directions
        const double a = k * units::kPi / 8.0;
        const double ux = std::cos(a), uy = std::sin(a);
        const double cx = at.first + ux * (d + 0.5 * w), cy = at.second + uy * (d + 0.6 * mark_h);
        Text t = make_text(PlacedText::event_number, s, cx, cy + 0.15 * mark_h, 0.5, mark_h);
        if (!free_spot(g, t.box, obstacles, ch)) continue;
        if (ring > 1) {
          const Point end{std::clamp(at.first, t.box.x0, t.box.x1),
                          std::clamp(at.second, t.box.y0, t.box.y1)};
          const Point from{at.first + 0.35 * ch * ux, at.second + 0.35 * ch * uy};
          if (crosses_curve(from, end, curves_only)) continue;
          g.strokes.push_back({from.first, from.second, end.first, end.second, kGrey, 1, 0.8});
        }
        g.texts.push_back(std::move(t));
        placed = true;
      }
    }
  }
}

// Names of reference levels: on a free stretch of their line (crossing an event line if needed);
// left out where there is none.
void place_level_names(PanelGeometry& g, const Panel& p, const std::vector<Polyline>& obstacles,
                       const std::vector<Polyline>& curves_only, double ch) {
  const double line_h = 0.7 * ch, aw = g.axes.x1 - g.axes.x0;
  for (const auto& [level, name] : p.hlines) {
    const Point at = to_mm(g, g.wx0, level);
    bool placed = false;
    for (int pass = 0; pass < 2 && !placed; ++pass) {
      const std::vector<Polyline>& avoid = pass == 0 ? obstacles : curves_only;
      for (double fx : {0.0, 1.0, 0.25, 0.5, 0.75}) {
        for (double side : {1.0, -1.0}) {
          const double just = fx == 1.0 ? 1.0 : fx == 0.0 ? 0.0 : 0.5;
          const double x = g.axes.x0 + 0.8 * ch + fx * (aw - 1.6 * ch);
          const double ty = at.second + (side > 0 ? 0.95 * line_h : -0.65 * line_h);
          Text t = make_text(PlacedText::label, name, x, ty, just, line_h, kGrey);
          if (!free_spot(g, t.box, avoid, ch)) continue;
          g.texts.push_back(std::move(t));
          placed = true;
          break;
        }
        if (placed) break;
      }
    }
  }
}

}  // namespace

// The panel in rect r with base character height ch; the bands above the axes (title, legend, mode
// strip, event numbers) take at least min_bands, so that panels side by side line up.
// `left` is the room left of the axes for the tick numbers and the y axis' title (at least 6 ch;
// layout_page widens it to what the panels of a column need, g.left_needed).
// `title_cap` (if > 0) is the largest title height, so that the panels of a page share one.
PanelGeometry layout_panel(const Panel& p, const Box& r, double ch, double min_bands, double left,
                           double title_cap) {
  PanelGeometry g;
  g.h = ch;
  g.axes.x0 = r.x0 + std::max(6.0 * ch, left);
  g.axes.x1 = r.x1 - 1.5 * ch;
  g.axes.y0 = r.y0 + 4.4 * ch;
  data_window(p, g);

  // The bands above the axes (title, legend, mode strip, event numbers) decide the axes' height.
  const Legend legend = measure_legend(p, g, ch);
  const EventNumbers numbers = pack_event_numbers(p, g, ch);
  const double title_h = 1.1 * ch;
  const double tag_band = numbers.band(ch);
  g.bands = 0.8 * ch + title_h * 1.45 + 0.3 * ch +
            (legend.grid.rows.empty() ? 0.0 : legend.grid.rows.size() * legend.line + 0.3 * ch) +
            (p.modes.empty() ? 0.0 : 1.25 * ch) + tag_band;
  g.axes.y1 = r.y1 - std::max(g.bands, min_bands);
  const double ah = g.axes.y1 - g.axes.y0;

  const std::string title = p.title + (p.to_scale ? make_to_scale(g) : std::string());
  // Room above the highest reference level for its name.
  const double line_h = 0.7 * ch;
  for (const auto& l : p.hlines) {
    const double k = (1.6 * line_h + 0.7 * ch) / ah;
    if (g.wy1 - l.first < k * (g.wy1 - g.wy0)) g.wy1 = (l.first - k * g.wy0) / (1.0 - k);
  }

  place_legend(g, legend, place_title(g, title, r, ch, title_cap));
  if (!p.modes.empty()) {
    g.strip = {g.axes.x0, g.axes.y1 + tag_band, g.axes.x1, g.axes.y1 + tag_band + 1.0 * ch};
  }
  place_event_numbers(g, p, numbers, ch);
  place_y_axis(g, p, ch);
  // Where PLplot writes tick numbers and axis titles.
  g.reserved.push_back({r.x0, g.axes.y0 - 0.6 * ch, g.axes.x0, g.axes.y1 + 0.6 * ch});
  g.reserved.push_back({g.axes.x0 - 2.0 * ch, r.y0, g.axes.x1 + 2.0 * ch, g.axes.y0});

  // The texts inside the axes avoid the data; the event numbers avoid the events' lines too.
  map_data(g, p);
  std::vector<Polyline> obstacles = g.data;
  const std::vector<Polyline> curves_only = g.data;
  for (const EventGroup& e : p.events) {
    obstacles.push_back({to_mm(g, e.t, g.wy0), to_mm(g, e.t, g.wy1)});
  }
  place_marks(g, p, obstacles, curves_only, ch);
  place_level_names(g, p, obstacles, curves_only, ch);
  return g;
}

}  // namespace whatnext::viz::figure
