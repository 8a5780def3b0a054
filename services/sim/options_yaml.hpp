#pragma once
// The scenario's `sim` section -> the simulator's options. Every key is checked: unknown keys,
// wrong types and impossible values are a ConfigError naming file, line and key.

#include <cstdint>
#include <string>

#include "relplane/common/options.hpp"
#include "relplane/sim/odometry.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {

struct ServiceOptions {
  SimOptions sim;
  double start_delay = 0.3;  // seconds to wait before the first publish, so that subscribers
                             // started at the same time are listening
  // Fraction of SENSOR_POINTS frames not published, to test frame loss (issue 8). Which frames
  // is fixed by sensor.seed and the frame's seq, so a run is repeatable; seq keeps counting so
  // that downstream sees the gaps. SIM_TRUTH is published for every frame: the truth does not
  // depend on the transport, and the logger matches POSE to truth by seq.
  double drop_fraction = 0.0;
  // Wheel odometry on ODOMETRY (sim.odometry), off unless enabled.
  OdometryOptions odometry;
};

// True when frame `seq` is one of the `fraction` of frames dropped for `seed`: a hash of seed
// and seq, so the choice is independent of timing and of any other random stream.
bool DropFrame(uint64_t seed, int64_t seq, double fraction);

// Loads section `sim` of `file`; an empty file name gives the defaults.
ServiceOptions LoadServiceOptions(const std::string& file);
// Reads the section `reader` points at and calls Finish() on it.
ServiceOptions ReadServiceOptions(config::Reader reader);

}  // namespace relplane::sim
