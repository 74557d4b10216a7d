// An animation of the machine, to scale: frames drawn with Cairo, written as a GIF (giflib) or
// piped to ffmpeg for MP4.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "whatnext/vec2.hpp"
#include "whatnext/viz/recording.hpp"

namespace whatnext::viz {

struct AnimationOptions {
  double slowmo = 12.0;      // one simulated second lasts this many seconds on screen
  double fps = 25.0;         // frames per second on screen (a GIF: at most 50)
  int width = 800;           // pixels
  int height = 0;            // pixels; 0: as high as the machine needs at this width
  double hold = 1.2;         // seconds each event's frame is held on screen
  double max_length = 20.0;  // seconds on screen, at most: quiet stretches (and, if need be, the
                             // held frames and the slow motion) are shortened to fit
};
// Throws InputError naming the option when a value is out of range.
void validate(const AnimationOptions& opts);

// World (metres, origin at the pivot, h up) to pixels (origin top left, y down), the same scale on
// both axes.
struct View {
  int width = 0, height = 0;
  double scale = 1.0;     // pixels per metre
  double origin_x = 0.0;  // pixel of the pivot
  double origin_y = 0.0;
  int top = 0, bottom = 0;  // the drawing area is rows [top, bottom); text above, time bar below
  double font = 12.0;       // text size [px]
  double left_arm = 0.0;    // drawn length of the seesaw's left arm before the sandbag lands [m]
};
struct Pixel {
  double x = 0.0, y = 0.0;
};
Pixel to_pixel(const View& view, Vec2 p);
// The view that frames the machine over the whole run: pivot, seesaw, box, lid, balloon, radio, and
// the sandbag until it lands and while it stays within the arm's drawn length (the model's left
// arm is endless; further out an arrow at the edge points to the sandbag). height 0: the picture is
// as high as the machine needs at this width (between 0.45 and 1.25 times the width).
View make_view(const Recording& rec, int width, int height);

// The rope as drawn in state s of the run, a polyline in metres from the seesaw's end (or the lid's
// edge): straight while taut; slack, sagging under the line between the seesaw's end and the lid's
// edge, or lying on the closed lid and hanging from the hinge. With the radio the model lets the
// rope go at lid_open for good, and a heavy seesaw may swing its end farther from the lid's edge
// than the rope reaches: from the first such instant on the rope has come off the seesaw's end and
// hangs from the lid's edge straight down into the open box (what reaches the floor lies on it).
// After the latch the polyline is never longer than the rope; before it the model keeps its ends
// within the rope's length.
std::vector<Vec2> rope_path(const Recording& rec, const Snapshot& s);

// One frame: a state to draw and how long it stays on screen.
struct Frame {
  double t = 0.0;
  double delay = 0.04;  // seconds on screen
  Snapshot state;
  int event_group = -1;  // index into group_events(): this frame is held at that event
  double speed = 1.0;    // simulated seconds per second on screen (1/slowmo when not fast-forwarding)
  bool quiet = false;    // in a stretch without events, shown faster than the events
};
// The frames of the animation: equally spaced on screen, with simulated time slowed down by slowmo
// and one held frame at every instant with events. A run that would last longer than max_length
// on screen is fitted into it: first the stretches more than 0.4 s away from any event are played
// faster, then, if that is not enough, the held frames and the slow motion are shortened too.
std::vector<Frame> plan_frames(const Recording& rec, const AnimationOptions& opts);

// Colours of the machine's parts (exactly representable in the GIF palette).
struct Rgb {
  std::uint8_t r, g, b;
};
constexpr Rgb kSandbagColour{204, 127, 0};
constexpr Rgb kBalloonColour{255, 42, 51};

// An image as Cairo draws it: 0xAARRGGBB per pixel, row by row.
struct Image {
  int width = 0, height = 0;
  std::vector<std::uint32_t> pixels;
  Rgb at(int x, int y) const;
};
Image render_frame(const Recording& rec, const View& view, const Frame& frame, const AnimationOptions& opts);
void write_png(const Image& image, const std::string& path);

// Writes the animation to path: .gif with giflib, .mp4 through ffmpeg (InputError when ffmpeg is
// not on PATH, or for a GIF above 50 frames per second: its delays count in 1/100 s and viewers
// slow down shorter ones). If dump_dir is not empty, the held frames and one frame per second on
// screen are also written there as PNG (for looking at single frames). progress, if given, is
// called after each frame with the frames done and the total. Returns the number of frames.
// Errors name `option`, the command-line option that gave the path.
int write_animation(const Recording& rec, const std::string& path, const AnimationOptions& opts,
                    const std::string& dump_dir = "", const std::string& option = "--out",
                    const std::function<void(int done, int total)>& progress = {});

// Checks before any work that path can take an animation: a .gif or .mp4 name, ffmpeg on PATH for
// .mp4, a writable place. InputError naming option otherwise.
void check_animation_target(const std::string& path, const std::string& option);

// True for paths ending in .mp4; InputError (naming option) for anything else but .gif.
bool is_mp4(const std::string& path, const std::string& option = "--out");

}  // namespace whatnext::viz
