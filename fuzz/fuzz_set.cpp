// libFuzzer harness: any bytes as the text of --set on top of example 1 (or of several --set,
// one per line, as a shell would pass them one by one).
#include <algorithm>
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace whatnext;
  std::string_view text(reinterpret_cast<const char*>(data), size);
  Config cfg = example_config(1);
  try {
    // The first line as one argument (newlines inside must be refused), the rest line by line.
    apply_set(cfg, text);
    fuzz::check_round_trip(build_scenario(cfg));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  cfg = example_config(1);
  try {
    while (!text.empty()) {
      const std::size_t end = std::min(text.find('\n'), text.size());
      apply_set(cfg, text.substr(0, end));
      text.remove_prefix(std::min(end + 1, text.size()));
    }
    fuzz::check_round_trip(build_scenario(cfg));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
