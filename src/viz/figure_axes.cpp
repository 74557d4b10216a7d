// The figures' axes: the data's range, PLplot's tick spacing and numbers, and the table that
// lays out legends and the event key.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "figure.hpp"

namespace whatnext::viz::figure {

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

Grid grid(const std::vector<double>& widths, double x0, double x1, double spacing, std::size_t max_columns) {
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

}  // namespace whatnext::viz::figure
