#pragma once
// §II.D current position from the present untransformed observations against the global map,
// and §II.E the motion model when only one partial plane is in view.

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

// Solves the sensor pose: yaw from the mean orientation difference, position by least squares
// over the walls' lines (one equation each) and their static edges seen now (one more each, along
// the wall), with `previous` as a weak prior. With a single wall, or walls that leave the position
// underdetermined, the result is the motion model (§II.E): the wall stays where the map has it,
// the unobserved direction keeps its previous value, and a mapped wall end seen at its predicted
// place pins the position along the wall.
PoseEstimate Localise(const std::vector<Sighting>& sightings, const geometry::Pose2& previous,
                      const LocalisationOptions& options);

}  // namespace relplane::mapper
