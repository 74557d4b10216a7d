// The input keys: the table of every key with its unit, default and meaning (docs/inputs.md), and
// the suggestions for a misspelt key or word.
#include <algorithm>
#include <array>
#include <cmath>
#include <cstdlib>
#include <iterator>
#include <limits>
#include <string>
#include <unordered_map>
#include <vector>

#include "input_common.hpp"
#include "key_table.hpp"

namespace whatnext {

using io::kKeyCount;
using io::kKeys;

namespace {

std::size_t edit_distance(std::string_view a, std::string_view b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diag = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t up = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diag + (a[i - 1] == b[j - 1] ? 0u : 1u)});
      diag = up;
    }
  }
  return row[b.size()];
}

}  // namespace

namespace io {
[[noreturn]] void unknown_key(const std::string& where, std::string_view key) {
  const std::string near = nearest_key(key);
  if (near.empty() || near == key)
    throw InputError(fmt::format("{}: unknown key '{}'", where, printable(key)));
  throw InputError(fmt::format("{}: unknown key '{}' (did you mean '{}'?)", where, printable(key), near));
}
}  // namespace io

const std::vector<KeySpec>& known_keys() {
  static const std::vector<KeySpec> keys(std::begin(kKeys), std::end(kKeys));
  return keys;
}

namespace io {
double key_default_at(std::size_t index) {
  // Read once: validation asks for the defaults of every key a machine leaves out, per machine of
  // a sweep.
  static const std::array<double, kKeyCount> table = [] {
    std::array<double, kKeyCount> t;
    for (std::size_t i = 0; i < kKeyCount; ++i) {
      const std::string text(kKeys[i].default_text);
      char* end = nullptr;
      const double v = std::strtod(text.c_str(), &end);
      const bool number = !text.empty() && end == text.c_str() + text.size() && std::isfinite(v);
      t[i] = number ? v : std::numeric_limits<double>::quiet_NaN();
    }
    return t;
  }();
  return index < kKeyCount ? table[index] : std::numeric_limits<double>::quiet_NaN();
}

namespace {
// Validation finds the place of every key a machine gives, per machine of a sweep: hashed by its
// length and three bytes (which tell the table's keys apart; std::hash reads all of them) into a
// table of places a few times the keys', searched from there on (open addressing).
std::size_t key_hash(std::string_view key) {
  if (key.size() < 3) return key.size();
  const auto byte = [&key](std::size_t i) { return static_cast<unsigned char>(key[i]) + std::size_t{0}; };
  return key.size() * 97 + byte(0) * 31 + byte(key.size() - 3) * 7 + byte(key.size() - 1);
}
constexpr std::size_t kSlots = 256;  // four times the keys and more: few share a slot
static_assert(kSlots >= 4 * kKeyCount && kKeyCount < 255, "the key table outgrew its hash table");
}  // namespace

std::size_t find_key_index(std::string_view key) {
  static const std::array<unsigned char, kSlots> places = [] {
    std::array<unsigned char, kSlots> t;
    t.fill(static_cast<unsigned char>(kKeyCount));  // an empty slot
    for (std::size_t i = 0; i < kKeyCount; ++i) {
      std::size_t s = key_hash(kKeys[i].key) % kSlots;
      while (t[s] != kKeyCount) s = (s + 1) % kSlots;
      t[s] = static_cast<unsigned char>(i);
    }
    return t;
  }();
  for (std::size_t s = key_hash(key) % kSlots;; s = (s + 1) % kSlots) {
    const std::size_t i = places[s];
    if (i == kKeyCount || kKeys[i].key == key) return i;
  }
}
}  // namespace io

double key_default(std::string_view key) { return io::key_default_at(io::find_key_index(key)); }

Vec2 key_default_pair(std::string_view key) {
  // Read once, as --set reads a pair ("[0.5, 0]"; a word such as "none" is the key left out):
  // validation asks for it per machine of a sweep.
  static const std::unordered_map<std::string_view, Vec2> table = [] {
    std::unordered_map<std::string_view, Vec2> t;
    for (const KeySpec& k : kKeys) {
      if (k.kind != KeyKind::pair) continue;
      Config c;
      apply_set(c, std::string(k.key) + "=" + std::string(k.default_text));
      const auto it = c.values.find(k.key);
      if (it != c.values.end()) t.emplace(k.key, Vec2{it->second.pair[0], it->second.pair[1]});
    }
    return t;
  }();
  const auto it = table.find(key);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  return it == table.end() ? Vec2{nan, nan} : it->second;
}

const KeySpec* find_key(std::string_view key) {
  const std::size_t i = io::find_key_index(key);
  return i < kKeyCount ? &kKeys[i] : nullptr;
}

std::string nearest_key(std::string_view key) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const KeySpec& k : kKeys) {
    // Compare both the full key and its last part, so "rope_lenght" finds geometry.rope_length.
    const std::string_view tail = k.key.substr(k.key.find('.') + 1);
    const std::size_t d = std::min(edit_distance(key, k.key), edit_distance(key, tail));
    if (d < best_d) best_d = d, best = std::string(k.key);
  }
  return best_d <= std::max<std::size_t>(3, key.size() / 3) ? best : std::string();
}

std::string nearest_word(std::string_view word, const std::vector<std::string>& choices) {
  std::string best;
  std::size_t best_d = std::string::npos;
  for (const std::string& c : choices) {
    const std::size_t d = edit_distance(word, c);
    if (d < best_d) best_d = d, best = c;
  }
  return best_d <= std::max<std::size_t>(2, word.size() / 3) ? best : std::string();
}

}  // namespace whatnext
