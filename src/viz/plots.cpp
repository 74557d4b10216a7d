// The paper's figures for a run, and its comparisons: which panels a page has, and what each shows
// (curves, events, modes, reference levels). Laying a page out (layout_page.cpp, layout_panel.cpp)
// and drawing it with PLplot (draw_figure.cpp) are stages of their own.
//
// Every page is laid out first, in millimetres, and then drawn from that layout in each format.
// Legends, event numbers and the event key sit outside the axes; the few texts inside the axes
// (event numbers on the trajectory, the 90° line's name) are placed by a collision test against
// the curves and the other texts. Text widths are measured with Cairo in DejaVu Sans, the font
// PLplot's drivers use here (figure_text.cpp).
#include "whatnext/units.hpp"
#include "whatnext/viz/plots.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <sstream>

#include <fmt/format.h>

#include "figure.hpp"
#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/output.hpp"

namespace whatnext::viz {

namespace fs = std::filesystem;

using namespace figure;

namespace {

// Indices of the states to draw: every event state and at most about `limit` plain samples.
std::vector<std::size_t> thin(const Recording& rec, std::size_t limit = 4000) {
  const std::size_t n = rec.states.size();
  const std::size_t stride = std::max<std::size_t>(1, n / limit);
  std::vector<std::size_t> idx;
  for (std::size_t i = 0; i < n; ++i) {
    if (rec.event_index[i] >= 0 || i % stride == 0 || i + 1 == n) idx.push_back(i);
  }
  return idx;
}

// An empty curve with its legend label and pen.
Curve styled(std::string label, int colour, int style, double width) {
  Curve c;
  c.label = std::move(label);
  c.colour = colour;
  c.style = style;
  c.width = width;
  return c;
}

Curve series(const Recording& rec, const std::function<double(const Snapshot&)>& x,
             const std::function<double(const Snapshot&)>& y, std::string label, int colour, int style = 1,
             double width = 2.0) {
  Curve c = styled(std::move(label), colour, style, width);
  for (std::size_t i : thin(rec)) {
    c.x.push_back(x(rec.states[i]));
    c.y.push_back(y(rec.states[i]));
  }
  return c;
}

double time_of(const Snapshot& s) { return s.t; }

std::vector<ModeSpan> mode_spans(const Recording& rec) {
  std::vector<ModeSpan> spans;
  for (const Snapshot& s : rec.states) {
    if (spans.empty() || spans.back().mode != s.mode) {
      if (!spans.empty()) spans.back().t1 = s.t;
      // A mode held for no time (M4 for the instant of an impact) gets no band of its own.
      if (!spans.empty() && spans.back().t1 <= spans.back().t0) spans.pop_back();
      if (!spans.empty() && spans.back().mode == s.mode) continue;
      spans.push_back({s.t, s.t, s.mode});
    }
    spans.back().t1 = s.t;
  }
  return spans;
}

Panel time_panel(const Recording& rec, std::string title, std::string ylabel) {
  Panel p;
  p.title = std::move(title);
  p.xlabel = "time t [s]";
  p.ylabel = std::move(ylabel);
  p.events = group_events(rec.result);
  p.modes = mode_spans(rec);
  p.fixed_x = true;
  p.x0 = 0.0;
  p.x1 = rec.t_end() > 0.0 ? rec.t_end() * 1.04 : 1.0;
  return p;
}

// Total energy with its jumps at impacts drawn as vertical steps.
Curve total_energy(const Recording& rec, std::string label, int colour, int style = 1, double width = 2.5) {
  Curve c = styled(std::move(label), colour, style, width);
  for (std::size_t i : thin(rec)) {
    const Snapshot& s = rec.states[i];
    const int e = rec.event_index[i];
    if (e >= 0 && rec.result.events[e].impact) {
      c.x.push_back(s.t);
      c.y.push_back(rec.result.events[e].energy_before);
    }
    c.x.push_back(s.t);
    c.y.push_back(s.energy());
  }
  return c;
}

std::vector<Panel> run_panels(const Recording& rec, const std::string& title) {
  const std::string pre = title.empty() ? "" : title + ": ";
  std::vector<Panel> panels;

  Panel x = time_panel(rec, pre + "sandbag, horizontal position", "x [m] (from the pivot)");
  x.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.x; }, "", kBlue));
  panels.push_back(x);

  Panel h = time_panel(rec, pre + "sandbag, height", "h [m] (above the pivot)");
  h.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.h; }, "", kBlue));
  panels.push_back(h);

  Panel tr;
  tr.title = pre + "sandbag, trajectory";
  tr.xlabel = "x [m] (from the pivot)";
  tr.ylabel = "h [m] (above the pivot)";
  tr.to_scale = true;
  tr.curves.push_back(series(
      rec, [](const Snapshot& s) { return s.x; }, [](const Snapshot& s) { return s.h; }, "sandbag", kBlue));
  {
    // The seesaw at the start, for orientation.
    const Snapshot& s0 = rec.states.front();
    const double right = rec.scenario.machine.seesaw_right_arm;
    const double len = std::max(right, 1.2 * std::fabs(s0.x) / std::max(0.2, std::cos(s0.phi_s)));
    Curve arm = styled("seesaw at t = 0", kBrown, 2, 1.5);
    arm.x = {-len * std::cos(s0.phi_s), right * std::cos(s0.phi_s)};
    arm.y = {-len * std::sin(s0.phi_s), right * std::sin(s0.phi_s)};
    tr.curves.push_back(arm);
  }
  const std::vector<EventGroup> groups = group_events(rec.result);
  for (std::size_t i = 0; i < groups.size(); ++i) {
    const Snapshot& s = rec.result.events[groups[i].events.back()].after;
    tr.marks.push_back({s.x, s.h, static_cast<int>(i) + 1});
  }
  panels.push_back(tr);

  Panel ang = time_panel(rec, pre + "seesaw and lid angles", "angle [deg]");
  ang.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; },
      "φ#dS#u seesaw (+ = left arm down)", kBlue));
  ang.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; }, "φ#dL#u lid",
      kOrange));
  ang.hlines.push_back({90.0, "90°: vertical"});
  panels.push_back(ang);

  Panel bal = time_panel(rec, pre + "balloon", "height [m] (from the box top)");
  bal.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.balloon_h; }, "balloon h#dB#u", kBlue));
  bal.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.balloon_limit; }, "limit under the lid h#dlim#u",
      kOrange, 2, 2.0));
  panels.push_back(bal);

  Panel en = time_panel(rec, pre + "mechanical energy", "energy [J]");
  en.curves.push_back(total_energy(rec, "total", kBlack));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.sandbag_kinetic + s.sandbag_potential; },
      "sandbag (zero: at rest at the pivot's height)", kGreen, 1, 1.5));
  en.curves.push_back(series(
      rec, time_of, [](const Snapshot& s) { return s.lid_kinetic + s.lid_potential; },
      "lid (zero: at rest, horizontal)", kPurple, 1, 1.5));
  panels.push_back(en);
  return panels;
}

std::string law_words(ImpactLaw law) {
  switch (law) {
    case ImpactLaw::rope: return "rope impulse (eq. 7)";
    case ImpactLaw::angular_momentum_sum: return "sum of angular momenta";
    case ImpactLaw::kinetic_energy: return "kinetic energy";
    case ImpactLaw::linear_momentum: return "linear momentum (unphysical)";
  }
  return "";
}

std::string outcome_words(const Result& r) {
  return fmt::format("{} {:.3f} s", event_words(r.outcome(), false), r.outcome().t);
}

// Event points on a curve of angle over time.
Curve event_points(const Recording& rec, bool lid, int colour) {
  Curve c;
  c.colour = colour;
  c.dots = true;
  for (const Event& e : rec.result.events) {
    c.x.push_back(e.t);
    c.y.push_back((lid ? e.after.phi_l : e.after.phi_s) * units::kDegreesPerRadian);
  }
  return c;
}

Page make_page(std::string name, int width, int height, int nx, int ny, std::vector<Panel> panels,
               std::vector<EventGroup> key = {}) {
  Page page;
  page.name = std::move(name);
  page.width = width;
  page.height = height;
  page.nx = nx;
  page.ny = ny;
  page.panels = std::move(panels);
  page.key = std::move(key);
  return page;
}

}  // namespace

std::string_view extension(Format f) {
  switch (f) {
    case Format::png: return "png";
    case Format::svg: return "svg";
    case Format::pdf: return "pdf";
  }
  return "png";
}

bool parse_formats(std::string_view text, std::vector<Format>& out) {
  std::vector<Format> formats;
  std::stringstream ss{std::string(text)};
  std::string item;
  while (std::getline(ss, item, ',')) {
    Format f;
    if (item == "png")
      f = Format::png;
    else if (item == "svg")
      f = Format::svg;
    else if (item == "pdf")
      f = Format::pdf;
    else
      return false;
    if (std::find(formats.begin(), formats.end(), f) == formats.end()) formats.push_back(f);
  }
  if (formats.empty()) return false;
  out = formats;
  return true;
}

void prepare_output_dir(const std::string& dir, std::string_view option) {
  if (dir.empty()) throw InputError(fmt::format("{}: give a directory", option));
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec || !fs::is_directory(dir)) {
    throw InputError(fmt::format("{}: cannot create directory '{}'{}{}", option, dir, ec ? ": " : "",
                                 ec ? ec.message() : ""));
  }
  if (can_create_in(dir) != 0)
    throw InputError(fmt::format("{}: cannot write into directory '{}'", option, dir));
}

std::vector<std::string> write_run_figures(const Recording& rec, const std::string& dir,
                                           const FigureOptions& opts, std::vector<PageLayout>* layouts) {
  prepare_output_dir(dir, "--out");
  const std::vector<Panel> panels = run_panels(rec, opts.title);
  const std::vector<EventGroup> key = group_events(rec.result);
  static const char* const names[] = {"sandbag_x", "sandbag_h", "trajectory", "angles", "balloon", "energy"};
  std::vector<std::string> written;
  for (std::size_t i = 0; i < panels.size(); ++i) {
    auto w =
        write_page(dir, make_page(names[i], opts.width, opts.height, 1, 1, {panels[i]}, key), opts, layouts);
    written.insert(written.end(), w.begin(), w.end());
  }
  Page overview = make_page("overview", opts.width * 9 / 5, opts.height * 3 / 2, 3, 2, panels, key);
  overview.text_scale = 1.35;
  auto w = write_page(dir, overview, opts, layouts);
  written.insert(written.end(), w.begin(), w.end());
  return written;
}

std::vector<std::string> write_law_comparison(const Scenario& scenario, const std::string& dir,
                                              const FigureOptions& opts, std::vector<PageLayout>* layouts) {
  prepare_output_dir(dir, "--out");
  const std::string pre = opts.title.empty() ? "" : opts.title + ": ";
  Panel ps, pl;
  ps.title = pre + "seesaw angle for the four impact laws (dots: events)";
  pl.title = pre + "lid angle for the four impact laws";
  for (Panel* p : {&ps, &pl}) {
    p->xlabel = "time t [s]";
    p->fixed_x = true;
    p->hlines.push_back({90.0, "90°: vertical"});
  }
  ps.ylabel = "φ#dS#u [deg]";
  pl.ylabel = "φ#dL#u [deg]";
  pl.show_legend = false;  // the same four laws as above
  const int colours[] = {kBlue, kOrange, kGreen, kRed};
  const int styles[] = {1, 2, 3, 4};
  double t_end = 0.0;
  int i = 0;
  for (ImpactLaw law : {ImpactLaw::rope, ImpactLaw::angular_momentum_sum, ImpactLaw::kinetic_energy,
                        ImpactLaw::linear_momentum}) {
    Scenario sc = scenario;
    sc.run.impact_law = law;
    const Recording rec = record(sc);
    t_end = std::max(t_end, rec.t_end());
    const std::string label = fmt::format("{}: {}", law_words(law), outcome_words(rec.result));
    ps.curves.push_back(series(
        rec, time_of, [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; }, label, colours[i],
        styles[i]));
    pl.curves.push_back(series(
        rec, time_of, [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; }, label, colours[i],
        styles[i]));
    ps.curves.push_back(event_points(rec, false, colours[i]));
    pl.curves.push_back(event_points(rec, true, colours[i]));
    ++i;
  }
  for (Panel* p : {&ps, &pl}) p->x1 = t_end * 1.04;
  return write_page(dir, make_page("compare_laws", opts.width, opts.height * 8 / 5, 1, 2, {ps, pl}), opts,
                    layouts);
}

std::vector<std::string> write_integrator_comparison(const Scenario& scenario, IntegratorKind fixed,
                                                     double step, const std::string& dir,
                                                     const FigureOptions& opts,
                                                     std::vector<PageLayout>* layouts) {
  if (fixed == IntegratorKind::adaptive) {
    throw InputError("--integrator: compare the adaptive integrator with euler or rk4, not with itself");
  }
  if (!(step > 0.0)) throw InputError(fmt::format("--step: must be > 0 s, got {}", step));
  prepare_output_dir(dir, "--out");
  Scenario sa = scenario, sf = scenario;
  sa.run.integrator = IntegratorKind::adaptive;
  sf.run.integrator = fixed;
  sf.run.step = step;
  const Recording ra = record(sa), rf = record(sf);
  const std::string pre = opts.title.empty() ? "" : opts.title + ": ";
  const std::string fixed_name = fmt::format("{}, dt = {:g} ms", to_string(fixed), step * 1e3);

  Panel ang;
  ang.title = pre + fmt::format("angles: adaptive (solid) against {} (dashed)", fixed_name);
  ang.xlabel = "time t [s]";
  ang.ylabel = "angle [deg]";
  ang.fixed_x = true;
  ang.x1 = std::max(ra.t_end(), rf.t_end()) * 1.04;
  ang.hlines.push_back({90.0, "90°: vertical"});
  ang.legend_columns = 2;  // a row per integrator
  ang.events = group_events(ra.result);
  auto phs = [](const Snapshot& s) { return s.phi_s * units::kDegreesPerRadian; };
  auto phl = [](const Snapshot& s) { return s.phi_l * units::kDegreesPerRadian; };
  ang.curves.push_back(series(ra, time_of, phs, "φ#dS#u adaptive: " + outcome_words(ra.result), kBlue));
  ang.curves.push_back(series(ra, time_of, phl, "φ#dL#u adaptive", kOrange));
  ang.curves.push_back(
      series(rf, time_of, phs, "φ#dS#u " + fixed_name + ": " + outcome_words(rf.result), kBlue, 2));
  ang.curves.push_back(series(rf, time_of, phl, "φ#dL#u " + fixed_name, kOrange, 2));
  ang.curves.push_back(event_points(rf, false, kBlue));
  ang.curves.push_back(event_points(rf, true, kOrange));

  Panel en = ang;
  en.title = pre + "total mechanical energy (drops only at impacts; drift is integration error)";
  en.ylabel = "energy [J]";
  en.hlines.clear();
  en.curves.clear();
  en.curves.push_back(total_energy(ra, "adaptive", kBlack));
  en.curves.push_back(total_energy(rf, fixed_name, kRed, 2, 2.0));
  return write_page(
      dir, make_page("compare_integrator", opts.width, opts.height * 8 / 5, 1, 2, {ang, en}, ang.events),
      opts, layouts);
}

}  // namespace whatnext::viz
