// The machine drawn to scale with Cairo, frame by frame, and written as GIF (giflib, fixed
// palette: deterministic and enough for a drawing of a few flat colours) or MP4 (ffmpeg).
// The stages live in their own files: the scene's geometry (scene.cpp), the view (view.cpp), the
// frames' plan (frame_plan.cpp), drawing the parts (draw_machine.cpp) and the texts
// (frame_text.cpp), the GIF encoder (gif_encoder.cpp).
#include "whatnext/viz/animation.hpp"

#include <cairo.h>
#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>

#include <fmt/format.h>

#include "draw_frame.hpp"
#include "gif_encoder.hpp"
#include "scene.hpp"
#include "whatnext/config.hpp"
#include "whatnext/events.hpp"
#include "whatnext/output.hpp"
#include "whatnext/viz/plots.hpp"

namespace whatnext::viz {

namespace fs = std::filesystem;

namespace {

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

// Cairo's pixels into an Image (0xAARRGGBB, row by row without the stride's padding).
Image to_image(cairo_surface_t* surface, const View& v) {
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
  return img;
}

}  // namespace

bool is_mp4(const std::string& path, const std::string& option) {
  const std::string ext = fs::path(path).extension().string();
  std::string lower;
  for (char c : ext) lower += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  if (lower == ".mp4") return true;
  if (lower == ".gif") return false;
  throw InputError(fmt::format("{}: the animation must be a .gif or .mp4 file, got '{}'", option, path));
}

Rgb Image::at(int x, int y) const {
  const std::uint32_t p = pixels[static_cast<std::size_t>(y) * width + x];
  return {static_cast<std::uint8_t>(p >> 16), static_cast<std::uint8_t>(p >> 8),
          static_cast<std::uint8_t>(p)};
}

// A frame in stages: the scene's geometry for this state, the machine drawn part by part behind and
// in front of each other (clipped to its band, and above the built machine's floor), then the
// texts around it.
Image render_frame(const Recording& rec, const View& v, const Frame& frame,
                   const AnimationOptions& /*opts*/) {
  const Snapshot& s = frame.state;
  const std::vector<EventGroup> groups = group_events(rec.result);
  const scene::StillParts still = scene::still_parts(rec.scenario.machine);
  const double arm = scene::drawn_arm(rec, v.left_arm, frame.t);
  const scene::MovingParts moving =
      scene::moving_parts(rec.scenario.machine, s, scene::release_of(rec), arm, scene::stop_height(v.scale));

  cairo_surface_t* surface = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, v.width, v.height);
  cairo_t* cr = cairo_create(surface);
  const draw::Pen pen{cr, v};
  draw::set(cr, draw::kWhite);
  cairo_paint(cr);

  cairo_save(cr);
  cairo_rectangle(cr, 0, v.top, v.width, v.bottom - v.top);
  cairo_clip(cr);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  draw::floor(pen, still);
  draw::stand(pen, still);
  draw::box_inside(pen, still);  // the box's inside, then the balloon, then the walls in front
  draw::balloon(pen, moving);
  draw::walls(pen, still);
  draw::radio(pen, still);
  for (const Event& e : rec.result.events) {
    if (e.type == EventType::radio_on && e.t <= frame.t) draw::notes(pen, still);
  }
  // The moving parts; the built machine stands on its floor, so nothing of them is drawn below it
  // (a sandbag lying there, a point in the model, is half a disc).
  if (still.floor) {
    cairo_rectangle(cr, 0, 0, v.width, pen.px({0.0, still.ground}).y);
    cairo_clip(cr);
  }
  draw::lid(pen, moving);
  draw::seesaw(pen, moving);
  draw::rope(pen, moving);
  Pixel bag;
  const bool bag_visible = draw::sandbag(pen, moving, bag);
  cairo_restore(cr);

  cairo_select_font_face(cr, "DejaVu Sans", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  if (!bag_visible) draw::sandbag_arrow(pen, bag);
  draw::caption(cr, v, rec, groups, frame, bag_visible);
  draw::time_bar(cr, v, rec, groups, frame);

  cairo_destroy(cr);
  Image img = to_image(surface, v);
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
// ffmpeg, started without a shell (its arguments as they are) with a pipe for the frames, and
// killed by an interrupt before the temporaries are removed (it writes its own by name).
class FfmpegPipe {
 public:
  FfmpegPipe(const std::vector<std::string>& args, const std::string& option, const std::string& path) {
    int fds[2];
    if (::pipe2(fds, O_CLOEXEC) != 0) fail(option, path);
    std::vector<char*> argv;
    for (const std::string& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    posix_spawn_file_actions_t actions;
    posix_spawn_file_actions_init(&actions);
    posix_spawn_file_actions_adddup2(&actions, fds[0], 0);  // (the copy on 0 is not close-on-exec)
    pid_ = start_writing_process([&] {
      pid_t pid = -1;
      return ::posix_spawn(&pid, argv[0], &actions, nullptr, argv.data(), environ) == 0 ? pid : -1;
    });
    posix_spawn_file_actions_destroy(&actions);
    ::close(fds[0]);
    if (pid_ <= 0) {
      ::close(fds[1]);
      fail(option, path);
    }
    out_ = ::fdopen(fds[1], "w");
    if (!out_) {
      ::close(fds[1]);
      finish();
      fail(option, path);
    }
  }
  FfmpegPipe(const FfmpegPipe&) = delete;
  FfmpegPipe& operator=(const FfmpegPipe&) = delete;
  ~FfmpegPipe() {
    if (pid_ > 0) finish();  // an exception on the way: end of input, and ffmpeg's end awaited
  }
  bool write(const void* data, std::size_t size, std::size_t count) {
    return std::fwrite(data, size, count, out_) == count;
  }
  // Closes the pipe and waits for ffmpeg: true if every byte went and it exited with 0.
  bool finish() {
    bool ok = true;
    if (out_) {
      ok = std::fflush(out_) == 0;
      ok = std::fclose(out_) == 0 && ok;
      out_ = nullptr;
    }
    forget_writing_process(pid_);
    int status = 0;
    while (::waitpid(pid_, &status, 0) < 0 && errno == EINTR) {
    }
    pid_ = -1;
    return ok && WIFEXITED(status) && WEXITSTATUS(status) == 0;
  }

 private:
  [[noreturn]] static void fail(const std::string& option, const std::string& path) {
    throw OutputError(fmt::format("{} {}: cannot start ffmpeg", option, printable(path, 96)));
  }
  int pid_ = -1;
  FILE* out_ = nullptr;
};

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
  std::vector<std::string> args = {ffmpeg, "-loglevel", "error", "-y", "-f", "rawvideo", "-pix_fmt", "bgra"};
  args.insert(args.end(), {"-s", fmt::format("{}x{}", view.width, view.height)});
  args.insert(args.end(), {"-r", fmt::format("{:g}", opts.fps), "-i", "-"});
  args.insert(args.end(), {"-vf", "pad=ceil(iw/2)*2:ceil(ih/2)*2"});  // H.264 wants even sizes
  args.insert(args.end(), {"-c:v", "libx264", "-pix_fmt", "yuv420p", "-f", "mp4", file->temp_path()});
  struct sigaction ignore {
  }, before{};
  ignore.sa_handler = SIG_IGN;
  ::sigaction(SIGPIPE, &ignore, &before);
  struct Restore {
    struct sigaction* before;
    ~Restore() { ::sigaction(SIGPIPE, before, nullptr); }
  } restore{&before};
  FfmpegPipe pipe(args, option, path);
  double shown = 0.0;
  long written = 0;
  int index = 0;
  bool ok = true;
  for (const Frame& f : frames) {
    const Image img = render_frame(rec, view, f, opts);
    dump(img, f, index);
    shown += f.delay;
    // Up to the frame's end in whole video frames, and at least one (the bound fixed before the
    // loop: a bound of written + 1 re-read in it never ends).
    const long until = std::max(std::lround(shown * opts.fps), written + 1);
    for (; ok && written < until; ++written) {
      ok = pipe.write(img.pixels.data(), sizeof(std::uint32_t), img.pixels.size());
    }
    ++index;
    if (progress) progress(index, total);
    if (!ok) break;
  }
  if (!pipe.finish() || !ok) {
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
  gif::g_write_errno = 0;
  auto failed = [&](int err) {  // the work is done: a write error, not bad input (exit code 1)
    return OutputError(
        fmt::format("{} {}: writing failed: {}", option, printable(path, 96), std::strerror(err)));
  };
  try {
    gif::Encoder gif(fd, view.width, view.height);
    double shown = 0.0;
    long shown_cs = 0;
    int index = 0;
    std::vector<std::uint8_t> idx(static_cast<std::size_t>(view.width) * view.height);
    for (const Frame& f : frames) {
      const Image img = render_frame(rec, view, f, opts);
      dump(img, f, index);
      for (std::size_t i = 0; i < idx.size(); ++i) idx[i] = gif::palette_index(img.pixels[i]);
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
    if (gif::g_write_errno == 0) throw;
    throw failed(gif::g_write_errno);
  }
  file->commit();  // closes the descriptor (checked) and puts the file in place
  return static_cast<int>(frames.size());
}

}  // namespace whatnext::viz
