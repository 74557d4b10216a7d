// libFuzzer harness: any bytes as the paper's whatnext.inp.
#include <cstddef>
#include <cstdint>
#include <string_view>

#include "fuzz_common.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  using namespace whatnext;
  const std::string_view text(reinterpret_cast<const char*>(data), size);
  try {
    fuzz::check_round_trip(build_scenario(parse_inp(text, "fuzz.inp")));
  } catch (const InputError& e) {
    fuzz::check_message(e);
  }
  return 0;
}
