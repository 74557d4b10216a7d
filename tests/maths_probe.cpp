// The maths functions the library calls, on a few thousand arguments each, as one hash of their
// results' bits per function. Built twice, natively (with the library's maths, cmake/maths.cmake)
// and by Emscripten (web/wasm), so that web/tests/maths_native.js can require the same bits of the
// two: the page's runs are then the command's to the last digit.
//   maths_probe [SEED [COUNT]]
// The arguments come from SEED at run time, so that the compiler cannot work the results out itself.
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>

namespace {

// splitmix64: a well-mixed sequence of 64-bit numbers from any seed.
struct Draw {
  std::uint64_t state;
  std::uint64_t bits() {
    std::uint64_t z = (state += 0x9e3779b97f4a7c15ULL);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ULL;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebULL;
    return z ^ (z >> 31);
  }
  // Uniform in [lo, hi).
  double in(double lo, double hi) { return lo + (hi - lo) * (static_cast<double>(bits() >> 11) * 0x1p-53); }
  // Spread over many orders of magnitude: [1, 2) times 2^[lo, hi), exactly (no function under test).
  double octaves(int lo, int hi) {
    return std::ldexp(in(1.0, 2.0), lo + static_cast<int>(bits() % (hi - lo)));
  }
};

// FNV-1a over the results' bits.
struct Hash {
  std::uint64_t h = 0xcbf29ce484222325ULL;
  void add(double x) {
    std::uint64_t b;
    std::memcpy(&b, &x, sizeof b);
    for (int i = 0; i < 8; ++i) {
      h ^= (b >> (8 * i)) & 0xff;
      h *= 0x100000001b3ULL;
    }
  }
};

void report(const char* name, std::uint64_t seed, int count, const std::function<double(Draw&)>& one) {
  Draw d{seed};
  Hash hash;
  for (int i = 0; i < count; ++i) hash.add(one(d));
  std::printf("%s %d %016llx\n", name, count, static_cast<unsigned long long>(hash.h));
}

}  // namespace

int main(int argc, char** argv) {
  const std::uint64_t seed = argc > 1 ? std::strtoull(argv[1], nullptr, 10) : 1;
  const int count = argc > 2 ? std::atoi(argv[2]) : 4000;
  // The machine's angles, and now and then a large one (argument reduction).
  const auto angle = [](Draw& d) { return d.bits() % 16 == 0 ? d.in(-1e6, 1e6) : d.in(-10.0, 10.0); };
  report("sin", seed, count, [&](Draw& d) { return std::sin(angle(d)); });
  report("cos", seed, count, [&](Draw& d) { return std::cos(angle(d)); });
  report("tan", seed, count, [&](Draw& d) { return std::tan(angle(d)); });
  // A sine and a cosine of one angle, which the compiler may merge into one sincos.
  report("sincos", seed, count, [&](Draw& d) {
    const double a = angle(d);
    return std::sin(a) - 3.0 * std::cos(a);
  });
  report("atan2", seed, count, [](Draw& d) { return std::atan2(d.in(-2.0, 2.0), d.in(-2.0, 2.0)); });
  report("asin", seed, count, [](Draw& d) { return std::asin(d.in(-1.0, 1.0)); });
  report("acos", seed, count, [](Draw& d) { return std::acos(d.in(-1.0, 1.0)); });
  report("hypot", seed, count,
         [](Draw& d) { return std::hypot(d.in(-3.0, 3.0), d.in(-3.0, 3.0) * d.octaves(-26, 6)); });
  report("pow", seed, count, [](Draw& d) { return std::pow(d.octaves(-20, 20), d.in(-5.0, 5.0)); });
  report("log", seed, count, [](Draw& d) { return std::log(d.octaves(-40, 40)); });
  report("log10", seed, count, [](Draw& d) { return std::log10(d.octaves(-40, 40)); });
  report("exp", seed, count, [](Draw& d) { return std::exp(d.in(-50.0, 50.0)); });
  report("exp2", seed, count, [](Draw& d) { return std::exp2(d.in(-50.0, 50.0)); });
  return 0;
}
