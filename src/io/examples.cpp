// The paper's examples 1 to 4 and the named presets, embedded at build time (cmake/embed_examples.cmake).
#include <fmt/format.h>

#include "whatnext/config.hpp"

namespace whatnext {

Config example_config(int n) {
  if (n < 1 || n > 4) {
    throw InputError(fmt::format("--example: the paper has examples 1 to 4 (given '{}')", n));
  }
  return parse_toml(example_toml(n), fmt::format("example{}.toml", n));
}

Config example_config(std::string_view name) {
  const std::string_view text = example_toml(name);
  if (text.empty()) {
    throw InputError(
        fmt::format("--example: the examples are 1 to 4 (the paper's) and konstanz (given '{}')", name));
  }
  return parse_toml(text, fmt::format("{}.toml", name));
}

}  // namespace whatnext
