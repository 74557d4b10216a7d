// The paper's examples 1 to 4, embedded at build time (cmake/embed_examples.cmake).
#include <fmt/format.h>

#include "whatnext/config.hpp"

namespace whatnext {

Config example_config(int n) {
  if (n < 1 || n > 4) {
    throw InputError(fmt::format("--example: the paper has examples 1 to 4 (given '{}')", n));
  }
  return parse_toml(example_toml(n), fmt::format("example{}.toml", n));
}

}  // namespace whatnext
