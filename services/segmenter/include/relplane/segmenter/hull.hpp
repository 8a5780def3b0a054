#pragma once
// 2D convex hull for the extent polygon of non-vertical planes.

#include <Eigen/Core>
#include <vector>

namespace relplane::segmenter {

// Convex hull, counter-clockwise, without collinear points (Andrew's monotone chain).
// Fewer than three distinct points come back as they are (deduplicated).
std::vector<Eigen::Vector2f> ConvexHull(std::vector<Eigen::Vector2f> points);

}  // namespace relplane::segmenter
