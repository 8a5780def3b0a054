#pragma once
// Wheel odometry's readings at their own rate, each due once the simulated time reaches it:
// what relplane-sim publishes on ODOMETRY before each cloud, and what the accuracy sweep hands
// the mapper in-process, so both see the same readings at the same times.

#include <cstdint>
#include <vector>

#include "relplane/sim/odometry.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::sim {

struct TimedOdometry {
  OdometryReading reading;
  int64_t utime = 0;  // simulated time of the reading, microseconds
};

class OdometryStream {
 public:
  // `simulation` must outlive the stream. Readings come at options.rate_hz, or at the sensor's
  // rate when that is 0; none when options.enabled is false.
  OdometryStream(const OdometryOptions& options, const Simulation& simulation);

  // The readings due at or before iteration k's capture time and not yet taken, in time order.
  std::vector<TimedOdometry> UpTo(int64_t k);

 private:
  OdometryOptions options_;
  const Simulation& simulation_;
  WheelOdometry odometry_;
  double rate_hz_;
  int64_t next_ = 0;  // index of the next reading
};

}  // namespace relplane::sim
