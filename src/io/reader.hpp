// Validation: the limits of the range the model is made for (docs/inputs.md "Limits") and Reader,
// which reads a Config's values with their rules and says which input broke which rule.
#pragma once

#include <array>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>

#include <fmt/format.h>

#include "input_common.hpp"
#include "key_table.hpp"
#include "whatnext/config.hpp"
#include "whatnext/geometry.hpp"

namespace whatnext::io {

constexpr double kMaxSteps = 1e7;    // fixed-step runs longer than this are refused (rk4: about 2 s)
constexpr double kMaxSamples = 1e7;  // output rows

// Where the model is made for (docs/inputs.md "Limits"): a tabletop machine. Far outside, lengths
// fall below the contact tolerance (1e-9 m) or the rounding of the others, energies overflow, and
// the integrator cannot meet its tolerance in any number of steps.
constexpr double kMinLength = 1e-3, kMaxLength = 1e3;    // [m]
constexpr double kMinMass = 1e-3, kMaxMass = 1e3;        // [kg]
constexpr double kMinDensity = 1e-3, kMaxDensity = 1e3;  // [kg/m^3]
constexpr double kMinGravity = 1e-2, kMaxGravity = 1e3;  // [m/s^2]
constexpr double kMaxTime = 1e4;                         // run.t_max [s]
constexpr double kMinTolerance = 1e-15, kMaxTolerance = 1e-3;
constexpr double kMaxBalloonG = 1e3;       // free balloon's acceleration [g]
constexpr double kMaxDrag = 10.0;          // drag coefficient
constexpr double kMaxDamping = 1e3;        // [N m s/rad]
constexpr double kMaxCoulombTorque = 1e3;  // [N m]: a pivot that holds a tonne at a metre
constexpr double kMaxInertia = 1e4;        // seesaw [kg m^2]
constexpr double kMaxForce = 1e4;          // the radio's switch [N]

// --- validation helpers ---------------------------------------------------------------------

class Reader {
 public:
  const Config& cfg;

  // The values given, found by name once: validation reads about 180 keys, per machine of a sweep,
  // by their places in the key table (Key), and a key outside the table is not read.
  explicit Reader(const Config& config) : cfg(config) {
    for (const auto& [name, value] : cfg.values) {
      const std::size_t i = find_key_index(name);
      if (i < kKeyCount) given_[i] = &value;
    }
  }

  const ConfigValue* find(Key key) const { return given_[key.index()]; }
  std::string where(Key key) const {
    const ConfigValue* v = find(key);
    if (!v) return cfg.source;
    // A number set_number set has its origin written here, only for a message.
    if (v->origin.empty() && v->type == ConfigValue::Type::number) {
      return fmt::format("{} = {}", key.name(), shortest(v->number));
    }
    return v->origin;
  }
  [[noreturn]] void fail(Key key, const std::string& rule) const {
    throw InputError(fmt::format("{}: {} {}", where(key), key.name(), rule));
  }
  // The value as the input gave it: an integer too long for a double as written.
  std::string shown(Key key, double x) const {
    const ConfigValue* v = find(key);
    if (v && v->type == ConfigValue::Type::number && !v->text.empty() && v->number == x) return v->text;
    return fmt_num(x);
  }
  static std::string unit(Key key) { return std::string(key.spec().unit); }
  // Without a fallback the key table's default stands for a key not given (key_default: the one
  // place it is written), looked up only then.
  static constexpr double kTable = std::numeric_limits<double>::quiet_NaN();
  static double table_default(Key key) {
    const double x = key_default_at(key.index());
    if (std::isnan(x))
      throw std::logic_error("no numeric default in the key table for " + std::string(key.name()));
    return x;
  }
  double number(Key key) const { return number(key, kTable); }
  double positive(Key key) const { return positive(key, kTable); }
  double length(Key key) const { return length(key, kTable); }
  double mass(Key key) const { return mass(key, kTable); }
  double offset(Key key) const { return offset(key, kTable); }
  double in_range(Key key, double lo, bool lo_closed, double hi, bool hi_closed) const {
    return in_range(key, kTable, lo, lo_closed, hi, hi_closed);
  }
  double number(Key key, double fallback) const {
    const ConfigValue* v = find(key);
    if (!v) return std::isnan(fallback) ? table_default(key) : fallback;
    if (!std::isfinite(v->number)) fail_finite(key, v->number);
    return v->number;
  }
  double positive(Key key, double fallback) const {
    const double x = number(key, fallback);
    if (!(x > 0.0)) fail_positive(key, x);
    return x;
  }
  double in_range(Key key, double fallback, double lo, bool lo_closed, double hi, bool hi_closed) const {
    const double x = number(key, fallback);
    const bool ok = (lo_closed ? x >= lo : x > lo) && (hi_closed ? x <= hi : x < hi);
    if (!ok) fail_range(key, x, lo, lo_closed, hi, hi_closed);
    return x;
  }
  // The plausibility limits: a value the rules accept, outside what the model is made for.
  void plausible(Key key, double x, double lo, double hi) const {
    if (!(x >= lo && x <= hi)) fail_plausible(key, x, lo, hi);
  }
  double length(Key key, double fallback) const {
    const double x = positive(key, fallback);
    plausible(key, x, kMinLength, kMaxLength);
    return x;
  }
  double mass(Key key, double fallback) const {
    const double x = positive(key, fallback);
    plausible(key, x, kMinMass, kMaxMass);
    return x;
  }
  // A signed distance (an offset or a start position) within the machine's reach.
  double offset(Key key, double fallback) const {
    const double x = number(key, fallback);
    plausible(key, x, -kMaxLength, kMaxLength);
    return x;
  }
  Vec2 pair(Key key) const {
    const ConfigValue& v = *find(key);
    // As the input wrote it (v.text: numbers a double rounds), for the messages.
    const auto given = [&v] {
      return v.text.empty() ? fmt::format("[{}, {}]", fmt_num(v.pair[0]), fmt_num(v.pair[1])) : v.text;
    };
    if (!std::isfinite(v.pair[0]) || !std::isfinite(v.pair[1])) {
      fail(key, fmt::format("must hold finite numbers (given {})", given()));
    }
    if (std::fabs(v.pair[0]) > kMaxLength || std::fabs(v.pair[1]) > kMaxLength) {
      fail(key, fmt::format("must hold numbers within [{}, {}] m, the range the model is made for (given {})",
                            fmt_num(-kMaxLength), fmt_num(kMaxLength), given()));
    }
    return {v.pair[0], v.pair[1]};
  }
  // A text key: as given, else the key table's default.
  std::string text(Key key) const {
    const ConfigValue* v = find(key);
    return v ? v->text : std::string(key.spec().default_text);
  }

 private:
  std::array<const ConfigValue*, kKeyCount> given_{};

  // The messages of the rules above, out of line and cold: a sweep reads every key of every
  // machine, and the reads are inlined where they are short.
  [[noreturn, gnu::cold, gnu::noinline]] void fail_finite(Key key, double x) const {
    fail(key, fmt::format("must be a finite number (given {})", shown(key, x)));
  }
  [[noreturn, gnu::cold, gnu::noinline]] void fail_positive(Key key, double x) const {
    const std::string u = unit(key);
    fail(key, fmt::format("must be > 0{} (given {})", u.empty() ? "" : " " + u, shown(key, x)));
  }
  [[noreturn, gnu::cold, gnu::noinline]] void fail_range(Key key, double x, double lo, bool lo_closed,
                                                         double hi, bool hi_closed) const {
    const std::string u = unit(key);
    fail(key, fmt::format("must be in {}{}, {}{}{} (given {})", lo_closed ? "[" : "(", fmt_num(lo),
                          fmt_num(hi), hi_closed ? "]" : ")", u.empty() ? "" : " " + u, shown(key, x)));
  }
  [[noreturn, gnu::cold, gnu::noinline]] void fail_plausible(Key key, double x, double lo, double hi) const {
    const std::string u = unit(key);
    fail(key, fmt::format("must be within [{}, {}]{}, the range the model is made for (given {})",
                          fmt_num(lo), fmt_num(hi), u.empty() ? "" : " " + u, shown(key, x)));
  }
};

// The switches beyond the paper (build_extensions.cpp).
void build_extensions(const Reader& in, Machine& m);
// Start conditions that only the extensions can violate (build_extensions.cpp).
void check_extension_start(const Reader& in, const Scenario& sc);

}  // namespace whatnext::io
