#include "whatnext/columns.hpp"

#include <iterator>

namespace whatnext {

StateColumns state_columns() { return {kStateColumns, std::size(kStateColumns)}; }

}  // namespace whatnext
