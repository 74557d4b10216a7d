// What a sweep varies, as the user writes it: `--vary KEY=A:B:N` (a grid's or a Latin hypercube's
// range) and `--spread KEY=±X` (a Monte Carlo's spread around the machine's own value).
#pragma once

#include <string>
#include <string_view>

#include "whatnext/config.hpp"

namespace whatnext::explore {

// One varied key: values lo..hi, n of them on a grid (n = 0 where no count is needed).
struct Range {
  std::string key;
  double lo = 0.0, hi = 0.0;
  int n = 0;
};

// Parses "KEY=A:B:N" (need_count) or "KEY=A:B" (count optional) as given to the option named by
// option ("--vary"). Checks the key against the input keys (with a suggestion), A <= B, N >= 1.
// Throws InputError with one line naming the option, the rule and the value.
Range parse_range(std::string_view spec, std::string_view option, bool need_count);

// Monte Carlo over building tolerances (docs/explore.md, "Would the built machine work?"):
// each machine is the base machine with every spread key off by a random amount.
enum class SpreadKind { normal, uniform };
struct Spread {
  std::string key;
  double x = 0.0;  // normal: standard deviation; uniform: half-width (in the key's input unit)
};
// Parses "KEY=±X" (or KEY=+-X) as given to option ("--spread"): a numeric input key and X > 0.
// Throws InputError with one line naming the option, the rule and the value.
Spread parse_spread(std::string_view spec, std::string_view option);
// Throws InputError naming option unless kind is "normal" or "uniform".
SpreadKind parse_spread_kind(std::string_view kind, std::string_view option);
// The value a machine gives a numeric key (in its input unit): its own, or the documented default.
// Throws InputError naming option when the default is not a number (it follows from other keys).
double base_value(const Config& config, const std::string& key, std::string_view option);
// Throws InputError beginning with `where` unless key is an input key holding one number (text,
// pairs and flags cannot be varied); an unknown key's message suggests the nearest one.
void check_numeric_key(const std::string& key, std::string_view where);

}  // namespace whatnext::explore
