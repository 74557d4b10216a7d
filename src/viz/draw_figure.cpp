// Drawing a laid-out page with PLplot (C API): PNG and PDF through its Cairo drivers, SVG through
// its svg driver, which writes text as <text> (Cairo's SVG surface turns every glyph into an
// outline). Every position comes from the layout (figure.hpp); this file only draws.
#include <plplot/plplot.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ctime>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <optional>

#include <fmt/format.h>

#include "figure.hpp"
#include "whatnext/config.hpp"
#include "whatnext/output.hpp"

namespace whatnext::viz::figure {

namespace fs = std::filesystem;

namespace {

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

// The axes with their grid, tick numbers and titles.
void draw_axes(const Panel& p, const PanelGeometry& g, const PageGeometry& pg) {
  const double ch = g.h;
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
}

// The reference levels (dotted) and the events (dashed), in the data window.
void draw_reference_lines(const Panel& p, const PanelGeometry& g) {
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
}

// The curves (lines or dots) and the marked points.
void draw_curves(const Panel& p, const PanelGeometry& g) {
  plschr(g.h, 1.0);
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
}

// Everything placed in millimetres: legends, event numbers, leaders, labels, the title.
void draw_placed(const PanelGeometry& g, const PageGeometry& pg) {
  mm_space(pg);
  for (const Segment& s : g.strokes) {
    plcol0(s.colour);
    if (s.style == 0) {
      plschr(g.h, 1.0);
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

void draw_panel(const Panel& p, const PanelGeometry& g, const PageGeometry& pg) {
  if (!p.modes.empty()) draw_mode_strip(p, g, pg);
  draw_axes(p, g, pg);
  draw_reference_lines(p, g);
  draw_curves(p, g);
  draw_placed(g, pg);
}

}  // namespace

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
    // PLplot opens the temporary by name and ends the whole process when it cannot: a folder
    // removed while the figures are drawn is said here in one line instead (what is left is the
    // moment between this look and PLplot's own open).
    std::error_code gone;
    if (!fs::exists(file->temp_path(), gone)) {
      throw OutputError(
          fmt::format("--out {}: its folder was removed while the figures were drawn", printable(path, 96)));
    }
    opening_by_name([] { plinit(); });
    pladv(0);
    for (std::size_t i = 0; i < page.panels.size(); ++i) draw_panel(page.panels[i], pg.panels[i], pg);
    mm_space(pg);
    for (const Text& t : pg.texts) draw_text(t);
    plend1();
    utc.reset();
    if (f == Format::pdf) opening_by_name([&] { pin_pdf_date(file->temp_path(), path); });
    file->commit();
    written.push_back(path);
  }
  return written;
}

}  // namespace whatnext::viz::figure
