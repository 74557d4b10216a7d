// The animation's frames: which stretches of the run are shown how fast, and the held frames at
// the events.
#include <algorithm>
#include <cmath>
#include <limits>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/viz/animation.hpp"

namespace whatnext::viz {

namespace {

struct Piece {  // a stretch of simulated time shown at one speed
  double t0, t1, speed;
  bool quiet;
};
struct Warp {
  std::vector<Piece> pieces;
  double hold;  // seconds on screen of each event's frame
};

// Which stretches of the run are shown how fast, so that the whole fits into max_length seconds.
Warp time_warp(const Recording& rec, const AnimationOptions& opts) {
  const double t_end = rec.t_end();
  const std::size_t groups = group_events(rec.result).size();
  std::vector<double> keys{0.0};
  for (const EventGroup& g : group_events(rec.result)) keys.push_back(g.t);
  keys.push_back(t_end);
  std::sort(keys.begin(), keys.end());
  const double pad = 0.4;  // simulated seconds shown slowly on either side of an event
  Warp w;
  double active = 0.0, quiet = 0.0;
  for (std::size_t i = 0; i + 1 < keys.size(); ++i) {
    const double a = keys[i], b = keys[i + 1];
    if (b <= a) continue;
    if (b - a > 3.0 * pad) {
      w.pieces.push_back({a, a + pad, 0.0, false});
      w.pieces.push_back({a + pad, b - pad, 0.0, true});
      w.pieces.push_back({b - pad, b, 0.0, false});
      active += 2.0 * pad, quiet += b - a - 2.0 * pad;
    } else {
      w.pieces.push_back({a, b, 0.0, false});
      active += b - a;
    }
  }
  if (w.pieces.empty()) w.pieces.push_back({0.0, t_end, 0.0, false}), active = t_end;

  // Screen time: the held frames (the last one twice), the slow stretches, the quiet ones. Each
  // piece may run over by up to one frame; that is kept free.
  const double budget = opts.max_length - static_cast<double>(w.pieces.size()) / opts.fps;
  const double holds = static_cast<double>(groups) + 1.0;
  w.hold = std::min(opts.hold, std::max(0.0, 0.5 * budget / holds));
  const double rest = std::max(1e-3, budget - holds * w.hold);
  double slow = 1.0 / opts.slowmo, fast = slow;  // simulated seconds per second on screen
  if ((active + quiet) / slow > rest) {
    if (quiet > 0.0 && active / slow <= 0.75 * rest) {
      fast = quiet / (rest - active / slow);
    } else {
      slow = active / ((quiet > 0.0 ? 0.75 : 1.0) * rest);
      fast = quiet > 0.0 ? std::max(slow, quiet / (0.25 * rest)) : slow;
    }
  }
  for (Piece& p : w.pieces) {
    p.quiet = p.quiet && fast > slow;
    p.speed = p.quiet ? fast : slow;
  }
  return w;
}

}  // namespace

void validate(const AnimationOptions& o) {
  auto bad = [](const char* opt, const char* rule, double v) {
    throw InputError(fmt::format("{}: must be {}, got {:g}", opt, rule, v));
  };
  if (!(o.slowmo > 0.0 && o.slowmo <= 1e6)) bad("--slowmo", "> 0 and <= 1e6", o.slowmo);
  if (!(o.fps >= 1.0 && o.fps <= 100.0)) bad("--fps", "between 1 and 100", o.fps);
  if (!(o.width >= 64 && o.width <= 4096)) bad("--width", "between 64 and 4096 pixels", o.width);
  if (!(o.height == 0 || (o.height >= 64 && o.height <= 4096))) {
    bad("--height", "0 (fit the machine) or between 64 and 4096 pixels", o.height);
  }
  if (!(o.hold >= 0.0 && o.hold <= 60.0)) bad("--hold", "between 0 and 60 s", o.hold);
  if (!(o.max_length >= 1.0 && o.max_length <= 3600.0)) {
    bad("--max-length", "between 1 and 3600 s", o.max_length);
  }
}

std::vector<Frame> plan_frames(const Recording& rec, const AnimationOptions& opts) {
  validate(opts);
  const Warp warp = time_warp(rec, opts);
  const std::vector<EventGroup> groups = group_events(rec.result);
  std::vector<Frame> frames;
  std::size_t next_group = 0;
  auto hold_events_until = [&](double t) {
    while (next_group < groups.size() && groups[next_group].t <= t) {
      const EventGroup& g = groups[next_group];
      Frame f;
      f.t = g.t;
      f.state = rec.result.events[g.events.back()].after;
      f.delay = warp.hold;
      f.event_group = static_cast<int>(next_group);
      f.speed = frames.empty() ? warp.pieces.front().speed : frames.back().speed;
      frames.push_back(f);
      ++next_group;
    }
  };
  const double dt_screen = 1.0 / opts.fps;
  for (const Piece& p : warp.pieces) {
    const double step = p.speed * dt_screen;
    const auto n = static_cast<long>(std::ceil((p.t1 - p.t0) / step - 1e-9));
    for (long k = 0; k < n; ++k) {
      const double t = p.t0 + static_cast<double>(k) * step;
      hold_events_until(t);
      if (!frames.empty() && frames.back().event_group >= 0 && frames.back().t == t) continue;
      Frame f;
      f.t = t;
      f.state = rec.at(t);
      f.delay = dt_screen;
      f.speed = p.speed;
      f.quiet = p.quiet;
      frames.push_back(f);
    }
  }
  hold_events_until(std::numeric_limits<double>::infinity());
  // The last picture stays a little longer before the GIF starts over.
  if (!frames.empty()) frames.back().delay = std::max(frames.back().delay, 2.0 * warp.hold);
  return frames;
}

}  // namespace whatnext::viz
