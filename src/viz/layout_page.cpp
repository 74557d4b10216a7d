// A page of panels laid out in millimetres: the key to the event numbers under them, and the
// panels in a grid that share their bands' height, the room left of their axes and one title size.
#include <algorithm>
#include <cmath>

#include <fmt/format.h>

#include "figure.hpp"

namespace whatnext::viz::figure {

namespace {

// The key to the event numbers, under everything; shrunk if it would take too much room. Returns
// the height it takes from the page's bottom [mm].
double place_key(PageGeometry& pg, const Page& page) {
  const double ch = pg.ch;
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
  return key_top;
}

}  // namespace

PageGeometry layout_page(const Page& page) {
  PageGeometry pg;
  pg.w = page.width * kMmPerPt;
  pg.h = page.height * kMmPerPt;
  // PLplot's default for a 1000 x 650 page, scaled with the size of one panel.
  pg.ch = 5.82 * std::sqrt(page.width * static_cast<double>(page.height) / (page.nx * page.ny) / 650000.0) *
          page.text_scale;
  const double ch = pg.ch;

  const double key_top = place_key(pg, page);
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

}  // namespace whatnext::viz::figure
