// Figures with PLplot (C API) and its Cairo drivers. PLplot keeps global state, so each page is
// drawn by one function that sets everything it needs, from plinit to plend1.
#include "whatnext/viz/plots.hpp"

#include <plplot/plplot.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <limits>
#include <map>
#include <cctype>
#include <sstream>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"

namespace whatnext::viz {

namespace fs = std::filesystem;

namespace {

constexpr double kDeg = 180.0 / 3.14159265358979323846;

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
    {255, 255, 255}, {0, 0, 0},       {110, 110, 110}, {31, 119, 180},  {230, 120, 20},
    {44, 160, 44},   {214, 39, 40},   {148, 103, 189}, {140, 86, 75},   {215, 215, 215},
    {255, 236, 179}, {255, 205, 210}, {200, 230, 201}, {187, 222, 251}, {225, 200, 240},
}};

struct Curve {
  std::vector<double> x, y;
  std::string label;
  int colour = kBlack;
  int style = 1;  // PLplot line style: 1 solid, 2 and up dashed
  double width = 2.0;
  int symbol = -1;  // Hershey/Unicode symbol for point markers (no line) when >= 0
};

struct Mark {  // a labelled point (events on the trajectory)
  double x, y;
  std::string label;
  int colour = kBlack;
};

struct ModeSpan {
  double t0, t1;
  Mode mode;
};

struct Panel {
  std::string title, xlabel, ylabel;
  std::vector<Curve> curves;
  std::vector<Mark> marks;
  std::vector<EventGroup> events;  // vertical lines on a time axis
  std::vector<ModeSpan> modes;     // strip above the plot
  std::vector<std::pair<double, std::string>> hlines;  // reference levels
  double x0 = 0.0, x1 = 1.0;
  bool fixed_x = false;
  bool equal_aspect = false;
  PLINT legend_position = PL_POSITION_TOP | PL_POSITION_RIGHT;
};

std::string tmp_name(const std::string& path) { return path + ".part"; }

// Cairo's PDF surface stamps the wall-clock time; a fixed date of the same length keeps the byte
// offsets of the cross-reference table valid and makes the file reproducible.
void pin_pdf_date(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
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
}

// Cairo names SVG groups "surfaceN" with a counter that runs across the whole process, so the
// second figure drawn by one process would differ from the same figure drawn first. Renumbering
// per file, in order of appearance, makes the bytes depend on the figure only.
void renumber_svg_surfaces(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::string data((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  in.close();
  std::map<std::string, int> ids;
  std::string out;
  out.reserve(data.size());
  const std::string key = "surface";
  std::size_t pos = 0;
  for (;;) {
    const std::size_t at = data.find(key, pos);
    if (at == std::string::npos) break;
    std::size_t end = at + key.size();
    while (end < data.size() && std::isdigit(static_cast<unsigned char>(data[end]))) ++end;
    out.append(data, pos, at + key.size() - pos);
    if (end > at + key.size()) {
      const std::string num = data.substr(at + key.size(), end - at - key.size());
      auto it = ids.emplace(num, static_cast<int>(ids.size()) + 1).first;
      out += std::to_string(it->second);
    }
    pos = end;
  }
  out.append(data, pos, std::string::npos);
  std::ofstream o(path, std::ios::binary | std::ios::trunc);
  o << out;
}

const char* device(Format f) {
  switch (f) {
    case Format::png: return "pngcairo";
    case Format::svg: return "svgcairo";
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

// Vertical event lines with their labels written upwards along them. Labels that would overlap
// are pushed to the right (the line stays at the true time).
void draw_event_lines(const Panel& p, double x0, double x1, double y0, double y1,
                      double vp_width_mm, double scale) {
  if (p.events.empty()) return;
  PLFLT def_ht = 0, ht = 0;
  plschr(0.0, 0.75 * scale);
  plgchr(&def_ht, &ht);
  const double mm_to_x = (x1 - x0) / vp_width_mm;
  const double gap = 1.25 * ht * mm_to_x;
  double last = -std::numeric_limits<double>::infinity();
  pllsty(2);
  plwidth(1.0);
  for (const EventGroup& g : p.events) {
    plcol0(kGrey);
    const PLFLT xs[2] = {g.t, g.t}, ys[2] = {y0, y1};
    plline(2, xs, ys);
    double xl = std::max(g.t + 0.75 * ht * mm_to_x, last + gap);
    if (xl > x1 - 0.3 * gap) xl = g.t - 0.75 * ht * mm_to_x;  // no room on the right: left side
    last = xl;
    plcol0(kBlack);
    plptex(xl, y1 - 0.02 * (y1 - y0), 0.0, 1.0, 1.0, g.label.c_str());
  }
  pllsty(1);
  plschr(0.0, scale);
}

void draw_mode_strip(const Panel& p, double vx0, double vx1, double vy0, double vy1, double x0,
                     double x1, double scale) {
  plvpor(vx0, vx1, vy0, vy1);
  plwind(x0, x1, 0.0, 1.0);
  plschr(0.0, 0.7 * scale);
  for (const ModeSpan& m : p.modes) {
    const double a = std::max(x0, m.t0), b = std::min(x1, m.t1);
    if (b <= a) continue;
    plcol0(kModeFirst + static_cast<int>(m.mode) - 1);
    const PLFLT xs[4] = {a, b, b, a}, ys[4] = {0, 0, 1, 1};
    plfill(4, xs, ys);
    plcol0(kBlack);
    // Only where there is room for the two characters.
    if ((b - a) / (x1 - x0) > 0.025) {
      plptex(0.5 * (a + b), 0.5, 1.0, 0.0, 0.5, std::string(to_string(m.mode)).c_str());
    }
  }
  plcol0(kBlack);
  plwidth(1.0);
  plbox("bc", 0.0, 0, "bc", 0.0, 0);
  plschr(0.0, scale);
}

// The corner where the legend hides the fewest curve points and event labels. Sizes are
// estimates in fractions of the plot (character height known, width about 0.55 of it).
struct LegendPlace {
  PLINT corner;
  double cost, height;  // fraction of data it hides; its height as a fraction of the plot
};
LegendPlace legend_corner(const Panel& p, double x0, double x1, double y0, double y1, double w_mm,
                          double h_mm, double text_scale) {
  std::size_t chars = 0, n = 0;
  for (const Curve& c : p.curves) {
    if (!c.label.empty()) chars = std::max(chars, c.label.size()), ++n;
  }
  PLFLT def_ht = 0, ht = 0;
  plgchr(&def_ht, &ht);
  const double fw = std::min(1.0, (chars * 0.55 * ht * text_scale + 0.14 * w_mm) / w_mm);
  const double fh = std::min(1.0, (n * 1.7 * ht * text_scale + 2.0 * ht) / h_mm);
  const PLINT corners[4] = {PL_POSITION_TOP | PL_POSITION_RIGHT, PL_POSITION_TOP | PL_POSITION_LEFT,
                            PL_POSITION_BOTTOM | PL_POSITION_RIGHT,
                            PL_POSITION_BOTTOM | PL_POSITION_LEFT};
  PLINT best = p.legend_position;
  double best_cost = std::numeric_limits<double>::infinity();
  for (PLINT corner : corners) {
    const bool right = corner & PL_POSITION_RIGHT, top = corner & PL_POSITION_TOP;
    const double ax = right ? 1.0 - fw : 0.0, bx = right ? 1.0 : fw;
    const double ay = top ? 1.0 - fh : 0.0, by = top ? 1.0 : fh;
    double cost = 0.0;
    for (const Curve& c : p.curves) {
      for (std::size_t i = 0; i < c.x.size(); ++i) {
        const double u = (c.x[i] - x0) / (x1 - x0), v = (c.y[i] - y0) / (y1 - y0);
        if (u >= ax && u <= bx && v >= ay && v <= by) cost += 1.0 / c.x.size();
      }
    }
    for (const Mark& m : p.marks) {
      const double u = (m.x - x0) / (x1 - x0), v = (m.y - y0) / (y1 - y0);
      const double len = m.label.size() * 0.55 * ht * 0.75 / w_mm;
      if (v >= ay && v <= by && u <= bx && u + len >= ax) cost += 0.5;
    }
    if (corner == p.legend_position) cost -= 1e-6;  // the caller's choice wins ties
    if (cost < best_cost) best_cost = cost, best = corner;
  }
  return {best, n ? best_cost : 0.0, fh};
}

void draw_legend(const Panel& p, double scale) {
  std::vector<const Curve*> shown;
  for (const Curve& c : p.curves) {
    if (!c.label.empty()) shown.push_back(&c);
  }
  if (shown.empty()) return;
  const PLINT n = static_cast<PLINT>(shown.size());
  std::vector<PLINT> opt(n), text_colors(n, kBlack), line_colors(n), line_styles(n),
      symbol_colors(n), symbol_numbers(n, 1), box_colors(n, 0), box_patterns(n, 0);
  std::vector<PLFLT> line_widths(n), symbol_scales(n, 1.0), box_scales(n, 0.0),
      box_line_widths(n, 0.0);
  std::vector<const char*> text(n), symbols(n);
  for (PLINT i = 0; i < n; ++i) {
    const Curve& c = *shown[i];
    opt[i] = c.symbol >= 0 ? PL_LEGEND_SYMBOL : PL_LEGEND_LINE;
    line_colors[i] = symbol_colors[i] = c.colour;
    line_styles[i] = c.style;
    line_widths[i] = c.width;
    text[i] = c.label.c_str();
    symbols[i] = c.symbol >= 0 ? "•" : "";
  }
  PLFLT w = 0, h = 0;
  // pllegend scales its text from the current character height by text_scale.
  plschr(0.0, scale);
  pllegend(&w, &h, PL_LEGEND_BACKGROUND | PL_LEGEND_BOUNDING_BOX, p.legend_position | PL_POSITION_INSIDE,
           0.015, 0.03, 0.06, kWhite, kGrey, 1, 0, 0, n, opt.data(), 1.0, 0.75, 1.8, 0.0,
           text_colors.data(), text.data(), box_colors.data(), box_patterns.data(),
           box_scales.data(), box_line_widths.data(), line_colors.data(), line_styles.data(),
           line_widths.data(), symbol_colors.data(), symbol_scales.data(), symbol_numbers.data(),
           symbols.data());
  plschr(0.0, scale);
}

// One panel in the current subpage; scale sizes the text.
void draw_panel(const Panel& p, double scale) {
  plschr(0.0, scale);
  PLFLT sx0, sx1, sy0, sy1;  // subpage in mm
  plgspa(&sx0, &sx1, &sy0, &sy1);
  const double vx0 = 0.115, vx1 = 0.975, vy0 = 0.13;
  const double vy1 = p.modes.empty() ? 0.89 : 0.84;
  double x0, x1, y0, y1;
  if (p.fixed_x) {
    x0 = p.x0, x1 = p.x1;
  } else {
    data_range(p, true, x0, x1);
  }
  data_range(p, false, y0, y1);
  const double pad_y = 0.06 * (y1 - y0);
  y0 -= pad_y, y1 += pad_y;
  if (!p.fixed_x) {
    const double pad_x = 0.04 * (x1 - x0);
    x0 -= pad_x, x1 += pad_x;
  }
  const double w_mm = (vx1 - vx0) * (sx1 - sx0), h_mm = (vy1 - vy0) * (sy1 - sy0);
  if (p.equal_aspect) {
    // Same metres per millimetre on both axes, as long as that leaves a readable plot.
    const double sx = (x1 - x0) / w_mm, sy = (y1 - y0) / h_mm;
    if (std::max(sx, sy) / std::min(sx, sy) < 8.0) {
      if (sx > sy) {
        const double c = 0.5 * (y0 + y1), half = 0.5 * sx * h_mm;
        y0 = c - half, y1 = c + half;
      } else {
        const double c = 0.5 * (x0 + x1), half = 0.5 * sy * w_mm;
        x0 = c - half, x1 = c + half;
      }
    }
  }
  // Where the legend goes; if every corner hides data, room is made above the data.
  Panel placed = p;
  LegendPlace place = legend_corner(p, x0, x1, y0, y1, w_mm, h_mm, 0.75);
  if (place.cost > 0.02 && !p.equal_aspect && place.height < 0.5) {
    y1 += (y1 - y0) * place.height / (1.0 - place.height);
    place.corner = PL_POSITION_TOP | PL_POSITION_RIGHT;
  }
  placed.legend_position = place.corner;
  if (!p.modes.empty()) draw_mode_strip(p, vx0, vx1, vy1 + 0.012, vy1 + 0.045, x0, x1, scale);

  plvpor(vx0, vx1, vy0, vy1);
  plwind(x0, x1, y0, y1);
  plcol0(kLightGrey);
  plwidth(0.5);
  plbox("g", 0.0, 0, "g", 0.0, 0);
  plcol0(kBlack);
  plwidth(1.0);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  plmtex("b", 3.0, 0.5, 0.5, p.xlabel.c_str());
  plmtex("l", 4.6, 0.5, 0.5, p.ylabel.c_str());
  plschr(0.0, 1.1 * scale);
  plmtex("t", p.modes.empty() ? 1.0 : 3.4, 0.5, 0.5, p.title.c_str());
  plschr(0.0, scale);

  for (const auto& l : p.hlines) {
    plcol0(kGrey);
    pllsty(3);
    plwidth(1.0);
    const PLFLT xs[2] = {x0, x1}, ys[2] = {l.first, l.first};
    plline(2, xs, ys);
    pllsty(1);
    plschr(0.0, 0.7 * scale);
    plptex(x0 + 0.01 * (x1 - x0), l.first + 0.012 * (y1 - y0), 1.0, 0.0, 0.0, l.second.c_str());
    plschr(0.0, scale);
  }
  draw_event_lines(p, x0, x1, y0, y1, w_mm, scale);

  for (const Curve& c : p.curves) {
    if (c.x.empty()) continue;
    plcol0(c.colour);
    if (c.symbol >= 0) {
      plschr(0.0, scale);
      for (std::size_t i = 0; i < c.x.size(); ++i) plptex(c.x[i], c.y[i], 1.0, 0.0, 0.5, "•");
      continue;
    }
    pllsty(c.style);
    plwidth(c.width);
    plline(static_cast<PLINT>(c.x.size()), c.x.data(), c.y.data());
    pllsty(1);
  }
  plwidth(1.0);
  plschr(0.0, 0.75 * scale);
  // Marks closer than a few per cent of the plot to the last labelled one share its label.
  std::vector<std::string> labels;
  std::vector<const Mark*> anchors;
  for (const Mark& m : p.marks) {
    plcol0(m.colour);
    plptex(m.x, m.y, 1.0, 0.0, 0.5, "•");
    if (!anchors.empty() && std::fabs(m.x - anchors.back()->x) < 0.03 * (x1 - x0) &&
        std::fabs(m.y - anchors.back()->y) < 0.04 * (y1 - y0)) {
      const auto at = labels.back().find(" (+");
      int more = 1;
      if (at != std::string::npos) more = std::stoi(labels.back().substr(at + 3)) + 1;
      labels.back() = labels.back().substr(0, at) + fmt::format(" (+{} more)", more);
      continue;
    }
    anchors.push_back(&m);
    labels.push_back(m.label);
  }
  plcol0(kBlack);
  for (std::size_t i = 0; i < anchors.size(); ++i) {
    plptex(anchors[i]->x + 0.012 * (x1 - x0), anchors[i]->y, 1.0, 0.0, 0.0, labels[i].c_str());
  }
  plschr(0.0, scale);
  draw_legend(placed, scale);
}

// Draws one page (nx by ny panels) in every requested format; files appear only when complete.
std::vector<std::string> write_page(const std::string& dir, const std::string& name,
                                    const FigureOptions& opts, int width, int height, int nx,
                                    int ny, const std::vector<Panel>& panels, double scale) {
  std::vector<std::string> written;
  for (Format f : opts.formats) {
    const std::string path = (fs::path(dir) / (name + "." + std::string(extension(f)))).string();
    const std::string tmp = tmp_name(path);
    plsdev(device(f));
    plsfnam(tmp.c_str());
    plsetopt("geometry", fmt::format("{}x{}", width, height).c_str());
    set_palette();
    plsfam(0, 0, 0);
    plssub(nx, ny);
    plinit();
    plfontld(0);
    for (const Panel& p : panels) {
      pladv(0);
      draw_panel(p, scale);
    }
    plend1();
    if (f == Format::pdf) pin_pdf_date(tmp);
    if (f == Format::svg) renumber_svg_surfaces(tmp);
    std::error_code ec;
    fs::rename(tmp, path, ec);
    if (ec) throw InputError(fmt::format("--out: cannot write '{}': {}", path, ec.message()));
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
             const std::function<double(const Snapshot&)>& y, std::string label, int colour,
             int style = 1, double width = 2.0) {
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
Curve total_energy(const Recording& rec, std::string label, int colour, int style = 1,
                   double width = 2.5) {
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
  x.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.x; }, "x", kBlue));
  x.curves.back().label.clear();
  panels.push_back(x);

  Panel h = time_panel(rec, pre + "sandbag, height", "h [m] (above the pivot)");
  h.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.h; }, "h", kBlue));
  h.curves.back().label.clear();
  panels.push_back(h);

  Panel tr;
  tr.title = pre + "sandbag, trajectory";
  tr.xlabel = "x [m]";
  tr.ylabel = "h [m]";
  tr.equal_aspect = true;
  tr.legend_position = PL_POSITION_BOTTOM | PL_POSITION_LEFT;
  tr.curves.push_back(series(
      rec, [](const Snapshot& s) { return s.x; }, [](const Snapshot& s) { return s.h; },
      "sandbag", kBlue));
  {
    // The seesaw's left arm at the start, for orientation.
    const Snapshot& s0 = rec.states.front();
    const double len = std::max(rec.scenario.machine.seesaw_right_arm,
                                1.2 * std::fabs(s0.x) / std::max(0.2, std::cos(s0.phi_s)));
    Curve arm;
    arm.label = "seesaw at t = 0";
    arm.colour = kBrown;
    arm.width = 1.5;
    arm.style = 2;
    arm.x = {-len * std::cos(s0.phi_s), rec.scenario.machine.seesaw_right_arm * std::cos(s0.phi_s)};
    arm.y = {-len * std::sin(s0.phi_s), rec.scenario.machine.seesaw_right_arm * std::sin(s0.phi_s)};
    tr.curves.push_back(arm);
  }
  for (const EventGroup& g : group_events(rec.result)) {
    const Snapshot& s = rec.result.events[g.events.back()].after;
    tr.marks.push_back({s.x, s.h, g.label, kRed});
  }
  panels.push_back(tr);

  Panel ang = time_panel(rec, pre + "seesaw and lid angles", "angle [deg]");
  ang.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.phi_s * kDeg; },
                              "φ#dS#u seesaw (+ = left arm down)", kBlue));
  ang.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.phi_l * kDeg; },
                              "φ#dL#u lid", kOrange));
  ang.hlines.push_back({90.0, "90°: vertical"});
  ang.legend_position = PL_POSITION_BOTTOM | PL_POSITION_RIGHT;
  panels.push_back(ang);

  Panel bal = time_panel(rec, pre + "balloon", "height of the balloon's centre [m] (from the box top)");
  bal.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.balloon_h; },
                              "balloon h#dB#u", kBlue));
  bal.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.balloon_limit; },
                              "limit under the lid h#dlim#u", kOrange, 2, 2.0));
  bal.legend_position = PL_POSITION_TOP | PL_POSITION_LEFT;
  panels.push_back(bal);

  Panel en = time_panel(rec, pre + "mechanical energy", "energy [J]");
  en.curves.push_back(total_energy(rec, "total", kBlack));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.sandbag_kinetic + s.sandbag_potential; },
      "sandbag (zero: at the pivot's height, at rest)", kGreen, 1, 1.5));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.lid_kinetic + s.lid_potential; },
      "lid (zero: horizontal, at rest)", kPurple, 1, 1.5));
  en.legend_position = PL_POSITION_BOTTOM | PL_POSITION_LEFT;
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
  c.symbol = 1;
  for (const Event& e : rec.result.events) {
    c.x.push_back(e.t);
    c.y.push_back((lid ? e.after.phi_l : e.after.phi_s) * kDeg);
  }
  return c;
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
    if (item == "png") f = Format::png;
    else if (item == "svg") f = Format::svg;
    else if (item == "pdf") f = Format::pdf;
    else return false;
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
    throw InputError(fmt::format("{}: cannot create directory '{}'{}{}", option, dir,
                                 ec ? ": " : "", ec ? ec.message() : ""));
  }
  const std::string probe = (fs::path(dir) / ".whatnext-probe.part").string();
  {
    std::ofstream out(probe);
    if (!out) throw InputError(fmt::format("{}: cannot write into directory '{}'", option, dir));
  }
  fs::remove(probe, ec);
}

std::vector<std::string> write_run_figures(const Recording& rec, const std::string& dir,
                                           const FigureOptions& opts) {
  prepare_output_dir(dir, "--out");
  const std::vector<Panel> panels = run_panels(rec, opts.title);
  static const char* const names[] = {"sandbag_x", "sandbag_h", "trajectory",
                                      "angles",    "balloon",   "energy"};
  std::vector<std::string> written;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    auto w = write_page(dir, names[i], opts, opts.width, opts.height, 1, 1, {panels[i]}, 1.0);
    written.insert(written.end(), w.begin(), w.end());
  }
  auto w = write_page(dir, "overview", opts, opts.width * 9 / 5, opts.height * 3 / 2, 3, 2, panels,
                      0.62);
  written.insert(written.end(), w.begin(), w.end());
  return written;
}

std::vector<std::string> write_law_comparison(const Scenario& scenario, const std::string& dir,
                                              const FigureOptions& opts) {
  prepare_output_dir(dir, "--out");
  const std::string pre = opts.title.empty() ? "" : opts.title + ": ";
  Panel ps, pl;
  ps.title = pre + "seesaw angle for the four impact laws";
  pl.title = pre + "lid angle for the four impact laws";
  for (Panel* p : {&ps, &pl}) {
    p->xlabel = "time t [s]";
    p->fixed_x = true;
    p->hlines.push_back({90.0, "90°: vertical"});
  }
  ps.ylabel = "φ#dS#u [deg]";
  pl.ylabel = "φ#dL#u [deg]";
  ps.legend_position = PL_POSITION_BOTTOM | PL_POSITION_RIGHT;
  pl.legend_position = PL_POSITION_TOP | PL_POSITION_LEFT;
  const int colours[] = {kBlue, kOrange, kGreen, kRed};
  const int styles[] = {1, 2, 3, 4};
  double t_end = 0.0;
  int i = 0;
  for (ImpactLaw law : {ImpactLaw::rope, ImpactLaw::angular_momentum_sum,
                        ImpactLaw::kinetic_energy, ImpactLaw::linear_momentum}) {
    Scenario sc = scenario;
    sc.run.impact_law = law;
    const Recording rec = record(sc);
    t_end = std::max(t_end, rec.t_end());
    const std::string label = fmt::format("{}: {}", law_words(law), outcome_words(rec.result));
    ps.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.phi_s * kDeg; },
                               label, colours[i], styles[i]));
    pl.curves.push_back(series(rec, time_of, [](const Snapshot& s) { return s.phi_l * kDeg; },
                               label, colours[i], styles[i]));
    ps.curves.push_back(event_points(rec, false, colours[i]));
    pl.curves.push_back(event_points(rec, true, colours[i]));
    ++i;
  }
  for (Panel* p : {&ps, &pl}) p->x1 = t_end * 1.04;
  return write_page(dir, "compare_laws", opts, opts.width, opts.height * 8 / 5, 1, 2, {ps, pl}, 1.0);
}

std::vector<std::string> write_integrator_comparison(const Scenario& scenario,
                                                     IntegratorKind fixed, double step,
                                                     const std::string& dir,
                                                     const FigureOptions& opts) {
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
  ang.legend_position = PL_POSITION_BOTTOM | PL_POSITION_RIGHT;
  ang.events = group_events(ra.result);
  auto phs = [](const Snapshot& s) { return s.phi_s * kDeg; };
  auto phl = [](const Snapshot& s) { return s.phi_l * kDeg; };
  ang.curves.push_back(series(ra, time_of, phs, "φ#dS#u adaptive: " + outcome_words(ra.result), kBlue));
  ang.curves.push_back(series(ra, time_of, phl, "φ#dL#u adaptive", kOrange));
  ang.curves.push_back(series(rf, time_of, phs, "φ#dS#u " + fixed_name + ": " + outcome_words(rf.result),
                              kBlue, 2));
  ang.curves.push_back(series(rf, time_of, phl, "φ#dL#u " + fixed_name, kOrange, 2));
  ang.curves.push_back(event_points(rf, false, kBlue));
  ang.curves.push_back(event_points(rf, true, kOrange));

  Panel en = ang;
  en.title = pre + "total mechanical energy (drops only at impacts; drift is integration error)";
  en.ylabel = "energy [J]";
  en.hlines.clear();
  en.curves.clear();
  en.legend_position = PL_POSITION_TOP | PL_POSITION_RIGHT;
  en.curves.push_back(total_energy(ra, "adaptive", kBlack));
  en.curves.push_back(total_energy(rf, fixed_name, kRed, 2, 2.0));
  return write_page(dir, "compare_integrator", opts, opts.width, opts.height * 8 / 5, 1, 2,
                    {ang, en}, 1.0);
}

}  // namespace whatnext::viz
