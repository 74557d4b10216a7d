// The error of an output that failed once the work was done. (Bad input is InputError,
// config.hpp; a run that failed is SimulationError, simulate.hpp.)
#pragma once

#include <stdexcept>

namespace whatnext {

// An output that could not be written once the work was done (disk full, /dev/full, a failing
// pipe). Bad output paths are found before any work and are InputErrors.
class OutputError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

}  // namespace whatnext
