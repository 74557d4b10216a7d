// GIF output through giflib's low-level encoder (gif_encoder.hpp).
#include "gif_encoder.hpp"

#include <unistd.h>

#include <algorithm>
#include <array>
#include <cerrno>
#include <stdexcept>

#include <fmt/format.h>

namespace whatnext::viz::gif {

thread_local int g_write_errno = 0;

namespace {

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

int gif_write(GifFileType* gif, const GifByteType* data, int n) {
  const int fd = *static_cast<int*>(gif->UserData);
  for (int done = 0; done < n;) {
    const ssize_t w = ::write(fd, data + done, static_cast<std::size_t>(n - done));
    if (w < 0 && errno == EINTR) continue;
    if (w <= 0) {
      g_write_errno = w < 0 ? errno : EIO;
      return 0;
    }
    done += static_cast<int>(w);
  }
  return n;
}

}  // namespace

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

Encoder::Encoder(int& fd, int width, int height) : w_(width), h_(height) {
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

Encoder::~Encoder() {
  if (gif_) {
    int err = 0;
    EGifCloseFile(gif_, &err);
  }
}

void Encoder::add(const std::vector<std::uint8_t>& idx, int delay_cs) {
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

void Encoder::close() {
  int err = 0;
  const int ok = EGifCloseFile(gif_, &err);
  gif_ = nullptr;
  if (ok != GIF_OK) throw std::runtime_error(fmt::format("GIF: {}", GifErrorString(err)));
}

void Encoder::check(int rc) {
  if (rc != GIF_OK) throw std::runtime_error(fmt::format("GIF: {}", GifErrorString(gif_->Error)));
}

}  // namespace whatnext::viz::gif
