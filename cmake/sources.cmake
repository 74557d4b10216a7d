# The library's sources, listed once for the native build (CMakeLists.txt) and the WebAssembly
# build (web/wasm/CMakeLists.txt), relative to the source root.
# The physics core: no I/O, compiles with Emscripten too.
set(WHATNEXT_CORE_SOURCES
  src/contact.cpp
  src/geometry.cpp
  src/model.cpp
  src/names.cpp
  src/simulate.cpp)
# Inputs and file outputs.
set(WHATNEXT_IO_SOURCES
  src/config.cpp
  src/output.cpp)
