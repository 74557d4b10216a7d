// The paper's figures (Fig. 8 and 9) for any run, drawn with PLplot: PNG and PDF with its Cairo
// drivers, SVG with its own svg driver, which keeps text as text.
#pragma once

#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "whatnext/params.hpp"
#include "whatnext/viz/recording.hpp"

namespace whatnext::viz {

enum class Format { png, svg, pdf };
std::string_view extension(Format f);
// "png,svg,pdf" (any subset, any order). False for anything else.
bool parse_formats(std::string_view text, std::vector<Format>& out);

struct FigureOptions {
  std::vector<Format> formats{Format::png, Format::svg, Format::pdf};
  int width = 1000;  // pixels of a one-panel PNG; SVG and PDF get the same size in points
  int height = 650;
  std::string title;  // what was run, e.g. "example 1"; starts every figure title
};

// Where a figure's parts lie on its page, in millimetres from the page's bottom-left corner. Every
// figure is drawn from its layout; tests use it to check that no text hides data or other text.
struct Box {
  double x0 = 0.0, y0 = 0.0, x1 = 0.0, y1 = 0.0;
};
struct PlacedText {
  enum Kind { title, legend, event_number, key, label } kind = label;
  std::string text;
  Box box;
};
struct PageLayout {
  std::string name;                    // the file's name without extension, e.g. "angles"
  double width = 0.0, height = 0.0;    // the page [mm]
  std::vector<Box> axes;               // each panel's plot area: data is drawn only inside
  std::vector<Box> windows;            // each panel's data range in its own units
  std::vector<Box> axis_labels;        // where PLplot writes tick numbers and axis titles
  std::vector<PlacedText> axis_texts;  // the y axes' tick numbers and titles, where PLplot writes them
  std::vector<PlacedText> texts;       // every text whatnext places itself
  std::vector<Box> legend_samples;     // the line samples of the legends
  std::vector<std::vector<std::pair<double, double>>> data;  // curves and dots as drawn [mm]
};

// The figure set of one run, written into dir (created if missing): sandbag_x, sandbag_h,
// trajectory, angles, balloon, energy and all six on one page as overview, each in every format.
// Returns the paths written. Throws InputError when dir cannot be written.
// If layouts is given, the layout of every page drawn is appended to it.
std::vector<std::string> write_run_figures(const Recording& rec, const std::string& dir,
                                           const FigureOptions& opts,
                                           std::vector<PageLayout>* layouts = nullptr);

// phiS and phiL of the four impact laws overlaid (the paper's Fig. 9): compare_laws.*
std::vector<std::string> write_law_comparison(const Scenario& scenario, const std::string& dir,
                                              const FigureOptions& opts,
                                              std::vector<PageLayout>* layouts = nullptr);

// The adaptive integrator against a fixed-step one (euler or rk4 with step dt): angles and total
// energy of both: compare_integrator.*
std::vector<std::string> write_integrator_comparison(const Scenario& scenario, IntegratorKind fixed,
                                                     double step, const std::string& dir,
                                                     const FigureOptions& opts,
                                                     std::vector<PageLayout>* layouts = nullptr);

// Creates dir if needed and checks that files can be written there. Throws InputError.
void prepare_output_dir(const std::string& dir, std::string_view option);

}  // namespace whatnext::viz
