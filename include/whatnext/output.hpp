// Everything about writing a run's results, in one include: errors.hpp (OutputError),
// atomic_file.hpp (files that appear whole), interrupts.hpp (what an interrupt cleans up) and
// writers.hpp (the timeline, events JSON, CSV and .dat writers). Include the one you need.
#pragma once

#include "whatnext/atomic_file.hpp"
#include "whatnext/errors.hpp"
#include "whatnext/interrupts.hpp"
#include "whatnext/writers.hpp"
