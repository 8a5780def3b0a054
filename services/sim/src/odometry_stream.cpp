#include "relplane/sim/odometry_stream.hpp"

#include <cmath>

namespace relplane::sim {

OdometryStream::OdometryStream(const OdometryOptions& options, const Simulation& simulation)
    : options_(options),
      simulation_(simulation),
      odometry_(options, simulation.PlanarPose(0)),
      rate_hz_(options.rate_hz > 0.0 ? options.rate_hz : simulation.Options().rate_hz) {}

std::vector<TimedOdometry> OdometryStream::UpTo(int64_t k) {
  std::vector<TimedOdometry> due;
  if (!options_.enabled || !(rate_hz_ > 0.0)) return due;
  const double t_k = static_cast<double>(k) / simulation_.Options().rate_hz;
  // A reading at the cloud's own time goes with it, whatever the rounding of the two times.
  for (double t; (t = static_cast<double>(next_) / rate_hz_) <= t_k + 1e-9; ++next_) {
    due.push_back({odometry_.Step(simulation_.PlanarPoseAt(t)), std::llround(t * 1e6)});
  }
  return due;
}

}  // namespace relplane::sim
