#pragma once
// Each segmented wall against the true wall it lies on, frame by frame: how far the fitted plane
// is off at its centroid and at the foot of the perpendicular from the sensor to the wall. A
// fit can pass through its points' centroid and still be turned (a short face takes a few of a
// neighbour's points at a crease): the mapper measures across the hallway from such a face, and
// the foot shows what that lever makes of the turn.

#include <Eigen/Geometry>
#include <cstdint>
#include <string>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::accuracy {

struct PlaneError {
  int64_t seq = 0;
  int true_id = 0;             // the true wall (sim::TruePlane::id)
  double true_length_m = 0.0;  // its horizontal length
  double range_m = 0.0;        // sensor to the detection's centroid, seen from above
  int points = 0;
  // Signed distances of the fitted plane from the true one, positive towards the sensor: at the
  // detection's centroid, and at the foot of the perpendicular from the sensor to the true wall.
  double centroid_error_m = 0.0;
  double foot_error_m = 0.0;
  double normal_error_deg = 0.0;  // between the fitted normal and the true one
  // The detection's own account of its fit: its RMS and its horizontal extent, for judging the
  // error against what the fit claims (an orientation sigma of about rms / (length sqrt(points /
  // 12)) if its points' errors were independent).
  double rms_m = 0.0;
  double length_m = 0.0;
};

// The detections (sensor frame) of one frame taken at `sensor` (sensor to world) that lie on a
// true wall: vertical, facing within 10 degrees of it, the centroid within 0.12 m of its plane and
// within 0.1 m of its ends along it; the nearest such wall when there are several.
std::vector<PlaneError> PlaneErrors(int64_t seq, const Eigen::Isometry3d& sensor,
                                    const std::vector<segmenter::DetectedPlane>& detections,
                                    const std::vector<sim::TruePlane>& walls);

// One row per error, with a header: seq,true_id,true_length_m,range_m,points,centroid_error_m,
// foot_error_m,normal_error_deg.
std::string PlaneErrorsCsv(const std::vector<PlaneError>& errors);

}  // namespace relplane::accuracy
