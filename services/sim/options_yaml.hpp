#pragma once
// The scenario's `sim` section -> the simulator's options. Every key is checked: unknown keys,
// wrong types and impossible values are a ConfigError naming file, line and key.

#include <string>

#include "relplane/common/options.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {

struct ServiceOptions {
  SimOptions sim;
  double start_delay = 0.3;  // seconds to wait before the first publish, so that subscribers
                             // started at the same time are listening
};

// Loads section `sim` of `file`; an empty file name gives the defaults.
ServiceOptions LoadServiceOptions(const std::string& file);
// Reads the section `reader` points at and calls Finish() on it.
ServiceOptions ReadServiceOptions(config::Reader reader);

}  // namespace relplane::sim
