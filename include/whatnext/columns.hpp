// The state's columns: one table of what a sample reports, with its name, unit and meaning, and
// how it follows from a Snapshot. The CSV's header and rows, the Python module's sample arrays
// and the page's columns are all made from it, so that a column is defined exactly once.
#pragma once

#include <cstddef>
#include <string_view>

#include "whatnext/state.hpp"

namespace whatnext {

struct StateColumn {
  std::string_view name;     // as in the CSV header and Python: quantity, then unit (phi_l_deg)
  std::string_view unit;     // "m", "deg/s", "J", ...; empty for pure numbers
  std::string_view meaning;  // one line for docs and tooltips
  double (*value)(const Snapshot&);  // in that unit (angles in degrees)
};

// The numeric columns of a sample in the CSV's order. They follow the CSV's four leading columns
// t_s, event, mode and rope_taut (text and flags, kLeadingColumns).
struct StateColumns {
  const StateColumn* data;
  std::size_t count;
  const StateColumn* begin() const { return data; }
  const StateColumn* end() const { return data + count; }
  std::size_t size() const { return count; }
  const StateColumn& operator[](std::size_t i) const { return data[i]; }
};
StateColumns state_columns();

constexpr std::string_view kLeadingColumns[] = {"t_s", "event", "mode", "rope_taut"};

}  // namespace whatnext
