// What the input files of src/io/ share: the unit conversion of angles, how numbers are shown in
// messages, and storing a TOML value under a key (TOML files and --set both do).
#pragma once

#include <string>
#include <string_view>

#include <fmt/format.h>

#define TOML_EXCEPTIONS 1
#include <toml++/toml.h>

#include "whatnext/config.hpp"
#include "whatnext/units.hpp"

namespace whatnext::io {

inline std::string fmt_num(double v) { return fmt::format("{}", v); }

// InputError "WHERE: unknown key 'KEY'", with the nearest known key when one is close (keys.cpp).
[[noreturn]] void unknown_key(const std::string& where, std::string_view key);

// Stores one TOML node under key, checking its type against the key's kind; `source` is the text the
// node was parsed from (for numbers as written in messages). toml_input.cpp.
void store(Config& cfg, const std::string& key, const toml::node& node, const std::string& origin,
           std::string_view source = {});

}  // namespace whatnext::io
