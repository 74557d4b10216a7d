// GIF output through giflib's low-level encoder, on a fixed palette: deterministic, and enough for
// a drawing of a few flat colours.
#pragma once

#include <gif_lib.h>

#include <cstdint>
#include <vector>

namespace whatnext::viz::gif {

// The palette index nearest to a Cairo pixel (0xAARRGGBB): a 6x7x6 colour cube and three greys.
std::uint8_t palette_index(std::uint32_t argb);

// Why the last write to the file failed (an errno), 0 if none: for the message, since giflib only
// says "Write failed".
extern thread_local int g_write_errno;

// Frames of palette indices into the open file descriptor fd, looping for ever. Throws
// std::runtime_error on giflib's errors.
class Encoder {
 public:
  Encoder(int& fd, int width, int height);
  ~Encoder();
  Encoder(const Encoder&) = delete;
  Encoder& operator=(const Encoder&) = delete;
  // Each frame after the first stores only the rectangle that changed, with unchanged pixels
  // transparent over the previous frame: far smaller files for a mostly still scene.
  void add(const std::vector<std::uint8_t>& idx, int delay_cs);
  void close();

 private:
  void check(int rc);
  GifFileType* gif_ = nullptr;
  int w_, h_;
  std::vector<std::uint8_t> prev_;
};

}  // namespace whatnext::viz::gif
