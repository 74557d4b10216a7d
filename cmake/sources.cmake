# The library's sources, listed once for the native build (CMakeLists.txt) and the WebAssembly
# build (web/wasm/CMakeLists.txt), relative to the source root.
# The physics core: no I/O, compiles with Emscripten too.
set(WHATNEXT_CORE_SOURCES
  src/core/contact.cpp
  src/core/geometry.cpp
  src/core/model.cpp
  src/core/kinematics.cpp
  src/core/dynamics.cpp
  src/core/contact_problem.cpp
  src/core/guards.cpp
  src/core/contact_decision.cpp
  src/core/impact_laws.cpp
  src/core/jumps.cpp
  src/core/ledger.cpp
  src/core/columns.cpp
  src/core/names.cpp
  src/core/simulate.cpp)
# Inputs and file outputs.
set(WHATNEXT_IO_SOURCES
  src/config.cpp
  src/output.cpp)
