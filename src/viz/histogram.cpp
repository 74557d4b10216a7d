#include "whatnext/viz/histogram.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "png_chart.hpp"

namespace whatnext::viz {

namespace {
using png_chart::fill_rect;
using png_chart::kInk;
constexpr PLINT kBar = png_chart::kFirstColour, kMark = kBar + 1;
}  // namespace

void draw_histogram(const std::string& path, const std::vector<double>& values, double mark,
                    const HistogramText& text) {
  png_chart::check_writable(path);
  double lo = INFINITY, hi = -INFINITY;
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    lo = std::fmin(lo, v);
    hi = std::fmax(hi, v);
  }
  if (std::isfinite(mark)) lo = std::fmin(lo, mark), hi = std::fmax(hi, mark);
  png_chart::usable_range(lo, hi);
  // About the square root of the count of bins (at least 10, at most 60): enough to show the
  // shape without every bin being noise.
  const int bins = std::clamp(static_cast<int>(std::sqrt(static_cast<double>(values.size()))), 10, 60);
  const double width = (hi - lo) / bins;
  std::vector<double> count(static_cast<std::size_t>(bins), 0.0);
  for (double v : values) {
    if (!std::isfinite(v)) continue;
    const int b = std::clamp(static_cast<int>((v - lo) / width), 0, bins - 1);
    count[static_cast<std::size_t>(b)] += 1.0;
  }
  const double top = std::max(1.0, *std::max_element(count.begin(), count.end())) * 1.08;

  png_chart::begin(path, {960, 640, {{59, 82, 139}, {220, 80, 30}}, {}});  // kBar, kMark
  plvpor(0.10, 0.95, 0.18, 0.90);
  plsxax(8, 0);  // times as they are (0.55), not scaled to 5.5 with an (x10^-1) beside the axis
  plwind(lo - 0.02 * (hi - lo), hi + 0.02 * (hi - lo), 0.0, top);
  plcol0(kBar);
  for (int b = 0; b < bins; ++b) {
    if (count[static_cast<std::size_t>(b)] > 0.0) {
      fill_rect(lo + width * b, lo + width * (b + 1), 0.0, count[static_cast<std::size_t>(b)]);
    }
  }
  if (std::isfinite(mark)) {
    plcol0(kMark);
    plwidth(2.5);
    PLFLT x[2] = {mark, mark};
    PLFLT y[2] = {0.0, top};
    plline(2, x, y);
    plwidth(1.0);
  }
  plcol0(kInk);
  plbox("bcnst", 0.0, 0, "bcnstv", 0.0, 0);
  pllab(text.x_label.c_str(), "machines", text.title.c_str());
  if (!text.note.empty()) plmtex("b", 5.0, 0.0, 0.0, text.note.c_str());
  plend();
}

}  // namespace whatnext::viz
