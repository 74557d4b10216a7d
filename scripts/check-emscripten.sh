#!/usr/bin/env bash
# Checks that the physics core (every file of src/core/) builds with Debian's
# Emscripten 3.1.6 (libc++ 13) for the coming browser version, and that example 1 runs the same
# under Node. Not part of the tests: it needs `apt-get install emscripten` (large), run as root.
set -euo pipefail
here="$(cd "$(dirname "$0")/.." && pwd)"
work="$(mktemp -d)"
trap 'rm -rf "$work"' EXIT
command -v em++ >/dev/null || { echo "check-emscripten: em++ not found (apt-get install emscripten)" >&2; exit 2; }
# Boost is header-only here; give em++ the headers without the host's C library.
mkdir -p "$work/inc" && ln -s /usr/include/boost "$work/inc/boost"
cat > "$work/main.cpp" <<'CPP'
#include <cstdio>
#include <string>
#include "whatnext/simulate.hpp"
int main() {  // example 1 is the keys' defaults, which a Scenario{} holds: no TOML layer in the core
  whatnext::Scenario sc;
  sc.run.t_max = 2.0;
  const whatnext::Result r = whatnext::simulate(sc);
  std::printf("%s at %.6f s\n", std::string(whatnext::to_string(r.outcome().type)).c_str(), r.outcome().t);
}
CPP
export NODE_PATH="${NODE_PATH:-/usr/share/nodejs}"  # Debian ships the JS optimizer's acorn there
em++ -std=c++20 -O2 -sSINGLE_FILE=1 -I"$here/include" -I"$here/src" -I"$work/inc" \
  "$work/main.cpp" "$here"/src/core/*.cpp -o "$work/core.js"
node "$work/core.js"
