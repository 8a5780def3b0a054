#pragma once
// A depth frame as an image, the input organized segmentation needs: width × height points,
// row-major, in relplane's sensor frame (x forward, y left, z up), NaN where nothing returned.

#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/sim/depth_sensor.hpp"

namespace relplane::compare {

struct OrganizedFrame {
  int width = 0;
  int height = 0;
  segmenter::Cloud points;  // width * height, row-major
};

// The simulator's scan on its ray grid (`width` rays per row, `height` rows): its rays are an
// image, column by column; a ray without a hit is NaN.
OrganizedFrame FromScan(const sim::Scan& scan, int width, int height);

// A plane some method found: its points (indices into the frame) and its plane n . p + d = 0,
// sensor frame.
struct PlaneFit {
  float nx = 0.0f, ny = 0.0f, nz = 1.0f, d = 0.0f;
  std::vector<int> indices;
};

}  // namespace relplane::compare
