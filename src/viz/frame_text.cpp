// The texts of an animation frame: the caption band above the machine and the time bar below it.
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "draw_frame.hpp"
#include "placement.hpp"
#include "whatnext/units.hpp"

namespace whatnext::viz::draw {

namespace {

// An event in a word or two, for the time bar.
std::string_view short_words(EventType type) {
  switch (type) {
    case EventType::sandbag_lands: return "lands";
    case EventType::rope_taut: return "taut";
    case EventType::rope_slack: return "slack";
    case EventType::lid_rests: return "lid rests";
    case EventType::lid_lifts: return "lid lifts";
    case EventType::balloon_caught: return "caught";
    case EventType::balloon_free: return "balloon free";
    case EventType::balloon_escapes: return "balloon out";
    case EventType::sandbag_falls_off: return "falls off";
    case EventType::sandbag_leaves: return "leaves arm";
    case EventType::sandbag_at_stop: return "at stop";
    case EventType::sandbag_leaves_stop: return "off stop";
    case EventType::sandbag_sticks: return "sticks";
    case EventType::sandbag_slips: return "slips";
    case EventType::seesaw_sticks: return "seesaw sticks";
    case EventType::seesaw_slips: return "seesaw turns";
    case EventType::lid_sticks: return "lid sticks";
    case EventType::lid_slips: return "lid turns";
    case EventType::seesaw_on_floor: return "on floor";
    case EventType::seesaw_lifts: return "lifts";
    case EventType::sandbag_on_floor: return "bag on floor";
    case EventType::sandbag_bounces: return "bounces";
    case EventType::lid_open: return "lid open";
    case EventType::seesaw_vertical: return "vertical";
    case EventType::sandbag_at_pivot: return "at pivot";
    case EventType::rope_locked: return "locked";
    case EventType::radio_on: return "radio on";
    case EventType::switch_stays_off: return "switch off";
    case EventType::timeout: return "t_max";
    case EventType::event_limit: return "event limit";
  }
  return "";
}

// How fast the run goes by, relative to real time, in words a viewer can check against a clock.
std::string speed_words(double speed, bool quiet) {
  const std::string pre = quiet ? "quiet stretch, faster: " : "";
  if (speed < 1.0 - 1e-9)
    return pre + fmt::format("slow motion, 1 s of the run = {:.3g} s here", 1.0 / speed);
  if (speed > 1.0 + 1e-9) return pre + fmt::format("fast forward, 1 s here = {:.3g} s of the run", speed);
  return pre + "real time";
}

void fit_text(cairo_t* cr, const std::string& text, double size, double max_width) {
  cairo_set_font_size(cr, size);
  cairo_text_extents_t ext;
  cairo_text_extents(cr, text.c_str(), &ext);
  if (ext.x_advance > max_width && ext.x_advance > 0) {
    cairo_set_font_size(cr, size * max_width / ext.x_advance);
  }
}

}  // namespace

void caption(cairo_t* cr, const View& v, const Recording& rec, const std::vector<EventGroup>& groups,
             const Frame& frame, bool bag_visible) {
  const Snapshot& s = frame.state;
  const double font = v.font;
  const double margin = 0.5 * font;
  set(cr, kLightGrey);
  cairo_rectangle(cr, 0, 0, v.width, v.top);
  cairo_fill(cr);
  set(cr, kBlack);
  const std::string line1 = fmt::format("t = {:.3f} s    {}", frame.t, mode_words(s));
  fit_text(cr, line1, font, v.width - 2 * margin);
  cairo_move_to(cr, margin, 1.15 * font);
  cairo_show_text(cr, line1.c_str());
  // A sandbag beyond the picture: its distance at the right end of the second line (next to the
  // arrow it would cover the machine or jump about from frame to frame).
  double room = v.width - 2 * margin;
  if (!bag_visible) {
    const std::string out = fmt::format("sandbag {:.4g} m out", std::hypot(s.x, s.h));
    fit_text(cr, out, 0.9 * font, 0.45 * v.width);
    cairo_text_extents_t ext;
    cairo_text_extents(cr, out.c_str(), &ext);
    set(cr, kBagText);
    cairo_move_to(cr, v.width - margin - ext.x_advance, 2.3 * font);
    cairo_show_text(cr, out.c_str());
    room -= ext.x_advance + font;
  }
  std::string line2;
  if (frame.event_group >= 0) {
    const EventGroup& grp = groups[frame.event_group];
    line2 = fmt::format("event at {:.3f} s: ", grp.t);
    for (std::size_t i = 0; i < grp.events.size(); ++i) {
      line2 += (i ? " + " : "") + event_words(rec.result.events[grp.events[i]], true);
    }
    set(cr, kEventRed);
  } else {
    line2 = speed_words(frame.speed, frame.quiet);
    set(cr, kGrey);
  }
  fit_text(cr, line2, 0.9 * font, room);
  cairo_move_to(cr, margin, 2.3 * font);
  cairo_show_text(cr, line2.c_str());
}

namespace {

// Where the time bar lies in the frame, and where a time of the run is on it.
struct Bar {
  double x0, x1, y, t_end;
  double x(double t) const { return x0 + (x1 - x0) * std::clamp(t / t_end, 0.0, 1.0); }
};
Bar bar_of(const View& v, const Recording& rec) {
  const double font = v.font, margin = 0.5 * font;
  return {margin + 3.2 * font, v.width - margin - 4.2 * font, v.bottom + 0.9 * font,
          std::max(rec.t_end(), 1e-9)};
}

// The events' names under the bar: one row if they fit, else two rows of smaller ones, alternating.
// Leaves the font size of the names set.
struct NameRows {
  int rows = 1;
  double size = 0.0;                              // font size [px]
  std::vector<double> widths;                     // of each name
  std::vector<std::vector<std::size_t>> members;  // the names in each row
  std::vector<std::vector<double>> pos;           // and their centres [px]
};
NameRows place_names(cairo_t* cr, const View& v, const std::vector<std::string>& names,
                     const std::vector<double>& want) {
  const double font = v.font, margin = 0.5 * font;
  NameRows n;
  n.size = 0.62 * font;
  for (; n.rows <= 2; ++n.rows, n.size = 0.5 * font) {
    cairo_set_font_size(cr, n.size);
    n.widths.clear();
    for (const std::string& name : names) {
      cairo_text_extents_t ext;
      cairo_text_extents(cr, name.c_str(), &ext);
      n.widths.push_back(ext.x_advance);
    }
    n.members.assign(n.rows, {});
    n.pos.assign(n.rows, {});
    bool ok = true;
    for (int r = 0; r < n.rows; ++r) {
      std::vector<double> c, w;
      for (std::size_t i = r; i < names.size(); i += n.rows) {
        n.members[r].push_back(i), c.push_back(want[i]), w.push_back(n.widths[i]);
      }
      ok = placement::pack_row(c, w, margin, v.width - margin, 0.4 * n.size, n.pos[r]) && ok;
    }
    if (ok || n.rows == 2) break;
  }
  return n;
}

// Each event's name under its tick, with a thin line leading to it.
void event_names(cairo_t* cr, const View& v, const Recording& rec, const std::vector<EventGroup>& groups,
                 const Bar& bar) {
  const double font = v.font;
  std::vector<std::string> names;
  std::vector<double> want;
  for (const EventGroup& grp : groups) {
    const Event& first = rec.result.events[grp.events.front()];
    names.push_back(std::string(short_words(first.type)) + (grp.events.size() > 1 ? "+" : ""));
    want.push_back(bar.x(grp.t));
  }
  const NameRows n = place_names(cr, v, names, want);
  for (int r = 0; r < static_cast<int>(n.members.size()); ++r) {
    const double base = bar.y + (n.rows == 1 ? 1.55 : 1.35 + 0.6 * r) * font;
    for (std::size_t k = 0; k < n.members[r].size(); ++k) {
      const std::size_t i = n.members[r][k];
      set(cr, kMidGrey);
      cairo_set_line_width(cr, 1.0);
      cairo_move_to(cr, want[i], bar.y + 0.5 * font);
      cairo_line_to(cr, n.pos[r][k], base - 0.8 * n.size);
      cairo_stroke(cr);
      set(cr, kEventRed);
      cairo_move_to(cr, n.pos[r][k] - 0.5 * n.widths[i], base);
      cairo_show_text(cr, names[i].c_str());
    }
  }
}

}  // namespace

void time_bar(cairo_t* cr, const View& v, const Recording& rec, const std::vector<EventGroup>& groups,
              const Frame& frame) {
  const double font = v.font;
  const double margin = 0.5 * font;
  const Bar bar = bar_of(v, rec);
  set(cr, kMidGrey);
  cairo_set_line_width(cr, 3.0);
  cairo_move_to(cr, bar.x0, bar.y);
  cairo_line_to(cr, bar.x1, bar.y);
  cairo_stroke(cr);
  set(cr, kEventRed);
  cairo_set_line_width(cr, 1.5);
  for (const EventGroup& grp : groups) {
    cairo_move_to(cr, bar.x(grp.t), bar.y - 0.45 * font);
    cairo_line_to(cr, bar.x(grp.t), bar.y + 0.45 * font);
    cairo_stroke(cr);
  }
  event_names(cr, v, rec, groups, bar);
  // Where this frame is, and the run's ends.
  set(cr, kCursor);
  cairo_new_sub_path(cr);
  cairo_arc(cr, bar.x(frame.t), bar.y, 0.35 * font, 0.0, 2.0 * units::kPi);
  cairo_fill(cr);
  set(cr, kBlack);
  cairo_set_font_size(cr, 0.75 * font);
  cairo_move_to(cr, margin, bar.y + 0.3 * font);
  cairo_show_text(cr, "0 s");
  const std::string end = fmt::format("{:.3g} s", rec.t_end());
  cairo_move_to(cr, bar.x1 + 0.6 * font, bar.y + 0.3 * font);
  cairo_show_text(cr, end.c_str());
}

}  // namespace whatnext::viz::draw
