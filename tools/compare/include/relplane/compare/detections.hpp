#pragma once
// Planes found by another library described as relplane's segmenter describes its own, so one
// set of scoring rules (relplane/plane_truth) applies to every method.

#include <cstdint>
#include <vector>

#include "relplane/compare/organized_frame.hpp"
#include "relplane/segmenter/cloud.hpp"

namespace relplane::compare {

struct Detections {
  std::vector<segmenter::DetectedPlane> planes;  // decreasing support
  std::vector<int32_t> labels;                   // per point of the frame: index in planes, or -1
};

// Each fit as a DetectedPlane: the fit's plane turned to face the sensor, the centroid and RMS of
// its points, its extent the convex hull of its points in the plane.
Detections Describe(const segmenter::Cloud& frame, std::vector<PlaneFit> fits);

}  // namespace relplane::compare
