#pragma once
// The Relative Plane mapper (the paper, §II): one call per iteration with the untransformed
// planes of that iteration; reads as register -> group -> compare -> build maps -> localise.

#include <cstdint>
#include <memory>
#include <optional>
#include <vector>

#include "relplane/mapper/odometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

struct MapperState;  // what the steps own, part by part (services/mapper/src/state.hpp)

class Mapper {
 public:
  explicit Mapper(MapperOptions options = {});
  ~Mapper();
  Mapper(Mapper&&) noexcept;
  Mapper& operator=(Mapper&&) noexcept;

  // Processes one plane set; `iteration` must increase (gaps are fine). Returns the pose.
  // `odometry`: wheel odometry's motion since the previous plane set, when the robot has it
  // (ODOMETRY, odometry.hpp). It predicts the pose in place of the velocity learnt from the
  // walls (§II.E), so it decides only what the walls in view leave open; without it the pose is
  // the planes' alone.
  PoseEstimate Process(int64_t iteration, const std::vector<PlaneInput>& planes,
                       const std::optional<OdometryIncrement>& odometry = std::nullopt);

  // True when the map changed since the last call to TakeMapChanged().
  bool TakeMapChanged();
  MapSnapshot Map() const;
  MapperStats Stats() const;
  const MapperOptions& Options() const { return options_; }
  // Sensor height added to planes' z (the start pose's z).
  double Height() const { return options_.start_pose.z; }
  // For the mapper's own tests (src/state.hpp).
  const MapperState& State() const;

 private:
  struct Steps;
  MapperOptions options_;
  std::unique_ptr<Steps> steps_;
};

}  // namespace relplane::mapper
