#pragma once
// What relplane-segment prints and writes about the planes found in each frame: a table per
// frame and one JSON document for all of them (docs/segment.md).

#include <Eigen/Core>
#include <string>
#include <vector>

#include "relplane/segmenter/cloud.hpp"

namespace relplane::segment {

struct FramePlanes {
  std::string name;  // the frame's file name
  int64_t points = 0;
  int64_t invalid_points = 0;
  std::vector<segmenter::DetectedPlane> planes;  // decreasing support
};

// Width and height of a plane's extent polygon, metres: along the horizontal line of the plane
// and across it (for a horizontal plane: along the sensor's x and y).
Eigen::Vector2f ExtentSize(const segmenter::DetectedPlane& plane);

// One frame as a table: a header line, then per plane its index, normal, d (m), supporting
// points, RMS (mm) and extent size (m).
std::string PlaneTable(const FramePlanes& frame);

// Every frame's planes as JSON (schema relplane-segment/1).
std::string PlanesJson(const std::vector<FramePlanes>& frames);

}  // namespace relplane::segment
