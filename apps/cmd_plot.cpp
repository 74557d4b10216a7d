// `whatnext plot`: the paper's figures for one run, or a comparison of impact laws or integrators.
#include <memory>
#include <string>
#include <utility>
#include <vector>

#include <fmt/format.h>

#include "cli_common.hpp"
#if WHATNEXT_FULL
#include "whatnext/viz/plots.hpp"
#endif

namespace whatnext::cli {

namespace {
struct PlotOptions {
  InputOptions input;
  std::string out, compare, integrator = "euler", formats = "png,svg,pdf";
  double step = 0.0;
  int width = 1000, height = 650;
  bool quiet = false, force_large = false;
};

#if WHATNEXT_FULL
// The figures' format and size, checked, and their title.
viz::FigureOptions figure_options(const PlotOptions& opts, const std::string& title) {
  viz::FigureOptions fig;
  if (!viz::parse_formats(opts.formats, fig.formats)) {
    throw InputError(
        fmt::format("--format: must list png, svg or pdf separated by commas, got '{}'", opts.formats));
  }
  if (opts.width < 200 || opts.width > 8000) {
    throw InputError(fmt::format("--width: must be between 200 and 8000 pixels, got {}", opts.width));
  }
  if (opts.height < 150 || opts.height > 8000) {
    throw InputError(fmt::format("--height: must be between 150 and 8000 pixels, got {}", opts.height));
  }
  fig.width = opts.width;
  fig.height = opts.height;
  fig.title = title;
  return fig;
}

// The integrator and step that --compare integrator sets against the adaptive run.
std::pair<IntegratorKind, double> compared_integrator(const PlotOptions& opts, const CLI::App& cmd,
                                                      const Scenario& sc) {
  IntegratorKind kind;
  if (!parse_integrator(opts.integrator, kind) || kind == IntegratorKind::adaptive) {
    throw InputError(fmt::format("--integrator: must be euler or rk4, got '{}'", opts.integrator));
  }
  const double step = cmd.count("--step") ? opts.step : sc.run.step;
  if (!(step > 0.0 && step <= 1.0)) {
    throw InputError(fmt::format("--step: must be > 0 and <= 1 s, got {:g}", step));
  }
  return {kind, step};
}

// The figures --compare asks for (the run's own without it), drawn into --out; the files written.
std::vector<std::string> draw(const PlotOptions& opts, const CLI::App& cmd, const Scenario& sc,
                              const viz::FigureOptions& fig) {
  if (opts.compare.empty()) {
    if (cmd.count("--integrator") || cmd.count("--step")) {
      throw InputError(
          "--integrator/--step: only with --compare integrator (use --set run.integrator=... to plot one "
          "run)");
    }
    return viz::write_run_figures(viz::record(sc), opts.out, fig);
  }
  if (opts.compare == "laws") return viz::write_law_comparison(sc, opts.out, fig);
  if (opts.compare == "integrator") {
    const auto [kind, step] = compared_integrator(opts, cmd, sc);
    return viz::write_integrator_comparison(sc, kind, step, opts.out, fig);
  }
  throw InputError(fmt::format("--compare: must be laws or integrator, got '{}'", opts.compare));
}
#endif
}  // namespace

void register_plot(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<PlotOptions>();
  CLI::App* cmd = app.add_subcommand("plot", "draw the paper's figures (Fig. 8, 9) for one machine");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--out", opts->out, "directory for the figures (created if missing)")
      ->required()
      ->type_name("DIR");
  cmd->add_option("--compare", opts->compare,
                  "laws: phiS and phiL for the four impact laws; integrator: adaptive against "
                  "--integrator with --step")
      ->type_name("laws|integrator");
  cmd->add_option("--integrator", opts->integrator, "with --compare integrator: euler or rk4")
      ->capture_default_str()
      ->type_name("euler|rk4");
  cmd->add_option("--step", opts->step, "with --compare integrator: its step [s] (default: run.step)")
      ->transform(number_text(false));
  cmd->add_option("--format", opts->formats, "comma-separated: png, svg, pdf")
      ->capture_default_str()
      ->type_name("LIST");
  cmd->add_option("--width", opts->width, "width of a one-panel figure [px]")
      ->capture_default_str()
      ->transform(number_text(true));
  cmd->add_option("--height", opts->height, "height of a one-panel figure [px]")
      ->capture_default_str()
      ->transform(number_text(true));
  cmd->add_flag("-q,--quiet", opts->quiet, "do not list the files written");
  cmd->add_flag("--force-large", opts->force_large,
                "draw runs whose states would take more than 256 MB of memory");
#if !WHATNEXT_FULL
  (void)exit_code;
  cmd->callback([opts] { hand_over_to_full(); });  // opts: the options write into it
#else
  cmd->callback([opts, cmd, &exit_code] {
    check_leftovers(*cmd);
    const LoadedInput in = load_input(opts->input);
    check_size(in.scenario, kStateBytes, "plot", opts->force_large, "hold in memory");
    const viz::FigureOptions fig = figure_options(*opts, in.source);
    prepare_picture_dir(opts->out, "--out");
    const std::vector<std::string> written = draw(*opts, *cmd, in.scenario, fig);
    if (!opts->quiet) {
      for (const std::string& w : written) fmt::print("{}\n", w);
    }
    exit_code = 0;
  });
#endif
}

}  // namespace whatnext::cli
