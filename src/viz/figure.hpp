// A figure page as the plots build it (figure_*.cpp, plots.cpp): the data (panels of curves, marks,
// events, modes), the layout in millimetres computed from it (layout_panel.cpp, layout_page.cpp)
// and the text measurement both use (figure_text.cpp). Drawn with PLplot by draw_figure.cpp.
#pragma once

#include <array>
#include <cstddef>
#include <string>
#include <utility>
#include <vector>

#include "whatnext/events.hpp"
#include "whatnext/viz/plots.hpp"

namespace whatnext::viz::figure {

constexpr double kMmPerPt = 25.4 / 72.0;  // the Cairo drivers map one pixel to one point

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
    {255, 255, 255},
    {0, 0, 0},
    {110, 110, 110},
    {31, 119, 180},
    {230, 120, 20},
    {44, 160, 44},
    {214, 39, 40},
    {148, 103, 189},
    {140, 86, 75},
    {215, 215, 215},
    {255, 236, 179},
    {255, 205, 210},
    {200, 230, 201},
    {187, 222, 251},
    {225, 200, 240},
}};

struct Curve {
  std::vector<double> x, y;
  std::string label;
  int colour = kBlack;
  int style = 1;  // PLplot line style: 1 solid, 2 and up dashed
  double width = 2.0;
  bool dots = false;  // point markers (no line)
};

struct Mark {  // a numbered point (events on the trajectory)
  double x, y;
  int number;
};

struct ModeSpan {
  double t0, t1;
  Mode mode;
};

struct Panel {
  std::string title, xlabel, ylabel;
  std::vector<Curve> curves;
  std::vector<Mark> marks;
  std::vector<EventGroup> events;                      // vertical lines on a time axis, numbered 1, 2, ...
  std::vector<ModeSpan> modes;                         // strip above the plot
  std::vector<std::pair<double, std::string>> hlines;  // reference levels
  double x0 = 0.0, x1 = 1.0;
  bool fixed_x = false;
  bool to_scale = false;           // same metres per millimetre on both axes, or say in the title
  bool show_legend = true;         // false: another panel of the page shows the same legend
  std::size_t legend_columns = 0;  // 0: as many as fit
};

// A page: panels in a grid and, under them, the key to the numbered events.
struct Page {
  std::string name;
  int width = 1000, height = 650;  // pixels of the PNG (points of SVG and PDF)
  int nx = 1, ny = 1;
  double text_scale = 1.0;
  std::vector<Panel> panels;
  std::vector<EventGroup> key;
};

// ---- text measurement and boxes (figure_text.cpp) ----

// PLplot's character height h [mm] is 3/4 of the font size; #d and #u shift to 3/4 size.
constexpr double kEmPerHeight = 1.0 / 0.75;
constexpr double kSubScale = 0.75;

bool has_subscript(const std::string& s);
// Width [mm] of a PLplot string (with #d/#u escapes) at character height h [mm], a little generous.
double text_width(const std::string& s, double h);
// Box of a text at reference height y, horizontal position x with justification just (0 left,
// 0.5 centre, 1 right).
Box text_box(const std::string& s, double x, double y, double just, double h);

bool overlap(const Box& a, const Box& b);
bool inside(const Box& in, const Box& out);
Box grow(Box b, double d);

using Point = std::pair<double, double>;
using Polyline = std::vector<Point>;

bool segment_hits(const Box& b, Point a, Point c);
bool hits_data(const Box& b, const std::vector<Polyline>& data);

// ---- layout ----

struct Text {
  PlacedText::Kind kind;
  std::string text;
  double x, y, just, h;  // reference point [mm], justification, character height [mm]
  int colour = kBlack;
  Box box;
};
inline Text make_text(PlacedText::Kind kind, std::string s, double x, double y, double just, double h,
                      int colour = kBlack) {
  Text t{kind, std::move(s), x, y, just, h, colour, {}};
  t.box = text_box(t.text, x, y, just, h);
  return t;
}

struct Segment {
  double x0, y0, x1, y1;
  int colour;
  int style;
  double width;
};

struct PanelGeometry {
  Box axes, strip;
  double wx0 = 0, wx1 = 1, wy0 = 0, wy1 = 1;  // the data window
  std::vector<Text> texts;
  std::vector<Segment> strokes;  // legend samples and leader lines, in mm
  std::vector<Box> samples;
  std::vector<Polyline> data;    // curves and dots in mm
  std::vector<Box> reserved;     // tick numbers and axis titles
  double h = 1.0;                // base character height [mm]
  double bands = 0.0;            // height of the bands above the axes [mm]
  double ylabel_h = 1.0;         // character height of the y axis' title [mm]
  double ytick = 0.0;            // spacing of the y axis' numbered ticks (data units)
  double ylabel_at = 0.0;        // the y axis' title: its reference point left of the axes [mm]
  double left_needed = 0.0;      // room the tick numbers and the y title need left of the axes [mm]
  std::vector<Text> axis_texts;  // where PLplot will write the y tick numbers and the y title
  double title_h = 0.0;          // the title's character height [mm] (shrunk to fit the panel)
};

struct PageGeometry {
  double w = 0, h = 0, ch = 1.0;  // page [mm], base character height [mm]
  std::vector<PanelGeometry> panels;
  std::vector<Text> texts;
};

// ---- axes (figure_axes.cpp) ----

// The range of the panel's data along x or y (with the reference levels), never empty.
void data_range(const Panel& p, bool along_x, double& lo, double& hi);
// PLplot's spacing of numbered ticks over [lo, hi], and the numbers it writes there.
double tick_spacing(double lo, double hi);
std::vector<std::pair<double, std::string>> tick_numbers(double lo, double hi, double tick);

// Entries of the given widths in a table as wide as fits between x0 and x1: row by row, in as many
// columns as fit (each column as wide as its widest entry).
struct Grid {
  std::vector<std::vector<std::size_t>> rows;
  std::vector<double> column_x;  // left edge of each column
  double x(std::size_t i) const { return column_x[i % column_x.size()]; }
};
Grid grid(const std::vector<double>& widths, double x0, double x1, double spacing,
          std::size_t max_columns = 0);

// ---- the layout (layout_panel.cpp, layout_page.cpp) ----

// The panel in rect r with base character height ch (see layout_panel.cpp for min_bands, left and
// title_cap, which line up the panels of a page).
PanelGeometry layout_panel(const Panel& p, const Box& r, double ch, double min_bands = 0.0, double left = 0.0,
                           double title_cap = 0.0);
PageGeometry layout_page(const Page& page);
// The layout as the library hands it out (PageLayout), for the tests that no text covers data.
PageLayout public_layout(const Page& page, const PageGeometry& pg);

// ---- drawing (draw_figure.cpp) ----

// Lays the page out and draws it in every requested format into dir; files appear only when
// complete. Hands the layout out through `layouts` if given. Returns the paths written.
std::vector<std::string> write_page(const std::string& dir, const Page& page, const FigureOptions& opts,
                                    std::vector<PageLayout>* layouts);

}  // namespace whatnext::viz::figure
