// The machine drawn to scale with Cairo, frame by frame, and written as GIF (giflib, fixed
// palette: deterministic and enough for a drawing of a few flat colours) or MP4 (ffmpeg).
#include "whatnext/viz/animation.hpp"

#include <cairo.h>
#include <fcntl.h>
#include <gif_lib.h>
#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <sstream>
#include <string_view>

#include <fmt/format.h>

#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/geometry.hpp"
#include "whatnext/output.hpp"
#include "whatnext/viz/plots.hpp"
#include "placement.hpp"

namespace whatnext::viz {

namespace fs = std::filesystem;

namespace {

constexpr double kPi = 3.14159265358979323846;

// ---- palette: a 6x7x6 colour cube, three greys and the transparent index 255 ----
constexpr int kLevelsRB = 6, kLevelsG = 7;
constexpr int kCube = kLevelsRB * kLevelsG * kLevelsRB;  // 252
constexpr std::array<int, 3> kGreys{96, 160, 224};
constexpr int kTransparent = 255;

int level_rb(int i) { return i * 51; }
int level_g(int i) { return i * 255 / 6; }  // 0 42 85 127 170 212 255

std::array<GifColorType, 256> make_palette() {
  std::array<GifColorType, 256> pal{};
  for (int r = 0; r < kLevelsRB; ++r) {
    for (int g = 0; g < kLevelsG; ++g) {
      for (int b = 0; b < kLevelsRB; ++b) {
        auto& c = pal[(r * kLevelsG + g) * kLevelsRB + b];
        c.Red = static_cast<GifByteType>(level_rb(r));
        c.Green = static_cast<GifByteType>(level_g(g));
        c.Blue = static_cast<GifByteType>(level_rb(b));
      }
    }
  }
  for (int i = 0; i < 3; ++i) {
    const auto v = static_cast<GifByteType>(kGreys[i]);
    pal[kCube + i] = {v, v, v};
  }
  pal[kTransparent] = {255, 0, 255};
  return pal;
}

// Nearest palette entry: the nearest cube colour or the nearest grey, whichever is closer.
std::uint8_t palette_index(std::uint32_t argb) {
  const int r = (argb >> 16) & 0xff, g = (argb >> 8) & 0xff, b = argb & 0xff;
  const int ir = (r + 25) / 51, ib = (b + 25) / 51;
  const int ig = std::min(6, (g * 6 + 127) / 255);
  auto sq = [](int v) { return v * v; };
  int best = (ir * kLevelsG + ig) * kLevelsRB + ib;
  int dist = sq(r - level_rb(ir)) + sq(g - level_g(ig)) + sq(b - level_rb(ib));
  for (int i = 0; i < 3; ++i) {
    const int d = sq(r - kGreys[i]) + sq(g - kGreys[i]) + sq(b - kGreys[i]);
    if (d < dist) dist = d, best = kCube + i;
  }
  return static_cast<std::uint8_t>(best);
}

// ---- colours of the drawing (all on the palette) ----
constexpr Rgb kWhite{255, 255, 255}, kBlack{0, 0, 0}, kDark{51, 42, 51}, kGrey{96, 96, 96},
    kMidGrey{160, 160, 160}, kLightGrey{224, 224, 224}, kSeesaw{153, 85, 51}, kBoxWall{153, 127, 51},
    kBoxInside{255, 255, 204}, kLid{51, 85, 153}, kRadio{51, 42, 102}, kDial{204, 212, 255},
    kEventRed{204, 0, 0}, kBagText{153, 85, 0}, kCursor{0, 85, 204};

void set(cairo_t* cr, Rgb c) { cairo_set_source_rgb(cr, c.r / 255.0, c.g / 255.0, c.b / 255.0); }

// ---- the slack rope and string: a parabola sagging under its chord, as long as the rope ----
std::vector<Vec2> sag_curve(Vec2 a, Vec2 b, double length, int n = 48) {
  std::vector<Vec2> pts;
  const double chord = norm(b - a);
  auto point = [&](double s, double d) { return a + s * (b - a) + Vec2{0.0, -4.0 * d * s * (1.0 - s)}; };
  auto arc = [&](double d) {
    double len = 0.0;
    Vec2 prev = a;
    for (int i = 1; i <= n; ++i) {
      const Vec2 p = point(static_cast<double>(i) / n, d);
      len += norm(p - prev);
      prev = p;
    }
    return len;
  };
  double d = 0.0;
  if (chord < length - 1e-9) {
    double lo = 0.0, hi = length;
    for (int it = 0; it < 60; ++it) {
      const double mid = 0.5 * (lo + hi);
      (arc(mid) < length ? lo : hi) = mid;
    }
    d = 0.5 * (lo + hi);
  }
  for (int i = 0; i <= n; ++i) pts.push_back(point(static_cast<double>(i) / n, d));
  return pts;
}

// Is a point inside the box, under its lid (or under the box's top while the lid is open)?
bool in_box(const Machine& m, Vec2 lid_edge, Vec2 p) {
  const Vec2 hinge = m.hinge;
  if (p.x <= hinge.x || p.x >= hinge.x + 2.0 * m.lid_half_length) return false;
  double top = hinge.h;
  if (lid_edge.x > hinge.x + 1e-9 && p.x <= lid_edge.x) {
    top = std::max(top, hinge.h + (p.x - hinge.x) * (lid_edge.h - hinge.h) / (lid_edge.x - hinge.x));
  }
  return p.h < top;
}

// The slack rope from the seesaw's end a to the lid's edge e, as long as the rope: a parabola under
// its chord, unless that would hang through the lid into the box. Then the rope lies on the lid
// from its edge back towards the hinge and hangs from the hinge (or, with less rope to spare, runs
// straight from the seesaw to a point on the lid).
std::vector<Vec2> slack_rope(const Machine& m, Vec2 a, Vec2 e, double length) {
  std::vector<Vec2> pts = sag_curve(a, e, length);
  // The ends are tied to the seesaw and to the lid's edge, which lies on the lid's line: only the
  // points between them can hang into the box (an end counted "under the lid" by a rounding error
  // drew the slack rope straight and along the open lid).
  if (std::none_of(pts.begin() + 1, pts.end() - 1, [&](Vec2 p) { return in_box(m, e, p); })) return pts;
  const Vec2 hinge = m.hinge;
  const double rest = length - norm(e - hinge);
  if (rest >= norm(a - hinge)) {
    pts = sag_curve(a, hinge, rest);
    pts.push_back(e);
    return pts;
  }
  // |e - p| + |p - a| = length for p between e (too short) and the hinge (too long).
  double lo = 0.0, hi = 1.0;
  for (int it = 0; it < 60; ++it) {
    const double mid = 0.5 * (lo + hi);
    const Vec2 p = e + mid * (hinge - e);
    (norm(e - p) + norm(p - a) < length ? lo : hi) = mid;
  }
  return {a, e + lo * (hinge - e), e};
}

// The balloon's string from its knot to the radio switch. While the knot is inside the box the
// string runs over the box's far wall and hangs from there with what is left of it.
// The string's length counts from the balloon's centre (as the radio's switch condition does), so
// it is drawn from the point of the balloon's skin that faces where it goes, with r_B less.
std::vector<Vec2> string_path(const Machine& m, Vec2 balloon) {
  const Vec2 corner{m.hinge.x + 2.0 * m.lid_half_length, m.hinge.h};
  const bool over_wall = balloon.h < corner.h && m.radio_switch.x > corner.x;
  const Vec2 target = over_wall ? corner : m.radio_switch;
  const Vec2 dir = target - balloon;
  const double dist = norm(dir);
  const Vec2 knot = dist > 0.0 ? balloon + (m.balloon_radius / dist) * dir : balloon;
  const double length = std::max(0.0, m.string_length - m.balloon_radius);
  if (!over_wall) return sag_curve(knot, m.radio_switch, length);
  std::vector<Vec2> pts{knot};
  const double rest = std::max(0.0, length - norm(corner - knot));
  for (Vec2 p : sag_curve(corner, m.radio_switch, rest)) pts.push_back(p);
  return pts;
}

double landing_distance(const Scenario& sc) {
  return std::fabs(sc.start.sandbag_x) / std::max(0.2, std::cos(sc.start.seesaw_angle));
}

// Where the model has it: the box's centre for the paper's balloon, anywhere in the plane for one
// smaller than the box (docs/extensions.md "A balloon smaller than the box").
Vec2 balloon_centre(const Machine& m, const Snapshot& s) {
  return {m.hinge.x + s.balloon_x, m.hinge.h + s.balloon_h};
}

double ground_level(const Machine& m) { return m.hinge.h - 2.0 * m.lid_half_length; }

// The rope let go at the seesaw's end: hanging from the lid's edge e straight down into the open
// box (the radio's latch holds the lid short of 90 deg, so e is above the box); what reaches the
// floor lies on it, folded between the walls. Beside the box it would lie on the ground, away from it.
std::vector<Vec2> hanging_rope(const Machine& m, Vec2 e, double length) {
  const double floor = ground_level(m);
  const double drop = std::clamp(e.h - floor, 0.0, length);
  std::vector<Vec2> pts{e, {e.x, e.h - drop}};
  double rest = length - drop;
  const double x0 = m.hinge.x, x1 = m.hinge.x + 2.0 * m.lid_half_length;
  if (rest <= 0.0) return pts;
  if (e.x < x0 || e.x > x1) {
    pts.push_back({e.x < x0 ? e.x - rest : e.x + rest, floor});
    return pts;
  }
  double x = e.x;
  for (bool right = true; rest > 0.0; right = !right) {
    const double along = std::min(rest, right ? x1 - x : x - x0);
    x += right ? along : -along;
    rest -= along;
    pts.push_back({x, floor});
  }
  return pts;
}

// The radio: its body stands on the ground under the switch (or hangs below a switch that is lower).
struct RadioBox {
  double x0, x1, h0, h1;
};
RadioBox radio_box(const Machine& m) {
  const double w = 0.36 * std::max(0.5, 2.0 * m.lid_half_length);
  const double g = ground_level(m);
  const double top = m.radio_switch.h - 0.03;
  const double bottom = top - g > 0.08 ? g : top - 0.25 * w * 2.0;
  return {m.radio_switch.x - 0.5 * w, m.radio_switch.x + 0.5 * w, bottom, top};
}

// Drawn length of the left arm at time t: a finite arm as it is; the model's endless arm long
// enough to catch the sandbag, and once it is on the arm as long as the farthest it has been out
// (and a little more). It does not shrink when the sandbag leaves it (the radio's latch sets it free).
double drawn_arm(const Recording& rec, double endless_default, double t) {
  const Machine& m = rec.scenario.machine;
  if (std::isfinite(m.seesaw_left_arm)) return m.seesaw_left_arm;
  double far = 0.0;
  for (std::size_t i = 0; i < rec.states.size() && rec.states[i].t <= t; ++i) {
    if (rec.states[i].on_seesaw) far = std::max(far, rec.states[i].r);
  }
  return std::max(endless_default, far + 0.1);
}

// A span up to this many rope lengths counts as the rope's length: the taut rope's closure holds
// the span to rounding, and the slack rope drawn straight is then no visible bit longer.
constexpr double kSpanTolerance = 1.0 + 1e-9;

// The radio's latch: lid_open in a run with the radio, which lets the rope go for good (without
// the radio lid_open ends the run); infinity if there is none.
double latch_time(const Recording& rec) {
  if (rec.scenario.machine.radio) {
    for (const Event& e : rec.result.events) {
      if (e.type == EventType::lid_open) return e.t;
    }
  }
  return std::numeric_limits<double>::infinity();
}

bool beyond_rope(const RopeGeometry& geo, const Snapshot& s) {
  return geo.span(s.phi_s, s.phi_l) > kSpanTolerance * geo.rope_length();
}

// Distance from the pivot beyond which the view no longer follows the sandbag.
double follow_radius(const Recording& rec, double left_arm) {
  const Machine& m = rec.scenario.machine;
  return 2.2 * std::max({m.seesaw_right_arm, left_arm, norm(m.hinge) + 2.0 * m.lid_half_length});
}

struct Bounds {
  double x0 = std::numeric_limits<double>::infinity(), x1 = -x0, h0 = x0, h1 = -x0;
  void add(Vec2 p) {
    if (!std::isfinite(p.x) || !std::isfinite(p.h)) return;
    x0 = std::min(x0, p.x), x1 = std::max(x1, p.x), h0 = std::min(h0, p.h), h1 = std::max(h1, p.h);
  }
};

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

// ---- GIF output through giflib's low-level encoder ----
thread_local int g_gif_errno = 0;  // why the last write failed, for the message

int gif_write(GifFileType* gif, const GifByteType* data, int n) {
  const int fd = *static_cast<int*>(gif->UserData);
  for (int done = 0; done < n;) {
    const ssize_t w = ::write(fd, data + done, static_cast<std::size_t>(n - done));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      g_gif_errno = w < 0 ? errno : EIO;
      return 0;
    }
    done += static_cast<int>(w);
  }
  return n;
}

class GifEncoder {
 public:
  GifEncoder(int& fd, int width, int height) : w_(width), h_(height) {
    int err = 0;
    gif_ = EGifOpen(&fd, gif_write, &err);
    if (!gif_) throw std::runtime_error(fmt::format("GIF: {}", GifErrorString(err)));
    EGifSetGifVersion(gif_, true);
    auto pal = make_palette();
    ColorMapObject* map = GifMakeMapObject(256, pal.data());
    check(EGifPutScreenDesc(gif_, w_, h_, 8, 0, map));
    GifFreeMapObject(map);
    // Loop for ever (the NETSCAPE2.0 application extension).
    check(EGifPutExtensionLeader(gif_, APPLICATION_EXT_FUNC_CODE));
    check(EGifPutExtensionBlock(gif_, 11, "NETSCAPE2.0"));
    const unsigned char loop[3] = {1, 0, 0};
    check(EGifPutExtensionBlock(gif_, 3, loop));
    check(EGifPutExtensionTrailer(gif_));
  }
  ~GifEncoder() {
    if (gif_) {
      int err = 0;
      EGifCloseFile(gif_, &err);
    }
  }
  // Each frame after the first stores only the rectangle that changed, with unchanged pixels
  // transparent over the previous frame: far smaller files for a mostly still scene.
  void add(const std::vector<std::uint8_t>& idx, int delay_cs) {
    int x0 = 0, y0 = 0, x1 = w_ - 1, y1 = h_ - 1;
    const bool first = prev_.empty();
    if (!first) {
      x0 = w_, y0 = h_, x1 = -1, y1 = -1;
      for (int y = 0; y < h_; ++y) {
        for (int x = 0; x < w_; ++x) {
          if (idx[y * w_ + x] != prev_[y * w_ + x]) {
            x0 = std::min(x0, x), x1 = std::max(x1, x), y0 = std::min(y0, y), y1 = std::max(y1, y);
          }
        }
      }
      if (x1 < 0) x0 = x1 = y0 = y1 = 0;  // nothing changed: one transparent pixel
    }
    GraphicsControlBlock gcb{};
    gcb.DisposalMode = DISPOSE_DO_NOT;
    gcb.UserInputFlag = false;
    gcb.DelayTime = delay_cs;
    gcb.TransparentColor = first ? NO_TRANSPARENT_COLOR : kTransparent;
    GifByteType ext[4];
    const size_t n = EGifGCBToExtension(&gcb, ext);
    check(EGifPutExtension(gif_, GRAPHICS_EXT_FUNC_CODE, static_cast<int>(n), ext));
    const int w = x1 - x0 + 1, h = y1 - y0 + 1;
    check(EGifPutImageDesc(gif_, x0, y0, w, h, false, nullptr));
    std::vector<GifByteType> row(w);
    for (int y = y0; y <= y1; ++y) {
      for (int x = x0; x <= x1; ++x) {
        const std::uint8_t v = idx[y * w_ + x];
        row[x - x0] = (!first && v == prev_[y * w_ + x]) ? kTransparent : v;
      }
      check(EGifPutLine(gif_, row.data(), w));
    }
    prev_ = idx;
  }
  void close() {
    int err = 0;
    const int ok = EGifCloseFile(gif_, &err);
    gif_ = nullptr;
    if (ok != GIF_OK) throw std::runtime_error(fmt::format("GIF: {}", GifErrorString(err)));
  }

 private:
  void check(int rc) {
    if (rc != GIF_OK) throw std::runtime_error(fmt::format("GIF: {}", GifErrorString(gif_->Error)));
  }
  GifFileType* gif_ = nullptr;
  int w_, h_;
  std::vector<std::uint8_t> prev_;
};

std::string find_on_path(const std::string& name) {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream ss(path);
  std::string dir;
  while (std::getline(ss, dir, ':')) {
    if (dir.empty()) continue;
    const std::string candidate = dir + "/" + name;
    if (::access(candidate.c_str(), X_OK) == 0) return candidate;
  }
  return "";
}

std::string shell_quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
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

bool is_mp4(const std::string& path, const std::string& option) {
  const std::string ext = fs::path(path).extension().string();
  std::string lower;
  for (char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".mp4") return true;
  if (lower == ".gif") return false;
  throw InputError(fmt::format("{}: the animation must be a .gif or .mp4 file, got '{}'", option, path));
}

Pixel to_pixel(const View& v, Vec2 p) { return {v.origin_x + p.x * v.scale, v.origin_y - p.h * v.scale}; }

View make_view(const Recording& rec, int width, int height) {
  const Machine& m = rec.scenario.machine;
  const RopeGeometry geo(m);
  View v;
  v.width = width;
  v.left_arm = std::max(m.seesaw_right_arm, 1.2 * landing_distance(rec.scenario));
  const double follow = follow_radius(rec, v.left_arm);

  // The machine over the whole run, and the sandbag while it falls onto the arm or stays on the
  // part of the arm drawn at its shortest.
  Bounds box;
  const double g = ground_level(m), rl = m.lid_half_length;
  box.add({0.0, 0.0});
  box.add({-0.15, g});
  box.add({0.15, g});
  box.add({m.hinge.x - 0.05, g});
  box.add({m.hinge.x + 2.0 * rl + 0.05, m.hinge.h});
  box.add(m.hinge + Vec2{0.0, 2.0 * rl});
  const RadioBox radio = radio_box(m);
  box.add({radio.x0 - 0.05, radio.h0});
  box.add({radio.x1 + 0.05, radio.h1 + 0.05});
  if (rec.result.outcome().type == EventType::radio_on) box.add({radio.x1, radio.h1 + 0.25});  // notes
  bool landed = false;
  const double bag = 0.05;  // the sandbag's drawn radius [m] (at least 6 px)
  for (const Snapshot& s : rec.states) {
    box.add(geo.seesaw_end(s.phi_s));
    box.add(geo.lid_edge(s.phi_l));                              // the rope's knot
    box.add(m.hinge + polar(2.0 * m.lid_half_length, s.phi_l));  // the lid's free edge
    box.add(polar(-v.left_arm, s.phi_s));
    landed = landed || s.on_seesaw;
    if (!landed || std::hypot(s.x, s.h) <= v.left_arm) {
      box.add({s.x - bag, s.h - bag});
      box.add({s.x + bag, s.h + bag});
    }
    const Vec2 c = balloon_centre(m, s);
    if (c.h - m.hinge.h <= follow) {
      box.add(c + Vec2{m.balloon_radius, m.balloon_radius});
      box.add(c - Vec2{m.balloon_radius, m.balloon_radius});
    }
  }
  for (const Snapshot* s : {&rec.states.front(), &rec.states.back()}) {
    for (Vec2 p : string_path(m, balloon_centre(m, *s))) box.add(p);
  }
  const double pad = 0.04 * std::max(box.x1 - box.x0, box.h1 - box.h0);
  box.x0 -= pad, box.x1 += pad, box.h0 -= pad, box.h1 += pad;

  // Text above, the time bar with its event names below, the machine in between.
  v.font = std::clamp(height > 0 ? std::min(width / 40.0, height / 30.0) : width / 40.0, 9.0, 22.0);
  v.top = static_cast<int>(std::lround(2.7 * v.font));
  const int below = static_cast<int>(std::lround(3.3 * v.font));
  if (height <= 0) {
    const double needed = (box.h1 - box.h0) * width / (box.x1 - box.x0);
    height = static_cast<int>(std::lround(v.top + needed + below));
    height = std::clamp(height, static_cast<int>(0.45 * width), static_cast<int>(1.25 * width));
    height += height % 2;  // even, as H.264 wants
  }
  v.height = height;
  v.bottom = height - below;
  const double area_w = width, area_h = v.bottom - v.top;
  v.scale = std::min(area_w / (box.x1 - box.x0), area_h / (box.h1 - box.h0));
  v.origin_x = 0.5 * area_w - 0.5 * (box.x0 + box.x1) * v.scale;
  v.origin_y = v.top + 0.5 * area_h + 0.5 * (box.h0 + box.h1) * v.scale;
  return v;
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

std::vector<Vec2> rope_path(const Recording& rec, const Snapshot& s) {
  const Machine& m = rec.scenario.machine;
  const RopeGeometry geo(m);
  const Vec2 r = geo.seesaw_end(s.phi_s), e = geo.lid_edge(s.phi_l);
  if (s.rope_taut) return {r, e};
  // Before the latch the model keeps the span within the rope's length (to its tolerance; a frame
  // between two recorded taut states, its angles interpolated, has the ends up to 3e-5 m too far
  // apart in example 3, a hundredth of a pixel): the slack rope sags, or is straight at full stretch.
  const double latch = latch_time(rec);
  if (s.t < latch) return slack_rope(m, r, e, m.rope_length);
  // After it nothing holds the rope. Once pulled off the seesaw's end it stays off, even where a
  // seesaw swinging back brings its end near enough again.
  bool off = beyond_rope(geo, s);
  for (auto it = std::lower_bound(rec.states.begin(), rec.states.end(), latch,
                                  [](const Snapshot&q, double t) { return q.t < t; });
       !off && it != rec.states.end() && it->t <= s.t; ++it) {
    off = beyond_rope(geo, *it);
  }
  if (off) return hanging_rope(m, e, m.rope_length);
  // Within the tolerance of the rope's length: straight, and a hair short of the seesaw's end.
  const double span = norm(r - e);
  if (span > m.rope_length) return {e + (m.rope_length / span) * (r - e), e};
  return slack_rope(m, r, e, m.rope_length);
}

Rgb Image::at(int x, int y) const {
  const std::uint32_t p = pixels[static_cast<std::size_t>(y) * width + x];
  return {static_cast<std::uint8_t>(p >> 16), static_cast<std::uint8_t>(p >> 8),
          static_cast<std::uint8_t>(p)};
}

Image render_frame(const Recording& rec, const View& v, const Frame& frame,
                   const AnimationOptions& /*opts*/) {
  const Machine& m = rec.scenario.machine;
  const RopeGeometry geo(m);
  const Snapshot& s = frame.state;
  const std::vector<EventGroup> groups = group_events(rec.result);
  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, v.width, v.height);
  cairo_t* cr = cairo_create(surface);
  set(cr, kWhite);
  cairo_paint(cr);

  auto px = [&](Vec2 p) { return to_pixel(v, p); };
  auto move = [&](Vec2 p) {
    const Pixel q = px(p);
    cairo_move_to(cr, q.x, q.y);
  };
  auto line = [&](Vec2 p) {
    const Pixel q = px(p);
    cairo_line_to(cr, q.x, q.y);
  };
  auto width_m = [&](double metres, double min_px) {
    cairo_set_line_width(cr, std::max(min_px, metres * v.scale));
  };
  auto polyline = [&](const std::vector<Vec2>& pts) {
    move(pts.front());
    for (std::size_t i = 1; i < pts.size(); ++i) line(pts[i]);
  };
  auto circle = [&](Vec2 c, double radius_px) {
    const Pixel q = px(c);
    cairo_new_sub_path(cr);
    cairo_arc(cr, q.x, q.y, radius_px, 0.0, 2.0 * kPi);
  };

  // Machine drawing, clipped to its band.
  cairo_save(cr);
  cairo_rectangle(cr, 0, v.top, v.width, v.bottom - v.top);
  cairo_clip(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  const double g = ground_level(m), rl = m.lid_half_length;
  const Vec2 hinge = m.hinge;
  const RadioBox radio = radio_box(m);

  // Floor pieces under the pivot stand, the box and the radio (the paper's model has no floor
  // elsewhere: the sandbag's arm is endless and may dip below them); the built machine's floor
  // (floor.enabled) runs across the picture, with the ground below it.
  set(cr, kMidGrey);
  width_m(0.01, 2.0);
  if (m.floor) {
    const Pixel q = px({0.0, g});
    set(cr, kLightGrey);
    cairo_rectangle(cr, 0, q.y, v.width, v.bottom - q.y);
    cairo_fill(cr);
    set(cr, kMidGrey);
    cairo_move_to(cr, 0, q.y);
    cairo_line_to(cr, v.width, q.y);
    cairo_stroke(cr);
  }
  for (auto [a, b] : {std::pair{-0.15, 0.15}, std::pair{hinge.x - 0.05, hinge.x + 2 * rl + 0.05},
                      std::pair{radio.x0 - 0.05, radio.x1 + 0.05}}) {
    if (m.floor) break;
    move({a, g});
    line({b, g});
    cairo_stroke(cr);
  }
  // Pivot stand.
  set(cr, kGrey);
  move({0.0, 0.0});
  line({-0.07, g});
  line({0.07, g});
  cairo_close_path(cr);
  cairo_fill(cr);

  // Box inside, then the balloon, then the walls in front.
  set(cr, kBoxInside);
  cairo_rectangle(cr, px(hinge).x, px(hinge).y, 2 * rl * v.scale, 2 * rl * v.scale);
  cairo_fill(cr);

  const Vec2 bc = balloon_centre(m, s);
  set(cr, kGrey);
  cairo_set_line_width(cr, 1.5);
  polyline(string_path(m, bc));
  cairo_stroke(cr);
  set(cr, kBalloonColour);
  circle(bc, m.balloon_radius * v.scale);
  cairo_fill(cr);

  set(cr, kBoxWall);
  width_m(0.02, 3.0);
  move(hinge);
  line({hinge.x, g});
  line({hinge.x + 2 * rl, g});
  line({hinge.x + 2 * rl, hinge.h});
  cairo_stroke(cr);

  // Radio with its switch, where the balloon's string is tied.
  set(cr, kRadio);
  cairo_rectangle(cr, px({radio.x0, radio.h1}).x, px({radio.x0, radio.h1}).y, (radio.x1 - radio.x0) * v.scale,
                  (radio.h1 - radio.h0) * v.scale);
  cairo_fill(cr);
  set(cr, kDial);
  circle(
      {0.5 * (radio.x0 + radio.x1), 0.5 * (radio.h0 + radio.h1)},
      0.3 * (radio.x1 - radio.x0) * v.scale * std::min(1.0, (radio.h1 - radio.h0) / (radio.x1 - radio.x0)));
  cairo_fill(cr);
  set(cr, kDark);
  width_m(0.012, 2.0);
  move({m.radio_switch.x, radio.h1});
  line(m.radio_switch);
  cairo_stroke(cr);

  // Once the radio is on, notes rise from it (above it, where make_view keeps room).
  for (const Event& e : rec.result.events) {
    if (e.type != EventType::radio_on || e.t > frame.t) continue;
    set(cr, kRadio);
    cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(cr, std::max(10.0, 0.12 * v.scale));
    cairo_text_extents_t ext;
    cairo_text_extents(cr, "\u266A \u266B", &ext);
    const Pixel q = px({0.5 * (radio.x0 + radio.x1), radio.h1 + 0.08});
    cairo_move_to(cr, q.x - 0.5 * ext.x_advance, q.y);
    cairo_show_text(cr, "\u266A \u266B");
  }

  // The moving parts; the built machine stands on its floor, so nothing of them is drawn below it
  // (a sandbag lying there, a point in the model, is half a disc).
  if (m.floor) {
    cairo_rectangle(cr, 0, 0, v.width, px({0.0, g}).y);
    cairo_clip(cr);
  }

  // Lid on its hinge.
  set(cr, kLid);
  width_m(0.025, 3.0);
  move(hinge);
  line(hinge + polar(2.0 * m.lid_half_length, s.phi_l));  // the whole lid; the rope is tied at its knot
  cairo_stroke(cr);
  set(cr, kBlack);
  circle(hinge, std::max(2.0, 0.012 * v.scale));
  cairo_fill(cr);

  // Seesaw: the left arm is as long as needed (the model's arm is endless).
  const double arm = drawn_arm(rec, v.left_arm, frame.t);
  set(cr, kSeesaw);
  width_m(0.03, 4.0);
  move(polar(-arm, s.phi_s));
  line(geo.seesaw_end(s.phi_s));
  if (m.end_stop) {  // an edge standing up from the left arm's end, above the sandbag drawn there
    move(polar(-arm, s.phi_s));
    line(polar(-arm, s.phi_s) + polar(std::max(0.08, 10.0 / v.scale), s.phi_s + 0.5 * kPi));
  }
  cairo_stroke(cr);
  set(cr, kBlack);
  circle({0.0, 0.0}, std::max(2.5, 0.015 * v.scale));
  cairo_fill(cr);

  // Rope: straight when taut; slack, sagging or lying on the lid; let go, hanging from the lid.
  set(cr, kDark);
  cairo_set_line_width(cr, std::max(1.5, 0.008 * v.scale));
  polyline(rope_path(rec, s));
  cairo_stroke(cr);

  // Sandbag, centred on the simulated point.
  const Pixel bag = px({s.x, s.h});
  const double bag_r = std::max(6.0, 0.05 * v.scale);
  const bool bag_visible =
      bag.x >= -bag_r && bag.x <= v.width + bag_r && bag.y >= v.top - bag_r && bag.y <= v.bottom + bag_r;
  if (bag_visible) {
    set(cr, kSandbagColour);
    cairo_new_sub_path(cr);
    cairo_arc(cr, bag.x, bag.y, bag_r, 0.0, 2.0 * kPi);
    cairo_fill_preserve(cr);
    set(cr, kDark);
    cairo_set_line_width(cr, 1.0);
    cairo_stroke(cr);
  }
  cairo_restore(cr);

  const double font = v.font;
  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  if (!bag_visible) {
    // An arrow at the edge of the picture, pointing from the pivot to the sandbag far out.
    const Pixel o = px({0.0, 0.0});
    const double dx = bag.x - o.x, dy = bag.y - o.y, len = std::hypot(dx, dy);
    const double ux = dx / len, uy = dy / len;
    double tmax = std::numeric_limits<double>::infinity();
    if (ux > 0) tmax = std::min(tmax, (v.width - 12 - o.x) / ux);
    if (ux < 0) tmax = std::min(tmax, (12 - o.x) / ux);
    if (uy > 0) tmax = std::min(tmax, (v.bottom - 12 - o.y) / uy);
    if (uy < 0) tmax = std::min(tmax, (v.top + 12 - o.y) / uy);
    const double tx = o.x + ux * tmax, ty = o.y + uy * tmax;
    set(cr, kSandbagColour);
    cairo_move_to(cr, tx, ty);
    cairo_line_to(cr, tx - 14 * ux - 7 * uy, ty - 14 * uy + 7 * ux);
    cairo_line_to(cr, tx - 14 * ux + 7 * uy, ty - 14 * uy - 7 * ux);
    cairo_close_path(cr);
    cairo_fill(cr);
  }

  // Text: time and mode; on held frames the event, otherwise the speed.
  const double margin = 0.5 * font;
  set(cr, kLightGrey);
  cairo_rectangle(cr, 0, 0, v.width, v.top);
  cairo_fill(cr);
  set(cr, kBlack);
  const std::string line1 = fmt::format("t = {:.3f} s    {}", frame.t, mode_words(s.mode));
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

  // Time bar: the whole run, its events (named under their ticks) and where this frame is.
  const double t_end = std::max(rec.t_end(), 1e-9);
  const double bx0 = margin + 3.2 * font, bx1 = v.width - margin - 4.2 * font;
  const double by = v.bottom + 0.9 * font;
  auto bar_x = [&](double t) { return bx0 + (bx1 - bx0) * std::clamp(t / t_end, 0.0, 1.0); };
  set(cr, kMidGrey);
  cairo_set_line_width(cr, 3.0);
  cairo_move_to(cr, bx0, by);
  cairo_line_to(cr, bx1, by);
  cairo_stroke(cr);
  set(cr, kEventRed);
  cairo_set_line_width(cr, 1.5);
  for (const EventGroup& grp : groups) {
    cairo_move_to(cr, bar_x(grp.t), by - 0.45 * font);
    cairo_line_to(cr, bar_x(grp.t), by + 0.45 * font);
    cairo_stroke(cr);
  }
  {
    std::vector<std::string> names;
    std::vector<double> want, widths, at;
    for (const EventGroup& grp : groups) {
      const Event& first = rec.result.events[grp.events.front()];
      names.push_back(std::string(short_words(first.type)) + (grp.events.size() > 1 ? "+" : ""));
      want.push_back(bar_x(grp.t));
    }
    // One row if the names fit, else two rows of smaller ones, alternating.
    int rows = 1;
    double size = 0.62 * font;
    std::vector<std::vector<std::size_t>> members;
    std::vector<std::vector<double>> pos;
    for (; rows <= 2; ++rows, size = 0.5 * font) {
      cairo_set_font_size(cr, size);
      widths.clear();
      for (const std::string& n : names) {
        cairo_text_extents_t ext;
        cairo_text_extents(cr, n.c_str(), &ext);
        widths.push_back(ext.x_advance);
      }
      members.assign(rows, {});
      pos.assign(rows, {});
      bool ok = true;
      for (int r = 0; r < rows; ++r) {
        std::vector<double> c, w;
        for (std::size_t i = r; i < names.size(); i += rows) {
          members[r].push_back(i), c.push_back(want[i]), w.push_back(widths[i]);
        }
        ok = placement::pack_row(c, w, margin, v.width - margin, 0.4 * size, pos[r]) && ok;
      }
      if (ok || rows == 2) break;
    }
    for (int r = 0; r < static_cast<int>(members.size()); ++r) {
      const double base = by + (rows == 1 ? 1.55 : 1.35 + 0.6 * r) * font;
      for (std::size_t k = 0; k < members[r].size(); ++k) {
        const std::size_t i = members[r][k];
        set(cr, kMidGrey);
        cairo_set_line_width(cr, 1.0);
        cairo_move_to(cr, want[i], by + 0.5 * font);
        cairo_line_to(cr, pos[r][k], base - 0.8 * size);
        cairo_stroke(cr);
        set(cr, kEventRed);
        cairo_move_to(cr, pos[r][k] - 0.5 * widths[i], base);
        cairo_show_text(cr, names[i].c_str());
      }
    }
  }
  set(cr, kCursor);
  cairo_new_sub_path(cr);
  cairo_arc(cr, bar_x(frame.t), by, 0.35 * font, 0.0, 2.0 * kPi);
  cairo_fill(cr);
  set(cr, kBlack);
  cairo_set_font_size(cr, 0.75 * font);
  cairo_move_to(cr, margin, by + 0.3 * font);
  cairo_show_text(cr, "0 s");
  const std::string end = fmt::format("{:.3g} s", rec.t_end());
  cairo_move_to(cr, bx1 + 0.6 * font, by + 0.3 * font);
  cairo_show_text(cr, end.c_str());

  cairo_destroy(cr);
  cairo_surface_flush(surface);
  Image img;
  img.width = v.width;
  img.height = v.height;
  img.pixels.resize(static_cast<std::size_t>(v.width) * v.height);
  const unsigned char* data = cairo_image_surface_get_data(surface);
  const int stride = cairo_image_surface_get_stride(surface);
  for (int y = 0; y < v.height; ++y) {
    std::copy_n(reinterpret_cast<const std::uint32_t*>(data + static_cast<std::size_t>(y) * stride), v.width,
                img.pixels.begin() + static_cast<std::ptrdiff_t>(y) * v.width);
  }
  cairo_surface_destroy(surface);
  return img;
}

namespace {
cairo_status_t png_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  auto& out = *static_cast<std::ostream*>(closure);
  out.write(reinterpret_cast<const char*>(data), static_cast<std::streamsize>(length));
  return out ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}
}  // namespace

void write_png(const Image& image, const std::string& path) {
  const int stride = cairo_format_stride_for_width(CAIRO_FORMAT_RGB24, image.width);
  std::vector<unsigned char> buffer(static_cast<std::size_t>(stride) * image.height);
  for (int y = 0; y < image.height; ++y) {
    std::copy_n(image.pixels.begin() + static_cast<std::ptrdiff_t>(y) * image.width, image.width,
                reinterpret_cast<std::uint32_t*>(buffer.data() + static_cast<std::size_t>(y) * stride));
  }
  const auto file = AtomicFile::during_work(path, "--dump-frames");
  cairo_surface_t* s = cairo_image_surface_create_for_data(buffer.data(), CAIRO_FORMAT_RGB24, image.width,
                                                           image.height, stride);
  const cairo_status_t st = cairo_surface_write_to_png_stream(s, png_to_stream, &file->stream());
  cairo_surface_destroy(s);
  file->flush();  // a failed write: its reason (a full disk)
  if (st != CAIRO_STATUS_SUCCESS) {
    throw OutputError(
        fmt::format("--dump-frames {}: writing failed: {}", printable(path, 96), cairo_status_to_string(st)));
  }
  file->commit();
}

void check_animation_target(const std::string& path, const std::string& option) {
  if (is_mp4(path, option) && find_on_path("ffmpeg").empty()) {
    throw InputError(
        fmt::format("{}: writing '{}' needs ffmpeg on PATH, and there is none "
                    "(write a .gif instead)",
                    option, path));
  }
  const std::string dir = fs::path(path).parent_path().string();
  if (const int err = can_create_in(dir.empty() ? "." : dir)) {
    throw InputError(fmt::format("{}: cannot write '{}': {}", option, path, std::strerror(err)));
  }
}

namespace {
// MP4 through ffmpeg, which writes the temporary by name; every frame's write into its pipe and its
// exit status are checked, and a pipe ffmpeg closed early is an error, not SIGPIPE.
template <class Dump>
int write_mp4(const Recording& rec, const View& view, const std::vector<Frame>& frames,
              const AnimationOptions& opts, const std::string& ffmpeg, const std::string& path,
              const std::string& option, const Dump& dump, const std::function<void(int, int)>& progress) {
  const int total = static_cast<int>(frames.size());
  const auto file = AtomicFile::during_work(path, option);
  // Raw BGRA frames (Cairo's ARGB32 in memory on little-endian machines) into ffmpeg; held
  // frames are repeated for their time on screen.
  const std::string cmd = fmt::format(
      "{} -loglevel error -y -f rawvideo -pix_fmt bgra -s {}x{} -r {:g} -i - "
      "-vf pad=ceil(iw/2)*2:ceil(ih/2)*2 -c:v libx264 -pix_fmt yuv420p -f mp4 {}",
      shell_quote(ffmpeg), view.width, view.height, opts.fps, shell_quote(file->temp_path()));
  struct sigaction ignore {
  }, before{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &before);
  struct Restore {
    struct sigaction* before;
    ~Restore() { ::sigaction(SIGPIPE, before, nullptr); }
  } restore{&before};
  FILE* pipe = ::popen(cmd.c_str(), "w");
  if (!pipe) throw OutputError(fmt::format("{} {}: cannot start ffmpeg", option, printable(path, 96)));
  double shown = 0.0;
  long written = 0;
  int index = 0;
  bool ok = true;
  for (const Frame& f : frames) {
    const Image img = render_frame(rec, view, f, opts);
    dump(img, f, index);
    shown += f.delay;
    const long until = std::lround(shown * opts.fps);
    for (; ok && written < std::max(until, written + 1); ++written) {
      ok =
          std::fwrite(img.pixels.data(), sizeof(std::uint32_t), img.pixels.size(), pipe) == img.pixels.size();
    }
    ++index;
    if (progress) progress(index, total);
    if (!ok) break;
  }
  ok = std::fflush(pipe) == 0 && ok;
  if (::pclose(pipe) != 0 || !ok) {
    throw OutputError(
        fmt::format("{} {}: writing failed: ffmpeg could not write it", option, printable(path, 96)));
  }
  file->commit();
  return total;
}
}  // namespace

int write_animation(const Recording& rec, const std::string& path, const AnimationOptions& opts,
                    const std::string& dump_dir, const std::string& option,
                    const std::function<void(int, int)>& progress) {
  validate(opts);
  const bool mp4 = is_mp4(path, option);
  if (!mp4 && opts.fps > 50.0) {
    throw InputError(fmt::format(
        "--fps: a GIF takes at most 50 frames per second (its delays count in 1/100 s and viewers "
        "slow down shorter ones), got {:g}; write an .mp4 for more",
        opts.fps));
  }
  check_animation_target(path, option);
  const std::string ffmpeg = mp4 ? find_on_path("ffmpeg") : std::string();
  if (!dump_dir.empty()) prepare_output_dir(dump_dir, "--dump-frames");
  const std::vector<Frame> frames = plan_frames(rec, opts);
  const View view = make_view(rec, opts.width, opts.height);
  const int total = static_cast<int>(frames.size());
  // The held frames and one frame per second on screen, for looking at single frames.
  const int dump_every = std::max(1, static_cast<int>(std::lround(opts.fps)));
  auto dump = [&](const Image& img, const Frame& f, int index) {
    if (dump_dir.empty() || (f.event_group < 0 && index % dump_every != 0)) return;
    write_png(img, (fs::path(dump_dir) / fmt::format("frame{:05d}.png", index)).string());
  };

  if (mp4) return write_mp4(rec, view, frames, opts, ffmpeg, path, option, dump, progress);

  const auto file = AtomicFile::during_work(path, option);
  int fd = file->descriptor();
  g_gif_errno = 0;
  auto failed = [&](int err) {  // the work is done: a write error, not bad input (exit code 1)
    return OutputError(
        fmt::format("{} {}: writing failed: {}", option, printable(path, 96), std::strerror(err)));
  };
  try {
    GifEncoder gif(fd, view.width, view.height);
    double shown = 0.0;
    long shown_cs = 0;
    int index = 0;
    std::vector<std::uint8_t> idx(static_cast<std::size_t>(view.width) * view.height);
    for (const Frame& f : frames) {
      const Image img = render_frame(rec, view, f, opts);
      dump(img, f, index);
      for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = palette_index(img.pixels[i]);
      // Delays in centiseconds, rounded on the running total so that they do not drift.
      shown += f.delay;
      const long until = std::lround(shown * 100.0);
      gif.add(idx, static_cast<int>(std::max(1L, until - shown_cs)));
      shown_cs = std::max(until, shown_cs + 1);
      ++index;
      if (progress) progress(index, total);
    }
    gif.close();
  } catch (const std::runtime_error&) {
    // giflib's "Write failed (disk full?)": say which file and why (a full disk, ulimit -f).
    if (g_gif_errno == 0) throw;
    throw failed(g_gif_errno);
  }
  file->commit();  // closes the descriptor (checked) and puts the file in place
  return static_cast<int>(frames.size());
}

}  // namespace whatnext::viz
