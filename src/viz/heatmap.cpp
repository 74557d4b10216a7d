#include "whatnext/viz/heatmap.hpp"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>
#include <plplot/plplot.h>

#include "whatnext/config.hpp"

namespace whatnext::viz {

using explore::Machines;
using explore::Outcome;
using explore::Plan;
using explore::Range;
using explore::SweepResult;
using explore::value_of;

namespace {
// Colour map 0 slots used here (0 is the background).
constexpr PLINT kInk = 1, kNever = 2, kInvalid = 3;

std::string with_unit(std::string_view value) {
  const char* unit = value == "final_r" ? "m" : value == "final_phi_l_deg" ? "deg" : "s";
  return fmt::format("{} [{}]", value, unit);
}

// An input key with its unit, for an axis: "geometry.rope_length [m]".
std::string key_with_unit(const std::string& key) {
  const KeySpec* spec = find_key(key);
  return spec && !spec->unit.empty() ? fmt::format("{} [{}]", key, spec->unit) : key;
}

void fill_rect(double x0, double x1, double y0, double y1) {
  PLFLT x[4] = {x0, x1, x1, x0};
  PLFLT y[4] = {y0, y0, y1, y1};
  plfill(4, x, y);
}

// Cell edges of a grid range: each value sits in the middle of its cell.
void cell_edges(const Range& r, double& lo, double& width) {
  width = r.n > 1 ? (r.hi - r.lo) / (r.n - 1)
                  : (r.hi > r.lo ? r.hi - r.lo : std::fmax(1e-3, std::fabs(r.lo) * 0.1));
  lo = r.lo - 0.5 * width;
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
  const Range& rx = plan.ranges[0];
  const Range& ry = plan.ranges[1];
  {
    // PLplot ends the process when it cannot open its file, so find that out first.
    std::ofstream probe(path, std::ios::binary | std::ios::trunc);
    if (!probe) throw std::runtime_error(fmt::format("{}: cannot write this file", path));
  }

  double vmin = INFINITY, vmax = -INFINITY;
  bool any_never = false, any_invalid = false;
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    if (!result.done[static_cast<std::size_t>(i)]) continue;
    const Outcome& o = result.rows[static_cast<std::size_t>(i)];
    if (!o.valid) {
      any_invalid = true;
      continue;
    }
    const double v = value_of(o, value);
    if (std::isnan(v)) {
      any_never = true;
      continue;
    }
    vmin = std::fmin(vmin, v);
    vmax = std::fmax(vmax, v);
  }
  if (!(vmin <= vmax)) vmin = 0.0, vmax = 1.0;
  if (vmax - vmin < 1e-12 * (1.0 + std::fabs(vmax))) {
    const double pad = std::fmax(1e-9, 1e-3 * std::fabs(vmax));
    vmin -= pad, vmax += pad;
  }

  plsdev("pngcairo");
  plsfnam(path.c_str());
  plspage(0.0, 0.0, 960, 720, 0, 0);
  plscolbg(255, 255, 255);
  plscol0(kInk, 0, 0, 0);
  plscol0(kNever, 190, 190, 190);
  plscol0(kInvalid, 40, 40, 40);
  // A dark-blue to yellow ramp that stays readable in greyscale (viridis' end points and middle).
  const PLFLT pos[3] = {0.0, 0.5, 1.0};
  const PLFLT red[3] = {0.267, 0.128, 0.993};
  const PLFLT green[3] = {0.005, 0.567, 0.906};
  const PLFLT blue[3] = {0.329, 0.551, 0.144};
  plscmap1n(256);
  plscmap1l(1, 3, pos, red, green, blue, nullptr);
  plinit();
  pladv(0);
  plschr(0.0, 0.9);

  double x0, wx, y0, wy;
  cell_edges(rx, x0, wx);
  cell_edges(ry, y0, wy);
  const double x_hi = x0 + wx * std::max(1, rx.n), y_hi = y0 + wy * std::max(1, ry.n);
  plvpor(0.10, 0.80, 0.16, 0.92);
  plwind(x0, x_hi, y0, y_hi);
  for (std::int64_t i = 0; i < machines.size(); ++i) {
    if (!result.done[static_cast<std::size_t>(i)]) continue;
    const Outcome& o = result.rows[static_cast<std::size_t>(i)];
    const auto ix = i / ry.n, iy = i % ry.n;  // the last key varies fastest
    const double v = value_of(o, value);
    if (!o.valid) {
      plcol0(kInvalid);
    } else if (std::isnan(v)) {
      plcol0(kNever);
    } else {
      plcol1((v - vmin) / (vmax - vmin));
    }
    const double cx = x0 + wx * static_cast<double>(ix), cy = y0 + wy * static_cast<double>(iy);
    fill_rect(cx, cx + wx, cy, cy + wy);
  }
  // Whatever is drawn, machines whose lid did not open in their run stay recognisable: hatched.
  bool any_closed = false;
  if (value != "lid_open") {
    plcol0(kInk);
    plpsty(3);
    for (std::int64_t i = 0; i < machines.size(); ++i) {
      const Outcome& o = result.rows[static_cast<std::size_t>(i)];
      if (!result.done[static_cast<std::size_t>(i)] || !o.valid || !std::isnan(value_of(o, "lid_open")))
        continue;
      any_closed = true;
      const double cx = x0 + wx * static_cast<double>(i / ry.n), cy = y0 + wy * static_cast<double>(i % ry.n);
      fill_rect(cx, cx + wx, cy, cy + wy);
    }
    plpsty(0);
  }
  plcol0(kInk);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  pllab(key_with_unit(rx.key).c_str(), key_with_unit(ry.key).c_str(),
        fmt::format("{} by {} and {}", with_unit(value), rx.key, ry.key).c_str());
  std::string legend;
  // "before the run ended": a grey machine may well get there given a longer run.t_max.
  if (any_never) legend += fmt::format("grey: no {} before the run ended", value);
  if (any_closed) legend += fmt::format("{}hatched: the lid did not open", legend.empty() ? "" : "   ");
  if (any_invalid)
    legend += fmt::format("{}black: invalid inputs or failed runs", legend.empty() ? "" : "   ");
  if (!legend.empty()) plmtex("b", 5.2, 0.0, 0.0, legend.c_str());

  // Colour bar: a column of thin slices over the value's range.
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
  plend();
}

}  // namespace whatnext::viz
