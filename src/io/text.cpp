// User text in one-line messages (printable), numbers as the shortest text that reads back, and how
// a run is named.
#include <string>
#include <vector>

#include <fmt/format.h>

#include "whatnext/config.hpp"

namespace whatnext {

std::string printable(std::string_view text, std::size_t max_chars) {
  // Split into characters as shown: an escape or one whole UTF-8 character each.
  std::vector<std::string> chars;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    std::size_t n = 0;  // length of a valid, printable UTF-8 sequence at i
    if (c >= 0x20 && c < 0x7f) {
      n = 1;
    } else if (c >= 0xc2 && c <= 0xf4) {
      const std::size_t want = c < 0xe0 ? 2 : c < 0xf0 ? 3 : 4;
      n = want;
      for (std::size_t k = 1; k < want; ++k) {
        if (i + k >= text.size() || (static_cast<unsigned char>(text[i + k]) & 0xc0) != 0x80) n = 0;
      }
      if (n == 2 && static_cast<unsigned char>(text[i + 1]) < 0xa0 && c == 0xc2) n = 0;  // C1 controls
      if (n == 3 && c == 0xe0 && static_cast<unsigned char>(text[i + 1]) < 0xa0) n = 0;  // overlong
      if (n == 4 && c == 0xf0 && static_cast<unsigned char>(text[i + 1]) < 0x90) n = 0;  // overlong
    }
    if (n > 0) {
      chars.emplace_back(text.substr(i, n));
      i += n;
      continue;
    }
    chars.push_back(c == '\n' ? "\\n" : c == '\t' ? "\\t" : c == '\r' ? "\\r" : fmt::format("\\x{:02x}", c));
    ++i;
  }
  std::string out;
  if (chars.size() <= max_chars || max_chars < 8) {
    for (const std::string& ch : chars) out += ch;
    return out;
  }
  const std::size_t head = (max_chars - 3) * 2 / 3, tail = max_chars - 3 - head;
  for (std::size_t i = 0; i < head; ++i) out += chars[i];
  out += "...";
  for (std::size_t i = chars.size() - tail; i < chars.size(); ++i) out += chars[i];
  return out;
}

std::string shortest(double value) { return fmt::format("{}", value); }

std::string input_label(std::string machine, const std::vector<std::string>& sets) {
  if (sets.empty()) return machine;
  std::string joined;
  for (const std::string& s : sets) {
    if (!joined.empty()) joined += ", ";
    joined += s;
  }
  return machine + " with --set " + printable(joined, 120);
}

}  // namespace whatnext
