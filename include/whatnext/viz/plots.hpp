// The paper's figures (Fig. 8 and 9) for any run, drawn with PLplot's Cairo drivers.
#pragma once

#include <string>
#include <string_view>
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

// The figure set of one run, written into dir (created if missing): sandbag_x, sandbag_h,
// trajectory, angles, balloon, energy and all six on one page as overview, each in every format.
// Returns the paths written. Throws InputError when dir cannot be written.
std::vector<std::string> write_run_figures(const Recording& rec, const std::string& dir,
                                           const FigureOptions& opts);

// phiS and phiL of the four impact laws overlaid (the paper's Fig. 9): compare_laws.*
std::vector<std::string> write_law_comparison(const Scenario& scenario, const std::string& dir,
                                              const FigureOptions& opts);

// The adaptive integrator against a fixed-step one (euler or rk4 with step dt): angles and total
// energy of both: compare_integrator.*
std::vector<std::string> write_integrator_comparison(const Scenario& scenario,
                                                     IntegratorKind fixed, double step,
                                                     const std::string& dir,
                                                     const FigureOptions& opts);

// Creates dir if needed and checks that files can be written there. Throws InputError.
void prepare_output_dir(const std::string& dir, std::string_view option);

}  // namespace whatnext::viz
