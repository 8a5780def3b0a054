#pragma once
// §II.D current position from the present untransformed observations against the global map,
// and §II.E the motion model when only one partial plane is in view.

#include <algorithm>
#include <cmath>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/state.hpp"

namespace relplane::mapper {

enum class PoseStatus { kTracking, kMotionModel, kInitializing, kLost };

struct PoseEstimate {
  geometry::Pose2 pose;
  PoseStatus status = PoseStatus::kLost;
  int planes = 0;  // planes used
};

// One observation of a mapped wall: what is seen now and where the map has it.
struct Sighting {
  const Observation* obs = nullptr;
  const RltPlane* plane = nullptr;
  Placement world;
};

// The sensor's horizontal field of view as learned from the edges it reports: the widest
// bearing seen. An edge at that bearing is cut by the view, not a wall's end. (Range is not
// learned: in a small world no wall reaches it and a far wall end would pass for the limit.)
class LearnedFrustum {
 public:
  void Observe(const Eigen::Vector2d& edge) {
    max_bearing_ = std::max(max_bearing_, std::abs(std::atan2(edge.y(), edge.x())));
  }
  bool Clipped(const Eigen::Vector2d& edge) const {
    return std::abs(std::atan2(edge.y(), edge.x())) > max_bearing_ - kBearingMargin;
  }

 private:
  static constexpr double kBearingMargin = 0.035;  // rad (2 degrees)
  double max_bearing_ = 0.0;
};

// Solves the sensor pose: yaw from the mean orientation difference, position by least squares
// over the walls' lines (one equation each) and their static edges seen now (one more each, along
// the wall), with `previous` as a weak prior. With a single wall, or walls that leave the position
// underdetermined, the result is the motion model (§II.E): the wall stays where the map has it,
// the unobserved direction keeps its previous value, and a mapped wall end seen at its predicted
// place pins the position along the wall.
PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LearnedFrustum& frustum, const LocalisationOptions& options);

}  // namespace relplane::mapper
