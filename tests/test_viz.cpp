// Pictures (issue 3): every output decodes, has the requested size and content, and the animation
// draws the sandbag where the simulation puts it.
#include <cairo.h>
#include <expat.h>
#include <gif_lib.h>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <set>
#include <string>
#include <vector>

#include <unistd.h>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/output.hpp"
#include "whatnext/viz/animation.hpp"
#include "whatnext/viz/plots.hpp"
#include "cli_runner.hpp"
#include "viz/scene.hpp"  // internal: the scene the animation and the page draw

namespace fs = std::filesystem;
using namespace whatnext;
using namespace whatnext::viz;

namespace {

Scenario example(int n) { return build_scenario(example_config(n)); }

// An empty folder of the given name under the temporary directory; the pid keeps runs of the
// same test in other build trees (or worktrees) apart (a fixed name let parallel runs collide).
fs::path fresh_dir(const std::string& name) {
  // Removed when the test program ends (named by pid, they would pile up run after run).
  static struct Made {
    std::vector<fs::path> dirs;
    ~Made() {
      std::error_code ec;
      for (const fs::path& d : dirs) fs::remove_all(d, ec);
    }
  } made;
  const fs::path dir =
      fs::temp_directory_path() / ("whatnext_test_viz_" + name + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  made.dirs.push_back(dir);
  return dir;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct Png {
  int width = 0, height = 0;
  std::set<std::uint32_t> colours;
  int count(Rgb c) const { return counts.count(key(c)) ? counts.at(key(c)) : 0; }
  static std::uint32_t key(Rgb c) { return (c.r << 16) | (c.g << 8) | c.b; }
  std::map<std::uint32_t, int> counts;
};

// A PNG's pixels as 0xRRGGBB, row by row from the top (empty, with a failure, if it does not decode).
struct Pixels {
  int width = 0, height = 0;
  std::vector<std::uint32_t> rgb;
  std::uint32_t at(int x, int y) const { return rgb[static_cast<std::size_t>(y) * width + x]; }
};

Pixels read_pixels(const fs::path& path) {
  cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
  Pixels img;
  if (cairo_surface_status(s) != CAIRO_STATUS_SUCCESS) {
    cairo_surface_destroy(s);
    ADD_FAILURE() << path << " does not decode as PNG";
    return img;
  }
  img.width = cairo_image_surface_get_width(s);
  img.height = cairo_image_surface_get_height(s);
  const unsigned char* data = cairo_image_surface_get_data(s);
  const int stride = cairo_image_surface_get_stride(s);
  img.rgb.reserve(static_cast<std::size_t>(img.width) * img.height);
  for (int y = 0; y < img.height; ++y) {
    const auto* row = reinterpret_cast<const std::uint32_t*>(data + y * stride);
    for (int x = 0; x < img.width; ++x) img.rgb.push_back(row[x] & 0xffffff);
  }
  cairo_surface_destroy(s);
  return img;
}

Png read_png(const fs::path& path) {
  const Pixels img = read_pixels(path);
  Png png;
  png.width = img.width;
  png.height = img.height;
  for (const std::uint32_t v : img.rgb) {
    png.colours.insert(v);
    ++png.counts[v];
  }
  return png;
}

// Root element name of a well-formed XML file ("" if it does not parse).
std::string xml_root(const fs::path& path) {
  const std::string text = slurp(path);
  XML_Parser parser = XML_ParserCreate(nullptr);
  std::string root;
  XML_SetUserData(parser, &root);
  XML_SetStartElementHandler(parser, [](void* user, const XML_Char* name, const XML_Char**) {
    auto* r = static_cast<std::string*>(user);
    if (r->empty()) *r = name;
  });
  const bool ok = XML_Parse(parser, text.data(), static_cast<int>(text.size()), 1) == XML_STATUS_OK;
  XML_ParserFree(parser);
  return ok ? root : "";
}

// A decoded GIF with every frame composited over the previous one, as a viewer shows it.
struct Gif {
  int width = 0, height = 0;
  std::vector<std::vector<Rgb>> frames;
  std::vector<int> delays_cs;
};

Gif read_gif(const fs::path& path) {
  Gif out;
  int err = 0;
  GifFileType* gif = DGifOpenFileName(path.c_str(), &err);
  if (!gif) {
    ADD_FAILURE() << path << " does not open as GIF";
    return out;
  }
  if (DGifSlurp(gif) != GIF_OK) {
    ADD_FAILURE() << path << " does not decode as GIF";
    DGifCloseFile(gif, &err);
    return out;
  }
  out.width = gif->SWidth;
  out.height = gif->SHeight;
  std::vector<Rgb> canvas(static_cast<std::size_t>(out.width) * out.height, Rgb{0, 0, 0});
  for (int i = 0; i < gif->ImageCount; ++i) {
    const SavedImage& img = gif->SavedImages[i];
    GraphicsControlBlock gcb{};
    gcb.TransparentColor = NO_TRANSPARENT_COLOR;
    DGifSavedExtensionToGCB(gif, i, &gcb);
    const ColorMapObject* map = img.ImageDesc.ColorMap ? img.ImageDesc.ColorMap : gif->SColorMap;
    const GifImageDesc& d = img.ImageDesc;
    for (int y = 0; y < d.Height; ++y) {
      for (int x = 0; x < d.Width; ++x) {
        const int v = img.RasterBits[y * d.Width + x];
        if (v == gcb.TransparentColor) continue;
        const GifColorType c = map->Colors[v];
        canvas[(d.Top + y) * out.width + d.Left + x] = {c.Red, c.Green, c.Blue};
      }
    }
    out.frames.push_back(canvas);
    out.delays_cs.push_back(gcb.DelayTime);
  }
  DGifCloseFile(gif, &err);
  return out;
}

bool same(Rgb a, Rgb b) { return a.r == b.r && a.g == b.g && a.b == b.b; }

AnimationOptions small_animation() {
  AnimationOptions o;
  o.width = 240;
  o.height = 180;
  o.fps = 10;
  o.slowmo = 3;
  o.hold = 0.5;
  return o;
}

// A text box must not touch a polyline: checked by walking every segment in 0.05 mm steps.
bool touches(const Box& b, const std::vector<std::pair<double, double>>& line) {
  auto in = [&](double x, double y) { return x >= b.x0 && x <= b.x1 && y >= b.y0 && y <= b.y1; };
  if (line.size() == 1) return in(line[0].first, line[0].second);
  for (std::size_t i = 1; i < line.size(); ++i) {
    const auto [ax, ay] = line[i - 1];
    const auto [cx, cy] = line[i];
    const int n = 1 + static_cast<int>(std::hypot(cx - ax, cy - ay) / 0.05);
    for (int k = 0; k <= n; ++k) {
      const double f = static_cast<double>(k) / n;
      if (in(ax + f * (cx - ax), ay + f * (cy - ay))) return true;
    }
  }
  return false;
}
bool overlaps(const Box& a, const Box& b) { return a.x0 < b.x1 && b.x0 < a.x1 && a.y0 < b.y1 && b.y0 < a.y1; }
bool within(const Box& a, const Box& b) {
  return a.x0 >= b.x0 && a.x1 <= b.x1 && a.y0 >= b.y0 && a.y1 <= b.y1;
}

// What every figure page promises: texts stay on the page and apart, legends and the event key stay
// out of the axes, and what is inside the axes touches no curve.
void check_layout(const PageLayout& page) {
  SCOPED_TRACE(page.name);
  const Box whole{0.0, 0.0, page.width, page.height};
  for (std::size_t i = 0; i < page.texts.size(); ++i) {
    const PlacedText& t = page.texts[i];
    SCOPED_TRACE(t.text);
    EXPECT_TRUE(within(t.box, whole));
    for (std::size_t j = i + 1; j < page.texts.size(); ++j) {
      EXPECT_FALSE(overlaps(t.box, page.texts[j].box)) << "overlaps " << page.texts[j].text;
    }
    for (const Box& r : page.axis_labels) EXPECT_FALSE(overlaps(t.box, r)) << "on the axis labels";
    for (const Box& s : page.legend_samples) EXPECT_FALSE(overlaps(t.box, s)) << "on a legend sample";
    bool in_axes = false;
    for (const Box& a : page.axes) in_axes = in_axes || overlaps(t.box, a);
    if (t.kind == PlacedText::legend || t.kind == PlacedText::key || t.kind == PlacedText::title) {
      EXPECT_FALSE(in_axes) << "inside the axes";
    }
    if (in_axes) {
      for (const Box& a : page.axes) {
        if (overlaps(t.box, a)) {
          EXPECT_TRUE(within(t.box, a)) << "across the axes' edge";
        }
      }
      for (const auto& line : page.data) EXPECT_FALSE(touches(t.box, line)) << "hides data";
    }
  }
  for (const Box& s : page.legend_samples) {
    for (const Box& a : page.axes) EXPECT_FALSE(overlaps(s, a)) << "legend sample inside the axes";
  }
}

}  // namespace

TEST(VizPlots, FigureSetDecodesWithSizeAndContent) {
  const fs::path dir = fresh_dir("figures");
  FigureOptions opts;
  opts.width = 500;
  opts.height = 320;
  opts.title = "example 1";
  const auto files = write_run_figures(record(example(1)), dir.string(), opts);
  ASSERT_EQ(files.size(), 7u * 3u);
  for (const char* name :
       {"sandbag_x", "sandbag_h", "trajectory", "angles", "balloon", "energy", "overview"}) {
    SCOPED_TRACE(name);
    const bool overview = std::string(name) == "overview";
    const Png png = read_png(dir / (std::string(name) + ".png"));
    EXPECT_EQ(png.width, overview ? 500 * 9 / 5 : 500);
    EXPECT_EQ(png.height, overview ? 320 * 3 / 2 : 320);
    // Antialiased curves, text and the mode strip: a blank or one-line picture has far fewer.
    EXPECT_GT(png.colours.size(), 40u);
    EXPECT_EQ(xml_root(dir / (std::string(name) + ".svg")), "svg");
    const std::string pdf = slurp(dir / (std::string(name) + ".pdf"));
    EXPECT_EQ(pdf.rfind("%PDF-", 0), 0u);
    EXPECT_NE(pdf.find("%%EOF"), std::string::npos);
  }
  // The angle plot draws phiS in blue and phiL in orange.
  const Png angles = read_png(dir / "angles.png");
  EXPECT_GT(angles.count({31, 119, 180}), 200);
  EXPECT_GT(angles.count({230, 120, 20}), 200);
  // Nothing half-written is left behind.
  for (const auto& e : fs::directory_iterator(dir)) EXPECT_NE(e.path().extension(), ".part");
}

TEST(VizPlots, TextNeverHidesDataOrOtherText) {
  for (int n = 1; n <= 4; ++n) {
    SCOPED_TRACE("example " + std::to_string(n));
    const fs::path dir = fresh_dir("layout" + std::to_string(n));
    FigureOptions opts;
    opts.formats = {Format::png};
    opts.title = "example " + std::to_string(n);
    std::vector<PageLayout> pages;
    const Scenario sc = example(n);
    write_run_figures(record(sc), dir.string(), opts, &pages);
    write_law_comparison(sc, dir.string(), opts, &pages);
    write_integrator_comparison(sc, IntegratorKind::euler, 0.002, dir.string(), opts, &pages);
    ASSERT_EQ(pages.size(), 9u);
    int numbers = 0;
    for (const PageLayout& page : pages) {
      check_layout(page);
      for (const PlacedText& t : page.texts) numbers += t.kind == PlacedText::event_number;
    }
    EXPECT_GT(numbers, 0);
  }
}

// Left of every plot PLplot writes the tick numbers and the y axis' title. The layout says where
// (axis_texts): those boxes must not overlap, and every inked pixel left of the axes must lie in
// one of them, so the PNG's numbers and title are really apart however wide the numbers get. In
// example 3's trajectory "-2000" ran into "h [m] (above the pivot)".
TEST(VizPlots, AxisTitleClearsTheTickNumbers) {
  std::vector<std::pair<std::string, Scenario>> runs;
  for (int n = 1; n <= 4; ++n) runs.emplace_back("example " + std::to_string(n), example(n));
  runs.emplace_back("radio",
                    build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml")));
  int panels = 0;
  for (const auto& [name, sc] : runs) {
    SCOPED_TRACE(name);
    const fs::path dir = fresh_dir("ticks");
    FigureOptions opts;
    opts.formats = {Format::png};
    opts.title = name;
    std::vector<PageLayout> pages;
    write_run_figures(record(sc), dir.string(), opts, &pages);
    write_law_comparison(sc, dir.string(), opts, &pages);
    for (const PageLayout& page : pages) {
      SCOPED_TRACE(page.name);
      for (std::size_t i = 0; i < page.axis_texts.size(); ++i) {
        for (std::size_t j = i + 1; j < page.axis_texts.size(); ++j) {
          EXPECT_FALSE(overlaps(page.axis_texts[i].box, page.axis_texts[j].box))
              << page.axis_texts[i].text << " on " << page.axis_texts[j].text;
        }
      }
      const Pixels img = read_pixels(dir / (page.name + ".png"));
      ASSERT_GT(img.width, 0);
      const int w = img.width, h = img.height;
      const double px = w / page.width;
      for (const Box& a : page.axes) {
        // The room left of these axes, as the layout reserves it for PLplot's texts.
        const Box* room = nullptr;
        for (const Box& r : page.axis_labels) {
          if (std::fabs(r.x1 - a.x0) < 1e-9 && r.y1 > a.y1) room = &r;
        }
        ASSERT_NE(room, nullptr);
        int inked = 0, stray = 0;
        for (int y = static_cast<int>(h - room->y1 * px) + 1; y < static_cast<int>(h - room->y0 * px); ++y) {
          for (int x = static_cast<int>(std::ceil(room->x0 * px)); x < static_cast<int>(a.x0 * px) - 1; ++x) {
            if (img.at(x, y) == 0xffffff) continue;
            ++inked;
            const double mx = (x + 0.5) / px, my = (h - y - 0.5) / px;
            bool known = false;
            for (const PlacedText& t : page.axis_texts) {
              known = known || (mx > t.box.x0 - 0.25 && mx < t.box.x1 + 0.25 && my > t.box.y0 - 0.25 &&
                                my < t.box.y1 + 0.25);
            }
            stray += !known;
          }
        }
        EXPECT_GT(inked, 200);
        EXPECT_EQ(stray, 0) << "ink left of the axes outside the tick numbers and the title";
        ++panels;
      }
    }
  }
  EXPECT_GT(panels, 60);
}

// A long input name shrinks the titles that would not fit; the titles of one page then share that
// size (with the radio example's path, three of the overview's six titles were smaller).
TEST(VizPlots, TitlesOfAPageShareOneSize) {
  const Scenario radio =
      build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml"));
  FigureOptions opts;
  opts.formats = {Format::png};
  opts.title = "examples/example1-radio.toml";
  std::vector<PageLayout> pages;
  write_run_figures(record(radio), fresh_dir("titles").string(), opts, &pages);
  write_law_comparison(radio, fresh_dir("titles").string(), opts, &pages);
  for (const PageLayout& page : pages) {
    SCOPED_TRACE(page.name);
    std::vector<double> heights;
    for (const PlacedText& t : page.texts) {
      if (t.kind == PlacedText::title) heights.push_back(t.box.y1 - t.box.y0);
    }
    ASSERT_FALSE(heights.empty());
    for (double h : heights) EXPECT_NEAR(h, heights.front(), 1e-9);
  }
}

TEST(VizPlots, TrajectoryIsToScaleOrSaysSo) {
  bool stretched = false, scaled = false;
  for (int n = 1; n <= 4; ++n) {
    SCOPED_TRACE("example " + std::to_string(n));
    FigureOptions opts;
    opts.formats = {Format::png};
    std::vector<PageLayout> pages;
    write_run_figures(record(example(n)), fresh_dir("scale").string(), opts, &pages);
    const PageLayout& tr = pages.at(2);
    ASSERT_EQ(tr.name, "trajectory");
    std::string title;
    for (const PlacedText& t : tr.texts) {
      if (t.kind == PlacedText::title) title = t.text;
    }
    const Box& a = tr.axes.at(0);
    const Box& w = tr.windows.at(0);
    const double mx = (w.x1 - w.x0) / (a.x1 - a.x0), my = (w.y1 - w.y0) / (a.y1 - a.y0);
    if (title.find("(to scale)") != std::string::npos) {
      EXPECT_NEAR(mx / my, 1.0, 1e-9);
      scaled = true;
    } else {
      ASSERT_NE(title.find("not to scale"), std::string::npos) << title;
      EXPECT_GT(std::max(mx / my, my / mx), 8.0);
      stretched = true;
    }
  }
  EXPECT_TRUE(scaled);     // examples 1 and 2
  EXPECT_TRUE(stretched);  // 3 and 4: 2 km down, 30 m across
}

// The measured text widths are not too small: just right of every legend entry, key entry and
// title the PNG is blank (in pixels: the Cairo drivers draw one pixel per point).
TEST(VizPlots, TextIsNoWiderThanMeasured) {
  const fs::path dir = fresh_dir("widths");
  FigureOptions opts;
  opts.formats = {Format::png};
  opts.title = "example 4";
  std::vector<PageLayout> pages;
  write_run_figures(record(example(4)), dir.string(), opts, &pages);
  int checked = 0;
  for (const PageLayout& page : pages) {
    SCOPED_TRACE(page.name);
    const Pixels img = read_pixels(dir / (page.name + ".png"));
    ASSERT_GT(img.width, 0);
    const int w = img.width, h = img.height;
    const double px_per_mm = w / page.width;
    for (const PlacedText& t : page.texts) {
      if (t.kind != PlacedText::legend && t.kind != PlacedText::key && t.kind != PlacedText::title) continue;
      SCOPED_TRACE(t.text);
      // From 0.3 mm to 1.2 mm right of the box, over the middle of its height.
      const int x0 = static_cast<int>(std::ceil((t.box.x1 + 0.3) * px_per_mm));
      const int x1 = std::min(w - 1, static_cast<int>((t.box.x1 + 1.2) * px_per_mm));
      const int y0 = static_cast<int>(h - (t.box.y1 - 0.2 * (t.box.y1 - t.box.y0)) * px_per_mm);
      const int y1 = static_cast<int>(h - (t.box.y0 + 0.3 * (t.box.y1 - t.box.y0)) * px_per_mm);
      int ink = 0;
      for (int y = std::max(0, y0); y <= std::min(h - 1, y1); ++y) {
        for (int x = x0; x <= x1; ++x) ink += img.at(x, y) != 0xffffff;
      }
      EXPECT_EQ(ink, 0);
      ++checked;
    }
  }
  EXPECT_GT(checked, 20);
}

// PLplot's svg driver writes text as <text> elements (Cairo's SVG would draw outlines).
TEST(VizPlots, SvgKeepsTextAsText) {
  const fs::path dir = fresh_dir("svgtext");
  FigureOptions opts;
  opts.formats = {Format::svg};
  write_run_figures(record(example(1)), dir.string(), opts);
  struct Collect {
    int depth = 0, elements = 0;
    std::string text;
  } c;
  const std::string svg = slurp(dir / "angles.svg");
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &c);
  XML_SetElementHandler(
      parser,
      [](void* u, const XML_Char* name, const XML_Char**) {
        auto* c = static_cast<Collect*>(u);
        if (std::string(name) == "text") ++c->depth, ++c->elements;
      },
      [](void* u, const XML_Char* name) {
        auto* c = static_cast<Collect*>(u);
        if (std::string(name) == "text") --c->depth, c->text += '|';
      });
  XML_SetCharacterDataHandler(parser, [](void* u, const XML_Char* s, int len) {
    auto* c = static_cast<Collect*>(u);
    if (c->depth > 0) c->text.append(s, static_cast<std::size_t>(len));
  });
  ASSERT_EQ(XML_Parse(parser, svg.data(), static_cast<int>(svg.size()), 1), XML_STATUS_OK);
  XML_ParserFree(parser);
  EXPECT_GT(c.elements, 20);
  for (const char* words : {"seesaw and lid angles", "0.820 s lid open", "angle [deg]", "φ", "time t [s]"}) {
    EXPECT_NE(c.text.find(words), std::string::npos) << words;
  }
}

TEST(VizPlots, SameInputSameBytes) {
  FigureOptions opts;
  opts.width = 300;
  opts.height = 200;
  const Recording rec = record(example(2));
  const fs::path a = fresh_dir("det_a"), b = fresh_dir("det_b");
  write_run_figures(rec, a.string(), opts);
  write_run_figures(rec, b.string(), opts);
  for (const char* f : {"angles.png", "angles.svg", "angles.pdf", "overview.pdf"}) {
    EXPECT_EQ(slurp(a / f), slurp(b / f)) << f;
  }
}

TEST(VizPlots, LawComparisonDrawsFourLaws) {
  const fs::path dir = fresh_dir("laws");
  FigureOptions opts;
  opts.width = 500;
  opts.height = 320;
  opts.formats = {Format::png, Format::svg};
  const auto files = write_law_comparison(example(2), dir.string(), opts);
  ASSERT_EQ(files.size(), 2u);
  const Png png = read_png(dir / "compare_laws.png");
  EXPECT_EQ(png.width, 500);
  EXPECT_EQ(png.height, 320 * 8 / 5);
  // One colour per law: blue, orange, green, red.
  for (Rgb c : {Rgb{31, 119, 180}, Rgb{230, 120, 20}, Rgb{44, 160, 44}, Rgb{214, 39, 40}}) {
    EXPECT_GT(png.count(c), 30) << int(c.r) << "," << int(c.g) << "," << int(c.b);
  }
  EXPECT_EQ(xml_root(dir / "compare_laws.svg"), "svg");
}

TEST(VizPlots, IntegratorComparisonAndBadInput) {
  const fs::path dir = fresh_dir("integrator");
  FigureOptions opts;
  opts.width = 400;
  opts.height = 260;
  opts.formats = {Format::png};
  write_integrator_comparison(example(1), IntegratorKind::euler, 0.002, dir.string(), opts);
  const Png png = read_png(dir / "compare_integrator.png");
  EXPECT_EQ(png.width, 400);
  EXPECT_GT(png.count({214, 39, 40}), 30);  // the fixed-step energy curve
  EXPECT_THROW(write_integrator_comparison(example(1), IntegratorKind::adaptive, 0.001, dir.string(), opts),
               InputError);
  EXPECT_THROW(write_run_figures(record(example(1)), "/proc/whatnext/no", opts), InputError);
  std::vector<Format> f;
  EXPECT_TRUE(parse_formats("svg,png", f));
  EXPECT_EQ(f.size(), 2u);
  EXPECT_FALSE(parse_formats("png,jpg", f));
}

TEST(VizAnimation, FramesHoldEveryEventOnce) {
  const Recording rec = record(example(1));
  const AnimationOptions o = small_animation();
  const auto frames = plan_frames(rec, o);
  const auto groups = group_events(rec.result);
  std::vector<int> held;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    if (i > 0) {
      EXPECT_GE(frames[i].t, frames[i - 1].t);
    }
    if (frames[i].event_group >= 0) {
      held.push_back(frames[i].event_group);
      EXPECT_DOUBLE_EQ(frames[i].t, groups[frames[i].event_group].t);
      EXPECT_GE(frames[i].delay, o.hold);
    }
  }
  ASSERT_EQ(held.size(), groups.size());
  for (std::size_t g = 0; g < groups.size(); ++g) EXPECT_EQ(held[g], static_cast<int>(g));
  // Slow motion: the regular frames advance 1 / (fps * slowmo) of simulated time.
  EXPECT_NEAR(frames[2].t - frames[1].t, 1.0 / (o.fps * o.slowmo), 1e-12);
  // Example 1 ends at 0.82 s: about 0.82 * slowmo * fps regular frames.
  EXPECT_NEAR(static_cast<double>(frames.size() - groups.size()), 0.82 * o.slowmo * o.fps, 2.0);
}

TEST(VizAnimation, LongRunsAreFastForwardedBetweenEvents) {
  const Recording rec = record(example(3));  // 20 s, three event instants
  AnimationOptions o = small_animation();
  o.slowmo = 10;
  o.max_length = 15;
  double screen = 0.0;
  double fastest = 0.0;
  for (const Frame& f : plan_frames(rec, o)) screen += f.delay, fastest = std::max(fastest, f.speed);
  EXPECT_LE(screen, o.max_length);  // slow motion throughout would take 200 s
  EXPECT_GT(fastest, 1.0 / o.slowmo);
}

TEST(VizAnimation, MaxLengthIsHonouredWithHeldFramesAndAll) {
  Scenario radio_sc = build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml"));
  std::vector<Recording> runs{record(example(1)), record(example(3)), record(example(4)), record(radio_sc)};
  for (const Recording& rec : runs) {
    for (double max_length : {3.0, 10.0, 31.0}) {
      AnimationOptions o;  // the defaults: 25 frames per second, 1.2 s held at each event
      o.max_length = max_length;
      double screen = 0.0;
      for (const Frame& f : plan_frames(rec, o)) screen += f.delay;
      // At most max_length, and not much shorter when the run needs the time.
      EXPECT_LE(screen, max_length + 1e-9) << rec.t_end() << " s run";
      const double natural = rec.t_end() * o.slowmo;
      if (natural > max_length) {
        EXPECT_GT(screen, 0.75 * max_length) << rec.t_end() << " s run";
      }
    }
  }
}

TEST(VizAnimation, GifFrameRateIsCappedAtFifty) {
  const Recording rec = record(example(2));
  AnimationOptions o = small_animation();
  const fs::path dir = fresh_dir("fps");
  o.fps = 60;
  EXPECT_THROW(write_animation(rec, (dir / "a.gif").string(), o), InputError);
  EXPECT_FALSE(fs::exists(dir / "a.gif"));
  o.fps = 50;
  write_animation(rec, (dir / "b.gif").string(), o);
  const Gif gif = read_gif(dir / "b.gif");
  int shortest = 1000;
  for (std::size_t i = 0; i + 1 < gif.delays_cs.size(); ++i) shortest = std::min(shortest, gif.delays_cs[i]);
  EXPECT_EQ(shortest, 2);
}

TEST(VizAnimation, ProgressIsReportedForEveryFrame) {
  const Recording rec = record(example(2));
  const AnimationOptions o = small_animation();
  const fs::path dir = fresh_dir("progress");
  std::vector<int> seen;
  int total_seen = 0;
  const int n = write_animation(rec, (dir / "a.gif").string(), o, "", "--out", [&](int done, int total) {
    seen.push_back(done);
    total_seen = total;
  });
  ASSERT_EQ(static_cast<int>(seen.size()), n);
  EXPECT_EQ(total_seen, n);
  for (int i = 0; i < n; ++i) EXPECT_EQ(seen[i], i + 1);
}

// With the default height the machine fills the picture: over the run, what is drawn reaches
// across nearly all of the drawing area, in both directions.
TEST(VizAnimation, TheMachineFillsThePicture) {
  Scenario radio_sc = build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml"));
  std::vector<Recording> runs{record(example(1)), record(example(2)), record(example(3)), record(example(4)),
                              record(radio_sc)};
  for (const Recording& rec : runs) {
    SCOPED_TRACE(rec.t_end());
    AnimationOptions o;
    o.width = 400;
    const View view = make_view(rec, o.width, 0);
    EXPECT_GE(view.height, 0.45 * o.width);
    EXPECT_LE(view.height, 1.25 * o.width);
    int x0 = view.width, x1 = -1, y0 = view.height, y1 = -1;
    const auto frames = plan_frames(rec, o);
    for (std::size_t i = 0; i < frames.size(); i += std::max<std::size_t>(1, frames.size() / 12)) {
      const Image img = render_frame(rec, view, frames[i], o);
      for (int y = view.top; y < view.bottom; ++y) {
        for (int x = 0; x < view.width; ++x) {
          const Rgb c = img.at(x, y);
          if (c.r == 255 && c.g == 255 && c.b == 255) continue;
          x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
        }
      }
    }
    EXPECT_GT(x1 - x0, 0.9 * view.width);
    EXPECT_GT(y1 - y0, 0.85 * (view.bottom - view.top));
  }
}

// At t = 0 in example 1 the rope has 0.43 m to spare: it must lie on the lid, not hang through it.
TEST(VizAnimation, SlackRopeStaysOutOfTheBox) {
  const Recording rec = record(example(1));
  const Machine& m = rec.scenario.machine;
  const View view = make_view(rec, 480, 0);
  Frame f;
  f.state = rec.at(0.0);
  const Image img = render_frame(rec, view, f, small_animation());
  const RopeGeometry geo(m);
  const Vec2 edge = geo.lid_edge(f.state.phi_l);
  const double wall = 0.02 * view.scale + 2.0;  // a wall's half width and antialiasing, in pixels
  int rope = 0, inside = 0;
  for (int y = view.top; y < view.bottom; ++y) {
    for (int x = 0; x < view.width; ++x) {
      // Back to metres: inside the walls and more than a rope's width under the lid.
      const double px = (x - view.origin_x) / view.scale, ph = (view.origin_y - y) / view.scale;
      if (px < m.hinge.x + wall / view.scale || px > m.hinge.x + 2.0 * m.lid_half_length - wall / view.scale)
        continue;
      const double lid_h = m.hinge.h + (px - m.hinge.x) * (edge.h - m.hinge.h) / (edge.x - m.hinge.x);
      if (ph > lid_h - wall / view.scale || ph < m.hinge.h - 2.0 * m.lid_half_length) continue;
      ++inside;
      const Rgb c = img.at(x, y);
      rope += c.r == 51 && c.g == 42 && c.b == 51;  // the rope's colour
    }
  }
  EXPECT_GT(inside, 1000);
  EXPECT_EQ(rope, 0);
}

// Once the lid is open, example 1's slack rope (0.26 m to spare, the seesaw's end far above the lid)
// hangs freely from the seesaw to the lid's edge: it is not drawn lying along the open lid. Before
// the fix a rounding error put the lid's edge itself "under the lid", and the rope was drawn
// straight, as if taut, to the middle of the lid and up along it. Checked at lid_open and, with
// the radio, while the lid stands latched open.
TEST(VizAnimation, SlackRopeHangsFreeOfTheOpenLid) {
  const Recording ex1 = record(example(1));
  const Recording radio =
      record(build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml")));
  double open = -1.0;
  for (const Event& e : ex1.result.events) {
    if (e.type == EventType::lid_open) open = e.t;
  }
  ASSERT_GT(open, 0.0);
  for (const auto& [rec, t] :
       {std::pair<const Recording*, double>{&ex1, open}, {&radio, open + 0.05}, {&radio, open + 0.25}}) {
    SCOPED_TRACE(t);
    const Machine& m = rec->scenario.machine;
    const View view = make_view(*rec, 480, 0);
    Frame f;
    f.t = t;
    f.state = rec->at(t);
    ASSERT_FALSE(f.state.rope_taut);
    ASSERT_GT(f.state.phi_l, 80.0 * 3.14159265358979323846 / 180.0);
    const Image img = render_frame(*rec, view, f, small_animation());
    const RopeGeometry geo(m);
    const Vec2 edge = geo.lid_edge(f.state.phi_l);
    int on_lid = 0, probes = 0;
    for (int k = 10; k <= 88; k += 2) {  // along the lid, from near the hinge to short of its edge
      const Pixel p = to_pixel(view, m.hinge + (k / 100.0) * (edge - m.hinge));
      for (int dx = -2; dx <= 2; ++dx) {
        const Rgb c = img.at(static_cast<int>(std::lround(p.x)) + dx, static_cast<int>(std::lround(p.y)));
        on_lid += c.r == 51 && c.g == 42 && c.b == 51;  // the rope's colour
        ++probes;
      }
    }
    EXPECT_GT(probes, 100);
    EXPECT_EQ(on_lid, 0);
  }
}

// With the radio, the lid latches at lid_open and the sandbag flies free; the seesaw keeps its
// angle, and the arm the length it had (it does not shrink back to a stub).
TEST(VizAnimation, ArmKeepsItsLengthAfterTheRadiosLatch) {
  const Recording rec =
      record(build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml")));
  const View view = make_view(rec, 480, 0);
  double latch = -1.0;
  for (const Event& e : rec.result.events) {
    if (e.type == EventType::lid_open) latch = e.t;
  }
  ASSERT_GT(latch, 0.0);
  Frame f;
  f.t = latch + 0.2;
  f.state = rec.at(f.t);
  ASSERT_FALSE(f.state.on_seesaw);
  const Image img = render_frame(rec, view, f, small_animation());
  // 0.7 m out along the left arm: beyond the arm drawn before the landing (0.4 m), within the
  // picture, and far short of where the sandbag was at the latch (2 m).
  const Pixel p = to_pixel(view, polar(-0.7, f.state.phi_s));
  ASSERT_TRUE(p.x >= 0 && p.x < view.width && p.y >= view.top && p.y < view.bottom);
  const Rgb c = img.at(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
  EXPECT_TRUE(same(c, Rgb{153, 85, 51})) << int(c.r) << "," << int(c.g) << "," << int(c.b);
}

namespace {

double polyline_length(const std::vector<Vec2>& pts) {
  double len = 0.0;
  for (std::size_t i = 1; i < pts.size(); ++i) len += norm(pts[i] - pts[i - 1]);
  return len;
}

// The stretched rope's machine: example 2 with a heavy seesaw (0.4 kg, a damped pivot), a 1.2 m left
// arm and the radio. The lid latches at 0.731 s with the rope taut; the seesaw swings on under its
// own weight until it turns vertical (no somersaults) at 1.092 s, carrying its end up to 0.91 m
// from the lid's edge, with 0.62 m of rope.
Recording heavy_radio() {
  Config c = example_config(2);
  for (const char* set :
       {"seesaw.mass=0.4", "radio.enabled=true", "seesaw.left_arm=1.2", "damping.pivot=0.5"})
    apply_set(c, set);
  return record(build_scenario(c));
}

double latch_time(const Recording& rec) {
  for (const Event& e : rec.result.events) {
    if (e.type == EventType::lid_open) return e.t;
  }
  return -1.0;
}

}  // namespace

// After the radio's latch nothing holds the rope. The drawing never shows it longer than it is:
// at the latch it is straight (taut), and once the seesaw's end is farther from the lid's edge than
// the rope reaches, the rope hangs from the lid's edge, its whole length, clear of the seesaw's
// end. Checked on every recorded state and every frame of the animation.
TEST(VizAnimation, RopeIsNeverDrawnLongerThanItself) {
  const Recording rec = heavy_radio();
  const Machine& m = rec.scenario.machine;
  const RopeGeometry geo(m);
  const double latch = latch_time(rec);
  ASSERT_GT(latch, 0.0);
  std::vector<Snapshot> states = rec.states;
  for (const Frame& f : plan_frames(rec, small_animation())) states.push_back(f.state);
  double widest = 0.0;
  int hanging = 0;
  for (const Snapshot& s : states) {
    SCOPED_TRACE(s.t);
    const std::vector<Vec2> path = rope_path(rec, s);
    const double span = geo.span(s.phi_s, s.phi_l);
    const Vec2 r = geo.seesaw_end(s.phi_s), e = geo.lid_edge(s.phi_l);
    if (s.t < latch) continue;
    EXPECT_LE(polyline_length(path), m.rope_length + 1e-9)
        << polyline_length(path) - m.rope_length << " m too long";
    widest = std::max(widest, span);
    if (span > m.rope_length + 1e-6) {
      ++hanging;
      EXPECT_NEAR(polyline_length(path), m.rope_length, 1e-9);  // all of it, hanging
      EXPECT_EQ(path.front().x, e.x);
      EXPECT_EQ(path.front().h, e.h);
      for (Vec2 p : path) EXPECT_GT(norm(p - r), 0.3) << "the rope reaches the seesaw's end";
      for (std::size_t i = 1; i < path.size(); ++i) EXPECT_LE(path[i].h, path[i - 1].h);  // it hangs
    } else if (s.t == latch) {  // the latch itself: the rope is taut, and drawn from the seesaw's end
      EXPECT_NEAR(norm(path.front() - r), 0.0, 1e-12);
      EXPECT_NEAR(polyline_length(path), m.rope_length, 1e-9);
    }
  }
  EXPECT_GT(widest, m.rope_length + 0.25);  // the defect's case: the seesaw carried its end far off
  EXPECT_GT(hanging, 100);
  // Let go for good: a later state with the seesaw swung back a little beyond its angle at the
  // latch, its end nearer the lid's edge than the rope is long, still has the rope hanging.
  Snapshot back = rec.at(latch + 0.2);
  back.phi_s = rec.at(latch).phi_s - 0.1;
  ASSERT_LT(geo.span(back.phi_s, back.phi_l), m.rope_length - 0.01);
  const std::vector<Vec2> again = rope_path(rec, back);
  EXPECT_EQ(again.front().x, geo.lid_edge(back.phi_l).x);
  EXPECT_EQ(again.front().h, geo.lid_edge(back.phi_l).h);
  EXPECT_NEAR(polyline_length(again), m.rope_length, 1e-9);
}

// The same in the picture: after the latch the straight line from the seesaw's end to the lid's
// edge (longer than the rope) is not drawn; the rope hangs from the lid's edge into the box.
TEST(VizAnimation, LetGoRopeHangsFromTheLid) {
  const Recording rec = heavy_radio();
  const RopeGeometry geo(rec.scenario.machine);
  const View view = make_view(rec, 480, 0);
  Frame f;
  f.t = latch_time(rec) + 0.15;
  f.state = rec.at(f.t);
  const Vec2 r = geo.seesaw_end(f.state.phi_s), e = geo.lid_edge(f.state.phi_l);
  ASSERT_GT(norm(e - r), rec.scenario.machine.rope_length + 0.1);
  const Image img = render_frame(rec, view, f, small_animation());
  auto dark = [&](Vec2 p) {  // the rope is drawn dark; the lid, walls and seesaw are not
    const Pixel q = to_pixel(view, p);
    const Rgb c = img.at(static_cast<int>(std::lround(q.x)), static_cast<int>(std::lround(q.y)));
    return c.r < 120 && c.g < 120 && c.b < 120;
  };
  int on_chord = 0;
  for (int k = 20; k <= 80; k += 2) on_chord += dark(r + (k / 100.0) * (e - r));
  EXPECT_EQ(on_chord, 0);
  for (double below : {0.1, 0.3, 0.5})
    EXPECT_TRUE(dark(e - Vec2{0.0, below})) << below << " m below the lid's edge";
}

// Before the latch the drawing takes the rope's ends where the model puts them, and the model keeps
// them within the rope's length: on every recorded state of the shipped machines and of the heavy
// radio one the rope is drawn as long as it is. A frame between two recorded taut states, its
// angles interpolated, may have them farther apart, but by 3.3e-5 m at most (example 3): a
// hundredth of a pixel.
TEST(VizAnimation, BeforeTheLatchTheRopeIsAsLongAsItself) {
  std::vector<Recording> runs{
      record(example(1)),
      record(example(2)),
      record(example(3)),
      record(example(4)),
      record(build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml"))),
      heavy_radio()};
  for (const Recording& rec : runs) {
    const Machine& m = rec.scenario.machine;
    const RopeGeometry geo(m);
    const double latch = m.radio ? latch_time(rec) : rec.t_end();
    for (const Snapshot& s : rec.states) {
      if (s.t > latch) break;
      SCOPED_TRACE(fmt::format("{} at t = {}", rec.scenario.machine.rope_length, s.t));
      EXPECT_LE(geo.span(s.phi_s, s.phi_l), m.rope_length + 1e-9);
      EXPECT_NEAR(polyline_length(rope_path(rec, s)), m.rope_length, 1e-9);
    }
    for (const Frame& f : plan_frames(rec, AnimationOptions{})) {
      if (f.t > latch) break;
      EXPECT_LE(polyline_length(rope_path(rec, f.state)), m.rope_length + 1e-4) << f.t;
    }
  }
}

// The page's icon (web/src/icon.svg) is a small drawing of the machine: each shape names its part
// (class = a name of scene::kColourNames, the table the animation and the page paint with) and has
// that part's colour; only the tile behind them has a colour of its own.
TEST(VizScene, TheIconPaintsEachPartInTheScenesColour) {
  struct Shapes {
    std::vector<std::string> errors;
    std::set<std::string> parts;
  } shapes;
  const std::string svg = slurp(fs::path(WHATNEXT_SOURCE_DIR) / "web/src/icon.svg");
  XML_Parser parser = XML_ParserCreate(nullptr);
  XML_SetUserData(parser, &shapes);
  XML_SetStartElementHandler(parser, [](void* u, const XML_Char* name, const XML_Char** attrs) {
    auto* shapes = static_cast<Shapes*>(u);
    std::map<std::string, std::string> a;
    for (int i = 0; attrs[i]; i += 2) a[attrs[i]] = attrs[i + 1];
    std::vector<std::string> paints;
    for (const char* paint : {"fill", "stroke"}) {
      if (a.count(paint) && a[paint] != "none") paints.push_back(a[paint]);
    }
    if (paints.empty() || a["class"] == "tile") return;
    const std::string part = a["class"];
    const scene::NamedColour* named = nullptr;
    for (const scene::NamedColour& c : scene::kColourNames) {
      if (c.name == part) named = &c;
    }
    if (!named) {
      shapes->errors.push_back(
          fmt::format("<{}> names no part of the scene's colours: class='{}'", name, part));
      return;
    }
    const std::string want = fmt::format("#{:02x}{:02x}{:02x}", named->rgb.r, named->rgb.g, named->rgb.b);
    for (const std::string& p : paints) {
      if (p != want)
        shapes->errors.push_back(fmt::format("{} is painted {}, the scene's {} is {}", part, p, part, want));
    }
    shapes->parts.insert(part);
  });
  ASSERT_EQ(XML_Parse(parser, svg.data(), static_cast<int>(svg.size()), 1), XML_STATUS_OK);
  XML_ParserFree(parser);
  for (const std::string& e : shapes.errors) ADD_FAILURE() << e;
  EXPECT_TRUE(shapes.parts.count("seesaw") && shapes.parts.count("sandbag") && shapes.parts.count("balloon"));
}

// Every event tick on the time bar has its name under it (drawn in the events' red).
// The scene is one table that the animation and the page draw from: its parts must meet where the
// machine joins them, in every recorded state of machines with and without the radio, the built
// machine and a heavy seesaw that pulls its end off the let-go rope. The lid is 2 r_L long from the
// hinge; the rope runs from the seesaw's end to the knot (or hangs from the knot once let go); the
// string ends at the radio's switch, on the radio's post, and is never longer than itself; the
// walls start at the hinge and the stand at the pivot.
TEST(VizScene, PartsMeetWhereTheMachineJoinsThem) {
  std::vector<Recording> runs{
      record(example(1)), record(example(4)),
      record(build_scenario(load_config_file(WHATNEXT_SOURCE_DIR "/examples/example1-radio.toml"))),
      record(build_scenario(example_config("konstanz"))), heavy_radio()};
  for (const Recording& rec : runs) {
    const Machine& m = rec.scenario.machine;
    const RopeGeometry geo(m);
    const scene::StillParts still = scene::still_parts(m);
    EXPECT_LT(norm(still.walls[0] - m.hinge), 1e-15);
    EXPECT_LT(norm(still.stand[0]), 1e-15);
    EXPECT_LT(norm(still.radio_post[1] - m.radio_switch), 1e-15);
    const scene::Release release = scene::release_of(rec);
    int hanging = 0;  // states after the rope came off the seesaw's end
    for (const Snapshot& s : rec.states) {
      const scene::MovingParts p = scene::moving_parts(m, s, release, 1.0, 0.08);
      ASSERT_NEAR(norm(p.lid_end - m.hinge), 2.0 * m.lid_half_length, 1e-12);
      const Vec2 knot = geo.lid_edge(s.phi_l), end = geo.seesaw_end(s.phi_s);
      ASSERT_GE(p.rope.size(), 2u);
      const bool from_seesaw = norm(p.rope.front() - end) < 1e-9 && norm(p.rope.back() - knot) < 1e-9;
      const bool from_knot = norm(p.rope.front() - knot) < 1e-9;
      EXPECT_TRUE(from_seesaw || from_knot || s.t >= release.latch) << "t = " << s.t;
      hanging += s.t >= release.off;
      ASSERT_LT(norm(p.string.back() - m.radio_switch), 1e-9);
      double drawn = 0.0;
      for (std::size_t i = 1; i < p.string.size(); ++i) drawn += norm(p.string[i] - p.string[i - 1]);
      EXPECT_LE(drawn, m.string_length - m.balloon_radius + 1e-6) << "t = " << s.t;
    }
    // Without the radio nothing lets the rope go.
    if (!m.radio) {
      EXPECT_TRUE(std::isinf(release.latch) && std::isinf(release.off) && hanging == 0);
    }
  }
  // The heavy seesaw pulls its end off the let-go rope after the latch, for the rest of the run.
  const scene::Release heavy = scene::release_of(runs.back());
  EXPECT_GT(heavy.off, heavy.latch);
  EXPECT_LT(heavy.off, runs.back().t_end());
}

TEST(VizAnimation, TimeBarNamesItsEvents) {
  const Recording rec = record(example(4));
  const View view = make_view(rec, 480, 0);
  Frame f;
  f.state = rec.at(0.0);
  const Image img = render_frame(rec, view, f, small_animation());
  const int label_row = static_cast<int>(view.bottom + 1.6 * view.font);
  int red = 0;
  for (int y = label_row; y < view.height; ++y) {
    for (int x = 0; x < view.width; ++x) {
      const Rgb c = img.at(x, y);
      red += c.r > 150 && c.g < 110 && c.b < 110;  // the events' red, antialiased
    }
  }
  EXPECT_GT(red, 50);
}

TEST(VizAnimation, GifDecodesAndShowsTheSandbagWhereTheSimulationPutsIt) {
  const Recording rec = record(example(1));
  const AnimationOptions o = small_animation();
  const fs::path dir = fresh_dir("gif");
  const fs::path path = dir / "a.gif";
  const int n = write_animation(rec, path.string(), o);
  const auto frames = plan_frames(rec, o);
  ASSERT_EQ(n, static_cast<int>(frames.size()));
  const Gif gif = read_gif(path);
  ASSERT_EQ(gif.frames.size(), frames.size());
  EXPECT_EQ(gif.width, o.width);
  EXPECT_EQ(gif.height, o.height);
  std::set<std::uint32_t> colours;
  for (const Rgb& c : gif.frames[0]) colours.insert((c.r << 16) | (c.g << 8) | c.b);
  EXPECT_GT(colours.size(), 20u);
  int total_cs = 0;
  for (int d : gif.delays_cs) total_cs += d;
  double planned = 0.0;
  for (const Frame& f : frames) planned += f.delay;
  EXPECT_NEAR(total_cs, planned * 100.0, 1.0);

  // Probe: one frame while falling, one on the seesaw, one held at the landing (later the sandbag
  // slides down the endless arm out of the picture).
  const View view = make_view(rec, o.width, o.height);
  int probed = 0;
  for (std::size_t i = 0; i < frames.size(); ++i) {
    const Frame& f = frames[i];
    const bool pick = (f.event_group < 0 && f.t > 0.25 && probed == 0) ||
                      (f.event_group >= 0 && f.t > 0.4 && probed == 1) ||
                      (f.event_group < 0 && f.t > 0.6 && probed == 2);
    if (!pick) continue;
    const Pixel p = to_pixel(view, {f.state.x, f.state.h});
    const int x = static_cast<int>(p.x), y = static_cast<int>(p.y);
    ASSERT_TRUE(x >= 0 && x < o.width && y >= view.top && y < view.bottom) << "t = " << f.t;
    const Rgb c = gif.frames[i][y * o.width + x];
    EXPECT_TRUE(same(c, kSandbagColour)) << "frame " << i << " t = " << f.t << " at " << x << "," << y << ": "
                                         << int(c.r) << "," << int(c.g) << "," << int(c.b);
    // ... and not where it was at the start (the frame really moved).
    const Pixel p0 = to_pixel(view, {frames[0].state.x, frames[0].state.h});
    EXPECT_FALSE(
        same(gif.frames[i][static_cast<int>(p0.y) * o.width + static_cast<int>(p0.x)], kSandbagColour));
    ++probed;
  }
  EXPECT_EQ(probed, 3);
}

TEST(VizAnimation, GifIsDeterministicAndBadOutputsFailCleanly) {
  const Recording rec = record(example(2));
  AnimationOptions o = small_animation();
  o.width = 120;
  o.height = 90;
  const fs::path dir = fresh_dir("gif_det");
  write_animation(rec, (dir / "a.gif").string(), o);
  write_animation(rec, (dir / "b.gif").string(), o);
  EXPECT_EQ(slurp(dir / "a.gif"), slurp(dir / "b.gif"));
  EXPECT_THROW(write_animation(rec, (dir / "c.avi").string(), o), InputError);
  EXPECT_THROW(write_animation(rec, (dir / "missing" / "d.gif").string(), o), InputError);
  const std::string old_path = std::getenv("PATH") ? std::getenv("PATH") : "";
  setenv("PATH", dir.c_str(), 1);  // no ffmpeg here
  EXPECT_THROW(write_animation(rec, (dir / "e.mp4").string(), o), InputError);
  setenv("PATH", old_path.c_str(), 1);
  o.fps = 0;
  EXPECT_THROW(write_animation(rec, (dir / "f.gif").string(), o), InputError);
  for (const char* f : {"c.avi", "missing", "e.mp4", "e.mp4.part", "f.gif", "f.gif.part"}) {
    EXPECT_FALSE(fs::exists(dir / f)) << f;
  }
}

// --- MP4 through ffmpeg, with stand-ins for it on PATH (ffmpeg itself is not a dependency) ----------

// ffmpeg gets its arguments as they are (no shell: the padding filter's parentheses once made the
// shell give up, and no MP4 was ever written), and the whole film: as many raw frames of the
// view's size as the GIF of the same animation lasts at that frame rate, each animation frame at
// least once. The stand-in writes what it got into its output, which becomes the MP4.
TEST(VizAnimation, Mp4GivesFfmpegItsArgumentsAndTheWholeFilm) {
  const Recording rec = record(example(2));
  const AnimationOptions o = small_animation();
  const fs::path dir = fresh_dir("mp4");
  write_animation(rec, (dir / "a.gif").string(), o);
  {
    const test_support::StandIn ffmpeg(
        dir, "ffmpeg",
        "for a; do last=$a; done\n"
        "{ for a; do printf '%s\\n' \"$a\"; done; printf 'bytes %s\\n' \"$(wc -c)\"; } > \"$last\"\n");
    EXPECT_GT(write_animation(rec, (dir / "a.mp4").string(), o), 0);
  }
  std::vector<std::string> got;
  {
    std::ifstream in(dir / "a.mp4");
    for (std::string line; std::getline(in, line);) got.push_back(line);
  }
  ASSERT_GE(got.size(), 4u);
  auto after = [&](const std::string& flag) {
    for (std::size_t i = 0; i + 1 < got.size(); ++i)
      if (got[i] == flag) return got[i + 1];
    return std::string("(none)");
  };
  EXPECT_EQ(after("-vf"), "pad=ceil(iw/2)*2:ceil(ih/2)*2");
  EXPECT_EQ(after("-i"), "-");
  EXPECT_EQ(after("-r"), "10");
  const Gif gif = read_gif(dir / "a.gif");
  EXPECT_EQ(after("-s"), fmt::format("{}x{}", gif.width, gif.height));
  ASSERT_EQ(got.back().rfind("bytes ", 0), 0u) << got.back();
  const long long bytes = std::stoll(got.back().substr(6));
  const long long frame = 4LL * gif.width * gif.height;
  ASSERT_GT(frame, 0);
  EXPECT_EQ(bytes % frame, 0) << bytes;
  double seconds = 0.0;
  for (int cs : gif.delays_cs) seconds += cs / 100.0;
  // The GIF's delays are whole hundredths; the film's frames whole tenths here.
  EXPECT_NEAR(static_cast<double>(bytes / frame), seconds * o.fps, 0.05 * gif.delays_cs.size() + 1.0);
  EXPECT_GE(bytes / frame, static_cast<long long>(gif.delays_cs.size()));
  EXPECT_TRUE(test_support::temps_in(dir).empty());
}

// An ffmpeg that fails (here without reading a frame) is an OutputError, and nothing is left: no
// MP4, no temporary, the old file as it was.
TEST(VizAnimation, AFailingFfmpegLeavesTheOldFileAndNoTemporary) {
  const Recording rec = record(example(2));
  const AnimationOptions o = small_animation();
  const fs::path dir = fresh_dir("mp4_fails");
  {
    std::ofstream old(dir / "a.mp4");
    old << "old";
  }
  {
    const test_support::StandIn ffmpeg(dir, "ffmpeg", "exit 1\n");
    EXPECT_THROW(write_animation(rec, (dir / "a.mp4").string(), o), whatnext::OutputError);
  }
  EXPECT_EQ(slurp(dir / "a.mp4"), "old");
  EXPECT_TRUE(test_support::temps_in(dir).empty());
}

TEST(VizAnimation, RopeIsStraightWhenTautAndSagsWhenSlack) {
  // Example 2: the rope is taut in M4 between 0.33 s and 0.49 s. Example 1: it starts slack with
  // 0.43 m to spare.
  const AnimationOptions o = small_animation();
  auto chord_mid_is_rope = [&](const Recording& rec, double t) {
    const View view = make_view(rec, 480, 360);
    const RopeGeometry geo(rec.scenario.machine);
    Frame f;
    f.t = t;
    f.state = rec.at(t);
    const Image img = render_frame(rec, view, f, o);
    const Vec2 r = geo.seesaw_end(f.state.phi_s), e = geo.lid_edge(f.state.phi_l);
    const Pixel p = to_pixel(view, 0.5 * (r + e));
    const Rgb c = img.at(static_cast<int>(std::lround(p.x)), static_cast<int>(std::lround(p.y)));
    return c.r < 120 && c.g < 120 && c.b < 120;  // the rope is drawn dark on a light background
  };
  const Recording ex2 = record(example(2)), ex1 = record(example(1));
  ASSERT_EQ(ex2.at(0.4).mode, Mode::M4);
  EXPECT_TRUE(chord_mid_is_rope(ex2, 0.4));
  ASSERT_EQ(ex1.at(0.1).mode, Mode::M1);
  EXPECT_FALSE(chord_mid_is_rope(ex1, 0.1));
}

TEST(VizCli, RunWritesPlotsAndAnimationAndRejectsBadOptions) {
  const fs::path dir = fresh_dir("cli");
  const std::string cli = WHATNEXT_CLI;
  const std::string ok = cli + " run --example 2 -q --plots " + (dir / "plots").string() + " --animate " +
                         (dir / "ex2.gif").string() + " > /dev/null";
  ASSERT_EQ(std::system(ok.c_str()), 0);
  EXPECT_TRUE(fs::exists(dir / "plots" / "overview.png"));
  EXPECT_EQ(read_gif(dir / "ex2.gif").width, AnimationOptions{}.width);
  const std::string bad = cli + " animate --example 2 --out " + (dir / "x.avi").string() + " 2> /dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad.c_str())), 2);
  const std::string bad2 =
      cli + " plot --example 2 --out " + dir.string() + " --compare nothing 2> /dev/null";
  EXPECT_EQ(WEXITSTATUS(std::system(bad2.c_str())), 2);
  EXPECT_FALSE(fs::exists(dir / "x.avi"));
}

TEST(VizCli, AnimateReportsProgressAndCapsTheGifFrameRate) {
  const fs::path dir = fresh_dir("cli_animate");
  const std::string cli = WHATNEXT_CLI;
  const std::string fast = cli + " animate --example 2 --fps 60 --out " + (dir / "fast.gif").string() +
                           " 2> " + (dir / "fast.err").string();
  EXPECT_EQ(WEXITSTATUS(std::system(fast.c_str())), 2);
  EXPECT_FALSE(fs::exists(dir / "fast.gif"));
  EXPECT_NE(slurp(dir / "fast.err").find("--fps"), std::string::npos);
  // Not a terminal: a line every 100 frames and one at the end.
  const std::string ok = cli + " animate --example 2 --width 200 --out " + (dir / "ok.gif").string() + " > " +
                         (dir / "ok.out").string() + " 2> " + (dir / "ok.err").string();
  ASSERT_EQ(std::system(ok.c_str()), 0);
  const std::string err = slurp(dir / "ok.err"), out = slurp(dir / "ok.out");
  const int frames = std::stoi(out.substr(out.find(": ") + 2));
  EXPECT_NE(err.find(fmt::format("animate: frame {} of {}\n", frames, frames)), std::string::npos) << err;
  EXPECT_NE(err.find(fmt::format("animate: frame 100 of {}\n", frames)), std::string::npos) << err;
}
