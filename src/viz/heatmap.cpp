#include "whatnext/viz/heatmap.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>

#include <fmt/format.h>

#include "png_chart.hpp"
#include "whatnext/config.hpp"

namespace whatnext::viz {

using explore::Machines;
using explore::Outcome;
using explore::Plan;
using explore::Range;
using explore::SweepResult;
using explore::value_of;

namespace {
using png_chart::fill_rect;
using png_chart::kInk;
// Colour map 0 slots of the cells that have no value to colour by.
constexpr PLINT kNever = png_chart::kFirstColour, kInvalid = kNever + 1;

std::string with_unit(std::string_view value) {
  const char* unit = value == "final_r" ? "m" : value == "final_phi_l_deg" ? "deg" : "s";
  return fmt::format("{} [{}]", value, unit);
}

// An input key with its unit, for an axis: "geometry.rope_length [m]".
std::string key_with_unit(const std::string& key) {
  const KeySpec* spec = find_key(key);
  return spec && !spec->unit.empty() ? fmt::format("{} [{}]", key, spec->unit) : key;
}

// Cell edges of a grid range: each value sits in the middle of its cell.
void cell_edges(const Range& r, double& lo, double& width) {
  width = r.n > 1 ? (r.hi - r.lo) / (r.n - 1)
                  : (r.hi > r.lo ? r.hi - r.lo : std::fmax(1e-3, std::fabs(r.lo) * 0.1));
  lo = r.lo - 0.5 * width;
}

// The machines as cells of the map: machine i's cell, the last key varying fastest.
struct Cells {
  double x0, wx, y0, wy;
  int ny;

  explicit Cells(const Plan& plan) : ny(plan.ranges[1].n) {
    cell_edges(plan.ranges[0], x0, wx);
    cell_edges(plan.ranges[1], y0, wy);
  }
  void fill(std::int64_t i) const {
    const double cx = x0 + wx * static_cast<double>(i / ny), cy = y0 + wy * static_cast<double>(i % ny);
    fill_rect(cx, cx + wx, cy, cy + wy);
  }
};

// The colour scale's range over the values that happened, and which grey and black cells there
// are (the legend names only those).
struct Scale {
  double vmin = INFINITY, vmax = -INFINITY;
  bool any_never = false, any_invalid = false;
};
Scale scale_of(const Machines& machines, const SweepResult& result, std::string_view value) {
  Scale sc;
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    if (!result.done[static_cast<std::size_t>(i)]) continue;
    const Outcome& o = result.rows[static_cast<std::size_t>(i)];
    if (!o.valid) {
      sc.any_invalid = true;
      continue;
    }
    const double v = value_of(o, value);
    if (std::isnan(v)) {
      sc.any_never = true;
      continue;
    }
    sc.vmin = std::fmin(sc.vmin, v);
    sc.vmax = std::fmax(sc.vmax, v);
  }
  png_chart::usable_range(sc.vmin, sc.vmax);
  return sc;
}

// The page, with a dark-blue to yellow ramp that stays readable in greyscale (viridis' end points
// and middle).
void begin_page(const std::string& path) {
  png_chart::begin(path,
                   {960,
                    720,
                    {{190, 190, 190}, {40, 40, 40}},  // kNever, kInvalid
                    {{0.0, 0.267, 0.005, 0.329}, {0.5, 0.128, 0.567, 0.551}, {1.0, 0.993, 0.906, 0.144}}});
}

// One cell per machine that ran, in its value's colour, grey or black.
void draw_cells(const Cells& cells, const Machines& machines, const SweepResult& result,
                std::string_view value, const Scale& sc) {
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    if (!result.done[static_cast<std::size_t>(i)]) continue;
    const Outcome& o = result.rows[static_cast<std::size_t>(i)];
    const double v = value_of(o, value);
    if (!o.valid) {
      plcol0(kInvalid);
    } else if (std::isnan(v)) {
      plcol0(kNever);
    } else {
      plcol1((v - sc.vmin) / (sc.vmax - sc.vmin));
    }
    cells.fill(i);
  }
}

// Whatever is drawn, machines whose lid did not open in their run stay recognisable: hatched.
// Says whether there were any.
bool hatch_closed(const Cells& cells, const Machines& machines, const SweepResult& result) {
  bool any_closed = false;
  plcol0(kInk);
  plpsty(3);
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    const Outcome& o = result.rows[static_cast<std::size_t>(i)];
    if (!result.done[static_cast<std::size_t>(i)] || !o.valid || !std::isnan(value_of(o, "lid_open")))
      continue;
    any_closed = true;
    cells.fill(i);
  }
  plpsty(0);
  return any_closed;
}

// Axes, title and a legend for the grey, hatched and black cells that are there.
void label_map(const Plan& plan, std::string_view value, const Scale& sc, bool any_closed) {
  const Range& rx = plan.ranges[0];
  const Range& ry = plan.ranges[1];
  plcol0(kInk);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  pllab(key_with_unit(rx.key).c_str(), key_with_unit(ry.key).c_str(),
        fmt::format("{} by {} and {}", with_unit(value), rx.key, ry.key).c_str());
  std::string legend;
  // "before the run ended": a grey machine may well get there given a longer run.t_max.
  if (sc.any_never) legend += fmt::format("grey: no {} before the run ended", value);
  if (any_closed) legend += fmt::format("{}hatched: the lid did not open", legend.empty() ? "" : "   ");
  if (sc.any_invalid)
    legend += fmt::format("{}black: invalid inputs or failed runs", legend.empty() ? "" : "   ");
  if (!legend.empty()) plmtex("b", 5.2, 0.0, 0.0, legend.c_str());
}

// Colour bar: a column of thin slices over the value's range, right of the map.
void draw_colour_bar(std::string_view value, const Scale& sc) {
  const double vmin = sc.vmin, vmax = sc.vmax;
  plvpor(0.86, 0.89, 0.16, 0.92);
  plwind(0.0, 1.0, vmin, vmax);
  constexpr int kSlices = 128;
  for (int s = 0; s < kSlices; ++s) {
    plcol1((s + 0.5) / kSlices);
    fill_rect(0.0, 1.0, vmin + (vmax - vmin) * s / kSlices, vmin + (vmax - vmin) * (s + 1) / kSlices);
  }
  plcol0(kInk);
  plbox("bc", 0.0, 0, "bcmstv", 0.0, 0);
  plmtex("t", 1.0, 0.5, 0.5, with_unit(value).c_str());
}
}  // namespace

void check_heatmap_plan(const Plan& plan, std::string_view option) {
  if (plan.samples > 0 || plan.ranges.size() != 2) {
    throw InputError(fmt::format("{}: a heat map needs a grid over exactly two keys (given {} --vary{})",
                                 option, plan.ranges.size(), plan.samples > 0 ? " and --samples" : ""));
  }
  for (const Range& r : plan.ranges) {
    if (r.n < 1) throw InputError(fmt::format("{}: --vary {} needs a count N", option, r.key));
  }
}

void draw_heatmap(const std::string& path, const Machines& machines, const SweepResult& result,
                  std::string_view value) {
  const Plan& plan = machines.plan();
  check_heatmap_plan(plan, "--heatmap");
  png_chart::check_writable(path);
  const Scale sc = scale_of(machines, result, value);
  begin_page(path);
  const Cells cells(plan);
  plvpor(0.10, 0.80, 0.16, 0.92);
  plwind(cells.x0, cells.x0 + cells.wx * std::max(1, plan.ranges[0].n), cells.y0,
         cells.y0 + cells.wy * std::max(1, plan.ranges[1].n));
  draw_cells(cells, machines, result, value, sc);
  const bool any_closed = value != "lid_open" && hatch_closed(cells, machines, result);
  label_map(plan, value, sc, any_closed);
  draw_colour_bar(value, sc);
  plend();
}

}  // namespace whatnext::viz
