# Writes radio_example.cpp holding examples/example1-radio.toml as a string literal.
file(READ ${SRC} text)
set(body "// Generated from examples/example1-radio.toml by web/wasm/embed_radio.cmake; do not edit.\n")
string(APPEND body "#include <string_view>\n\nnamespace whatnext::web {\n\n")
string(APPEND body "std::string_view radio_example_toml() {\n  return R\"WNEX(${text})WNEX\";\n}\n\n")
string(APPEND body "}  // namespace whatnext::web\n")
file(WRITE ${OUT}.tmp "${body}")
file(RENAME ${OUT}.tmp ${OUT})
