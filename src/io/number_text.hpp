// Decimal text of doubles for the output files, written into a caller's buffer without allocating:
// the .dat's Fortran F8.3 and the CSV's %.9g. The text is exactly fmt's for "{:8.3f}" and
// "{:.9g}" (the correctly rounded decimal, ties to even); numbers outside the range where the
// exact scaling below works are handed to fmt itself. fmt needs 60-100 ns per number here, which
// made the rows cost ten times the disk (docs/performance.md, "Output files").
#pragma once

#include <bit>
#include <cmath>
#include <cstdint>
#include <cstring>

#include <fmt/format.h>

namespace whatnext::numtext {

namespace detail {

inline constexpr double kPow10[23] = {1e0,  1e1,  1e2,  1e3,  1e4,  1e5,  1e6,  1e7,  1e8,  1e9,  1e10, 1e11,
                                      1e12, 1e13, 1e14, 1e15, 1e16, 1e17, 1e18, 1e19, 1e20, 1e21, 1e22};

// n = a * 10^k rounded to the nearest integer, ties to even, exactly; false where that is not
// certain (|k| > 22, where 10^k is not a double, or a result beyond 2^52). 10^k is exact, so the
// only rounding is that of the product (quotient) p, and the FMA gives its error exactly: the true
// value is p + delta with |delta| <= ulp(p)/2. p's fraction f is a multiple of ulp(p), as is 0.5,
// so f != 0.5 decides alone; f == 0.5 is decided by the sign of delta, an exact tie by evenness.
inline bool scaled(double a, int k, std::uint64_t& n) {
  if (k > 22 || k < -22) return false;  // folded away where k is a constant
  const double m = kPow10[k < 0 ? -k : k];
  const double p = k >= 0 ? a * m : a / m;
  if (!(p < 0x1p52)) return false;
  const auto whole = static_cast<std::int64_t>(p);  // floor: p >= 0
  const double f = p - static_cast<double>(whole);
  n = static_cast<std::uint64_t>(whole) + (f > 0.5 ? 1u : 0u);  // no branch: f is noise
  if (f == 0.5) {
    // The sign of the rounding error of p (exact through the FMA): only needed at a half.
    const double delta = k >= 0 ? std::fma(a, m, -p) : std::fma(-p, m, a);
    if (delta > 0.0 || (delta == 0.0 && (n & 1u))) ++n;
  }
  return true;
}

inline constexpr char kPairs[] =
    "00010203040506070809101112131415161718192021222324252627282930313233343536373839"
    "40414243444546474849505152535455565758596061626364656667686970717273747576777879"
    "8081828384858687888990919293949596979899";

// Writes the `count` lowest decimal digits of v, leading zeros included, ending before `end`.
inline void digits_back(char* end, std::uint32_t v, int count) {
  for (; count >= 2; count -= 2) {
    end -= 2;
    std::memcpy(end, kPairs + 2 * (v % 100), 2);
    v /= 100;
  }
  if (count) *--end = static_cast<char>('0' + v % 10);
}

inline char* g9_by_fmt(char* out, double v) { return fmt::format_to(out, "{:.9g}", v); }

// The eight decimal digits of x < 10^8 as ASCII in one word, the first digit in the lowest byte
// (so that storing it little-endian writes them in reading order): Paul Khuong's SWAR split into
// 4 + 4, 2 + 2 and 1 + 1 digits, a handful of multiplications instead of a division per digit.
inline std::uint64_t ascii8(std::uint32_t x) {
  const std::uint64_t merged = (x / 10000) | (std::uint64_t{x % 10000} << 32);
  const std::uint64_t top = ((merged * 10486u) >> 20) & ((std::uint64_t{0x7F} << 32) | 0x7Fu);
  const std::uint64_t bottom = merged - 100u * top;
  const std::uint64_t hundreds = (bottom << 16) + top;
  std::uint64_t tens = (hundreds * 103u) >> 10;
  tens &= (std::uint64_t{0xF} << 48) | (std::uint64_t{0xF} << 32) | (std::uint64_t{0xF} << 16) | 0xFu;
  tens += (hundreds - 10u * tens) << 8;
  return tens + 0x3030303030303030u;
}

// F8.3's two halves as text, made at compile time: the whole part right-aligned in four
// characters ("   0" to "9999") and the point with three decimals (".000" to ".999"). 44 KB, of
// which a run touches the few lines of its own numbers; a number is then two loads instead of
// eight digits' arithmetic (a third of the .dat's instructions; docs/performance.md).
struct F83Text {
  char whole[10000 * 4];
  char fraction[1000 * 4];
};
constexpr F83Text make_f83_text() {
  F83Text t{};
  for (int w = 0; w < 10000; ++w) {
    int x = w;
    for (int i = 3; i >= 0; --i) {
      t.whole[4 * w + i] = (i == 3 || x > 0) ? static_cast<char>('0' + x % 10) : ' ';
      x /= 10;
    }
  }
  for (int f = 0; f < 1000; ++f) {
    t.fraction[4 * f] = '.';
    t.fraction[4 * f + 1] = static_cast<char>('0' + f / 100);
    t.fraction[4 * f + 2] = static_cast<char>('0' + f / 10 % 10);
    t.fraction[4 * f + 3] = static_cast<char>('0' + f % 10);
  }
  return t;
}
inline constexpr F83Text kF83 = make_f83_text();

// scaled(a, 3, n) for 0 <= a < 1e4, whose tie is decided without the FMA (a library call where
// the build has no FMA instructions, in a quarter of the .dat's rows: the time column's ties).
// 1000 = 1024 - 16 - 8, and 1024 a - p, then minus 16 a, then minus 8 a are each exact (Sterbenz:
// the operands are within a factor of two of each other), which leaves p's rounding error exactly.
inline std::uint64_t thousandths(double a) {
  const double p = a * 1000.0;  // < 1e7: far inside the exact range of scaled()
  const auto whole = static_cast<std::int64_t>(p);
  const double f = p - static_cast<double>(whole);
  std::uint64_t n = static_cast<std::uint64_t>(whole) + (f > 0.5 ? 1u : 0u);
  if (f == 0.5) {
    const double delta = ((a * 1024.0 - p) - a * 16.0) - a * 8.0;
    if (delta > 0.0 || (delta == 0.0 && (n & 1u))) ++n;
  }
  return n;
}

}  // namespace detail

// Fortran's F8.3 as fmt's "{:8.3f}" writes it, or eight asterisks when it takes more than eight
// characters. v must be finite. Returns the end of the eight characters written.
inline char* put_f8_3(char* out, double v) {
  constexpr int kWidth = 8;
  const double a = std::fabs(v);
  const bool negative = std::signbit(v);
  std::uint64_t n = 0;
  // Eight characters hold "9999.999" and "-999.999"; anything from 1e4 on is wider.
  if (!(a < 1e4) || (n = detail::thousandths(a)) >= (negative ? 1'000'000u : 10'000'000u)) {
    std::memset(out, '*', kWidth);
    return out + kWidth;
  }
  const auto whole = static_cast<std::uint32_t>(n / 1000), fraction = static_cast<std::uint32_t>(n % 1000);
  std::memcpy(out, detail::kF83.whole + 4 * whole, 4);
  std::memcpy(out + 4, detail::kF83.fraction + 4 * fraction, 4);
  // The sign in the blank before the first digit (there is one: whole < 1000 when negative).
  if (negative) out[(whole < 10 ? 1 : 0) + (whole < 100 ? 1 : 0) + (whole < 1000 ? 1 : 0) - 1] = '-';
  return out + kWidth;
}

// The C library's %.9g as fmt's "{:.9g}" writes it: nine significant digits, trailing zeros
// dropped, an exponent (two digits at least) outside 1e-4 <= |v| < 1e9. v must be finite. Writes
// at most 16 characters and returns their end, but may scribble up to kG9Room characters from out.
inline constexpr int kG9Room = 24;
inline char* put_g9(char* out, double v) {
  constexpr int kDigits = 9;
  if (v == 0.0) {
    if (std::signbit(v)) *out++ = '-';
    *out++ = '0';
    return out;
  }
  const double a = std::fabs(v);
  std::uint64_t bits = 0;
  std::memcpy(&bits, &a, sizeof bits);
  const int e2 = static_cast<int>(bits >> 52) - 1023;
  // floor(log10(a)) is floor(e2 log10(2)) or one more (Dragonbox's floor_log10_pow2).
  int e10 = (e2 * 315653) >> 20;
  std::uint64_t n = 0;
  if (e2 == -1023 || !detail::scaled(a, kDigits - 1 - e10, n)) return detail::g9_by_fmt(out, v);
  if (n >= 1'000'000'000u) {
    ++e10;
    if (!detail::scaled(a, kDigits - 1 - e10, n)) return detail::g9_by_fmt(out, v);
  }
  if (n == 1'000'000'000u) {  // rounded up to the next power of ten
    n = 100'000'000u;
    ++e10;
  }
  // The nine digits; the fixed-size copies below read up to d[whole + 8], whole <= 9.
  char d[24] = {};
  int len = kDigits;  // without the trailing zeros
  if constexpr (std::endian::native == std::endian::little) {
    d[0] = static_cast<char>('0' + n / 100'000'000);
    const std::uint64_t rest = detail::ascii8(static_cast<std::uint32_t>(n % 100'000'000));
    std::memcpy(d + 1, &rest, 8);
    // Trailing zeros are the highest bytes of rest that hold '0'.
    const std::uint64_t values = rest - 0x3030303030303030u;
    len = values == 0 ? 1 : kDigits - std::countl_zero(values) / 8;
  } else {
    detail::digits_back(d + kDigits, static_cast<std::uint32_t>(n), kDigits);
    while (len > 1 && d[len - 1] == '0') --len;
  }
  if (std::signbit(v)) *out++ = '-';
  if (e10 >= 0 && e10 < kDigits) {
    // The digits, then those after the point moved one on for it (copies of a fixed size).
    const int whole = e10 + 1;
    std::memcpy(out, d, 9);
    std::memcpy(out + whole + 1, d + whole, 8);
    out[whole] = '.';
    return out + (len > whole ? len + 1 : whole);
  }
  if (e10 < 0 && e10 >= -4) {
    std::memcpy(out, "0.0000", 6);
    out += 1 - e10;  // "0." and -e10 - 1 zeros
    std::memcpy(out, d, 9);
    return out + len;
  }
  *out++ = d[0];
  if (len > 1) {
    *out++ = '.';
    std::memcpy(out, d + 1, 8);
    out += len - 1;
  }
  *out++ = 'e';
  *out++ = e10 < 0 ? '-' : '+';
  const int x = e10 < 0 ? -e10 : e10;
  if (x >= 100) *out++ = static_cast<char>('0' + x / 100);
  *out++ = static_cast<char>('0' + x / 10 % 10);
  *out++ = static_cast<char>('0' + x % 10);
  return out;
}

}  // namespace whatnext::numtext
