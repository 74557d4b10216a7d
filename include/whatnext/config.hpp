// The input layer: TOML files, the paper's whatnext.inp, --set overrides and the shipped examples,
// all turned into a validated Scenario. Degrees live here and nowhere deeper.
#pragma once

#include <cstddef>
#include <map>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "whatnext/params.hpp"

namespace whatnext {

// Bad input: the message is one line naming the input, the rule and the value given.
class InputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

enum class KeyKind { length, mass, density, angle, time, acceleration, positive, text, pair, flag };

struct KeySpec {
  std::string_view key;
  KeyKind kind;
  std::string_view unit;  // as written in inputs
  std::string_view help;
  std::string_view default_text;  // the default as documented ("0.6", "r_L", "off")
};
// Every key an input may set, in documentation order.
const std::vector<KeySpec>& known_keys();
const KeySpec* find_key(std::string_view key);
// The key's default as a number: the table's default_text read as one. The one place a key's
// default is written (validation falls back on it, sweeps spread around it); NaN where the default
// is not a number ("r_L", "bar", "endless") or the key is unknown.
double key_default(std::string_view key);
// A pair key's default ("[0.5, 0]"), NaN where it has none.
Vec2 key_default_pair(std::string_view key);

// A value as written (before unit conversion) and where it came from, for error messages.
struct ConfigValue {
  enum class Type { number, text, pair } type = Type::number;
  double number = 0.0;
  std::string text;
  double pair[2] = {0.0, 0.0};
  // "example1.toml:12", "--set", "whatnext.inp line 3"; empty for a number set_number set (per
  // machine of a sweep), which messages name "KEY = VALUE".
  std::string origin;
};

class Config {
 public:
  std::string source;                                      // shown in messages
  std::map<std::string, ConfigValue, std::less<>> values;  // found by string_view too
  bool has(std::string_view key) const { return values.count(key) != 0; }
};

// Reads a TOML file or the paper's 15-line .inp file (chosen by content: an .inp starts with a
// number). Only regular files (or pipes) of at most kMaxInputBytes are read. Throws InputError.
Config load_config_file(const std::string& path);
constexpr std::size_t kMaxInputBytes = 1 << 20;
Config parse_toml(std::string_view text, const std::string& source);
Config parse_inp(std::string_view text, const std::string& source);
// The paper's example n (1..4), as shipped in examples/exampleN.toml.
Config example_config(int n);
std::string_view example_toml(int n);
// The named presets beyond the paper's four: "konstanz" (examples/konstanz.toml, the machine the
// students built, the paper's Fig. 3/4). example_toml(name) is empty for any other name.
constexpr std::string_view kNamedExamples[] = {"konstanz"};
Config example_config(std::string_view name);
std::string_view example_toml(std::string_view name);
// Applies "KEY=VALUE" (VALUE as in TOML; bare words are text). Throws InputError.
void apply_set(Config& config, std::string_view assignment);
// Sets a numeric key directly (no parsing; for sweeps and optimisation). Throws InputError for an
// unknown or non-numeric key.
void set_number(Config& config, const std::string& key, double value);
// Validates everything and converts to SI and radians. Throws InputError.
Scenario build_scenario(const Config& config);
// Writes a scenario back as TOML that build_scenario accepts (round trip up to rounding; angles
// in the fewest digits that give the same radians). The hinge is written as hinge_offset, or, if
// `given` is the config the scenario was built from and gives the hinge as distance and angle (or
// not at all), in that form with its values.
std::string to_toml(const Scenario& scenario, const Config* given = nullptr);

// Closest known key to a misspelt one ("" if nothing is close).
std::string nearest_key(std::string_view key);
// Closest of `choices` to a misspelt word ("" if nothing is close).
std::string nearest_word(std::string_view word, const std::vector<std::string>& choices);

// Text from the user as it may appear in a one-line message: control bytes and invalid UTF-8
// escaped (\n, \t, \x1b), and cut in the middle ("abc...xyz") beyond max_chars characters.
std::string printable(std::string_view text, std::size_t max_chars = 64);
// How a run is named in titles, the timeline and the events JSON: the machine ("example 4", a
// file), then " with --set K=V, K=V" for the overrides given (printable, cut when long).
std::string input_label(std::string machine, const std::vector<std::string>& sets);

// The shortest decimal text that reads back as the same double ("0.6", not 0.59999999999999998).
std::string shortest(double value);

}  // namespace whatnext
