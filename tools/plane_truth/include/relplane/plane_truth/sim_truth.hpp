#pragma once
// Detected planes against the simulator's true rectangles: a detection matches a rectangle when
// its normal is within 5 degrees, its plane passes the sensor within 0.1 m of the rectangle's,
// and its extent overlaps the rectangle; a rectangle is in view in a frame when at least 300 of
// the frame's points lie on it within the camera's depth range.

#include <Eigen/Geometry>
#include <vector>

#include "relplane/common/depth_camera.hpp"
#include "relplane/plane_truth/accuracy.hpp"
#include "relplane/segmenter/cloud.hpp"
#include "relplane/sim/depth_sensor.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::plane_truth {

// Whether an extent (world frame) overlaps the rectangle by more than 5 cm in both directions.
bool Overlaps(const sim::TruePlane& t, const std::vector<Eigen::Vector3d>& extent);

// A scan's points as the segmenter takes them (hits only, the scan's order).
segmenter::Cloud CloudOf(const sim::Scan& scan);

// Scores frames of one simulation against its world, into a tally per method.
class SimScorer {
 public:
  SimScorer(std::vector<sim::TruePlane> truth, camera::DepthCameraModel camera);

  // One frame: its scan (which rectangle each point came from), the sensor's true pose and the
  // detections (sensor frame) in decreasing support: a rectangle is recalled by the
  // best-supported detection that matches it.
  void AddFrame(const sim::Scan& scan, const Eigen::Isometry3d& pose,
                const std::vector<segmenter::DetectedPlane>& planes, AccuracyTally* tally) const;

 private:
  std::vector<sim::TruePlane> truth_;
  camera::DepthCameraModel camera_;
};

}  // namespace relplane::plane_truth
