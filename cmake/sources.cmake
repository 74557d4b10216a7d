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
  src/core/balloon.cpp
  src/core/ledger.cpp
  src/core/stretchy_rope.cpp
  src/core/columns.cpp
  src/core/names.cpp
  src/core/simulate.cpp)
# Inputs and file outputs (src/io/): reading, parsing and validating machines, writing them back,
# and the output files.
set(WHATNEXT_IO_SOURCES
  src/io/keys.cpp
  src/io/text.cpp
  src/io/read_file.cpp
  src/io/toml_input.cpp
  src/io/inp_input.cpp
  src/io/set_input.cpp
  src/io/examples.cpp
  src/io/build_scenario.cpp
  src/io/build_extensions.cpp
  src/io/write_toml.cpp
  src/io/interrupts.cpp
  src/io/atomic_file.cpp
  src/io/timeline.cpp
  src/io/events_json.cpp
  src/io/csv.cpp
  src/io/dat.cpp)
