// Placing labels where they hide nothing: the two small helpers the figures and the animation share.
#pragma once

#include <algorithm>
#include <cstddef>
#include <vector>

namespace whatnext::viz::placement {

// Does the segment (ax, ay)-(cx, cy) cross the box [x0, x1] x [y0, y1]? (Liang-Barsky clipping.)
inline bool segment_crosses_box(double x0, double y0, double x1, double y1, double ax, double ay, double cx,
                                double cy) {
  double t0 = 0.0, t1 = 1.0;
  const double dx = cx - ax, dy = cy - ay;
  const double p[4] = {-dx, dx, -dy, dy};
  const double q[4] = {ax - x0, x1 - ax, ay - y0, y1 - ay};
  for (int i = 0; i < 4; ++i) {
    if (p[i] == 0.0) {
      if (q[i] < 0.0) return false;
    } else {
      const double r = q[i] / p[i];
      if (p[i] < 0.0)
        t0 = std::max(t0, r);
      else
        t1 = std::min(t1, r);
      if (t0 > t1) return false;
    }
  }
  return true;
}

// Centres for labels of widths w that want to sit at centres c (in increasing order), in one row
// between lo and hi and at least gap apart, each as near its wish as the others allow. False if
// they do not fit.
inline bool pack_row(const std::vector<double>& c, const std::vector<double>& w, double lo, double hi,
                     double gap, std::vector<double>& pos) {
  const std::size_t n = c.size();
  pos.assign(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    pos[i] = std::max(c[i], lo + 0.5 * w[i]);
    if (i > 0) pos[i] = std::max(pos[i], pos[i - 1] + 0.5 * (w[i - 1] + w[i]) + gap);
  }
  for (std::size_t k = n; k-- > 0;) {
    pos[k] = std::min(pos[k], hi - 0.5 * w[k]);
    if (k + 1 < n) pos[k] = std::min(pos[k], pos[k + 1] - 0.5 * (w[k] + w[k + 1]) - gap);
  }
  return n == 0 || pos[0] >= lo + 0.5 * w[0] - 1e-9;
}

}  // namespace whatnext::viz::placement
