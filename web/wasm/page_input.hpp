// What both of the page's WebAssembly modules (bindings.cpp, map.cpp) share: the machine as the
// page sends it, read as the command line reads a file and its --set options, and a call whose bad
// input or failed run comes back to the page as {ok: false, kind, message}.
#pragma once

#include <emscripten/bind.h>
#include <emscripten/val.h>

#include <exception>
#include <string>
#include <vector>

#include "whatnext/config.hpp"
#include "whatnext/simulate.hpp"

namespace whatnext::web {

// {toml, source, format, sets: ["key=value", ...]}: `toml` is the machine's text (the paper's
// whatnext.inp when format is "inp"), `source` names it in messages as a file name does.
inline Config config_of(const emscripten::val& in) {
  const std::string text = in["toml"].as<std::string>(), source = in["source"].as<std::string>();
  const bool inp = in["format"].isString() && in["format"].as<std::string>() == "inp";
  Config config = inp ? parse_inp(text, source) : parse_toml(text, source);
  for (const std::string& s : emscripten::vecFromJSArray<std::string>(in["sets"])) apply_set(config, s);
  return config;
}

inline emscripten::val failure(const char* kind, const char* message) {
  emscripten::val r = emscripten::val::object();
  r.set("ok", false);
  r.set("kind", std::string(kind));
  r.set("message", std::string(message));
  return r;
}

// Runs fn(); a bad input or a failed run becomes {ok: false, kind, message}.
template <class Fn>
emscripten::val guarded(Fn&& fn) {
  try {
    return fn();
  } catch (const InputError& e) {
    return failure("input", e.what());
  } catch (const SimulationError& e) {
    return failure("simulation", e.what());
  } catch (const std::exception& e) {
    return failure("error", e.what());
  }
}

}  // namespace whatnext::web
