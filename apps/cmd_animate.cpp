// `whatnext animate`: the machine to scale as an animated GIF (or MP4 through ffmpeg).
#include <unistd.h>

#include <cstdio>
#include <memory>

#include <fmt/format.h>

#include "cli_common.hpp"
#include "whatnext/viz/animation.hpp"

namespace whatnext::cli {

namespace {
struct AnimateOptions {
  InputOptions input;
  std::string out, dump;
  viz::AnimationOptions anim;
  bool quiet = false, force_large = false;
};
}  // namespace

void register_animate(CLI::App& app, int& exit_code) {
  auto opts = std::make_shared<AnimateOptions>();
  CLI::App* cmd = app.add_subcommand("animate", "draw the machine moving, as an animated GIF or MP4");
  add_input_options(*cmd, opts->input);
  cmd->add_option("--out", opts->out, "FILE.gif, or FILE.mp4 (needs ffmpeg on PATH)")
      ->required()
      ->type_name("FILE");
  cmd->add_option("--slowmo", opts->anim.slowmo, "one simulated second lasts this many seconds")
      ->capture_default_str()
      ->transform(number_text(false));
  cmd->add_option("--fps", opts->anim.fps,
                  "frames per second (a GIF: at most 50, viewers slow down shorter frames)")
      ->capture_default_str()
      ->transform(number_text(false));
  cmd->add_option("--width", opts->anim.width, "[px]")->capture_default_str()->transform(number_text(true));
  cmd->add_option("--height", opts->anim.height, "[px] (default: as high as the machine needs)")
      ->transform(number_text(true));
  cmd->add_option("--hold", opts->anim.hold, "seconds each event's frame is held")
      ->capture_default_str()
      ->transform(number_text(false));
  cmd->add_option("--max-length", opts->anim.max_length,
                  "seconds on screen at most; longer runs are fast-forwarded between events")
      ->capture_default_str()
      ->transform(number_text(false));
  cmd->add_option("--dump-frames", opts->dump,
                  "also write the held frames and one frame per second as PNG into this directory")
      ->type_name("DIR");
  cmd->add_flag("-q,--quiet", opts->quiet, "print nothing");
  cmd->add_flag("--force-large", opts->force_large,
                "animate runs whose states would take more than 256 MB of memory");
#if !WHATNEXT_FULL
  (void)exit_code;
  cmd->callback([opts] { hand_over_to_full(); });  // opts: the options write into it
#else
  cmd->callback([opts, cmd, &exit_code] {
    check_leftovers(*cmd);
    const LoadedInput in = load_input(opts->input);
    check_size(in.scenario, kStateBytes, "animate", opts->force_large, "hold in memory");
    viz::validate(opts->anim);
    // Checked before the run: the extension, a regular file (symlinks followed), a writable place.
    const std::string target = regular_output_target(opts->out, "--out");
    viz::check_animation_target(target, "--out");
    check_unclaimed("--out", target);
    if (given(*cmd, "--dump-frames")) prepare_picture_dir(opts->dump, "--dump-frames");
    // Progress on stderr: a counter on a terminal, otherwise a line every 100 frames.
    const bool tty = ::isatty(STDERR_FILENO) != 0;
    auto progress = [&](int done, int total) {
      if (opts->quiet) return;
      if (tty) {
        std::fprintf(stderr, "\ranimate: frame %d of %d", done, total);
        if (done == total) std::fputc('\n', stderr);
      } else if (done % 100 == 0 || done == total) {
        std::fprintf(stderr, "animate: frame %d of %d\n", done, total);
      }
    };
    const int frames =
        viz::write_animation(viz::record(in.scenario), target, opts->anim, opts->dump, "--out", progress);
    if (!opts->quiet) fmt::print("{}: {} frames\n", printable(opts->out, 96), frames);
    exit_code = 0;
  });
#endif
}

}  // namespace whatnext::cli
