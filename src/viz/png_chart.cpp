#include "png_chart.hpp"

#include <cmath>
#include <fstream>
#include <stdexcept>

#include <fmt/format.h>

#include "whatnext/output.hpp"

namespace whatnext::viz::png_chart {

void check_writable(const std::string& path) {
  bool ok = false;
  opening_by_name([&] { ok = static_cast<bool>(std::ofstream(path, std::ios::binary | std::ios::trunc)); });
  if (!ok) throw std::runtime_error(fmt::format("{}: cannot write this file", path));
}

void begin(const std::string& path, const Page& page) {
  plsdev("pngcairo");
  plsfnam(path.c_str());
  plspage(0.0, 0.0, page.width, page.height, 0, 0);
  plscolbg(255, 255, 255);
  plscol0(kInk, 0, 0, 0);
  for (std::size_t i = 0; i < page.colours.size(); ++i) {
    const Rgb& c = page.colours[i];
    plscol0(kFirstColour + static_cast<PLINT>(i), c.red, c.green, c.blue);
  }
  if (!page.ramp.empty()) {
    std::vector<PLFLT> pos, red, green, blue;
    for (const RampPoint& p : page.ramp) {
      pos.push_back(p.position), red.push_back(p.red), green.push_back(p.green), blue.push_back(p.blue);
    }
    plscmap1n(256);
    plscmap1l(1, static_cast<PLINT>(page.ramp.size()), pos.data(), red.data(), green.data(), blue.data(),
              nullptr);
  }
  opening_by_name([] { plinit(); });
  pladv(0);
  plschr(0.0, 0.9);
}

void fill_rect(double x0, double x1, double y0, double y1) {
  PLFLT x[4] = {x0, x1, x1, x0};
  PLFLT y[4] = {y0, y0, y1, y1};
  plfill(4, x, y);
}

void usable_range(double& lo, double& hi) {
  if (!(lo <= hi)) lo = 0.0, hi = 1.0;
  if (hi - lo < 1e-12 * (1.0 + std::fabs(hi))) {
    const double pad = std::fmax(1e-9, 1e-3 * std::fabs(hi));
    lo -= pad, hi += pad;
  }
}

}  // namespace whatnext::viz::png_chart
