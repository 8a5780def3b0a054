#pragma once
// A tiny ray-casting world for the segmenter tests: rectangles seen by a level depth sensor.
// World frame z up; sensor frame x forward, y left, z up.

#include <Eigen/Geometry>
#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segmenter::testing {

// The rectangle corner + s * edge_u + t * edge_v, s and t in [0, 1], world frame.
struct Rect {
  Eigen::Vector3d corner;
  Eigen::Vector3d edge_u;
  Eigen::Vector3d edge_v;
};

struct Sensor {
  int width = 160;
  int height = 120;
  double hfov_deg = 60.0;
  double max_range = 10.0;
  double sigma = 0.0;  // Gaussian range noise along each ray, metres
  uint32_t seed = 7;
  Eigen::Isometry3d world_from_sensor = Eigen::Isometry3d(Eigen::Translation3d(0, 0, 1));
};

struct Scan {
  Cloud cloud;           // sensor frame, pixels that hit nothing are left out
  std::vector<int> hit;  // rectangle index of each point
};

// Casts one ray per pixel (pinhole, square pixels) and keeps the nearest rectangle hit.
Scan Render(const std::vector<Rect>& world, const Sensor& sensor);
// Same pixels, but the points are shuffled: no image order survives.
Scan RenderUnorganized(const std::vector<Rect>& world, const Sensor& sensor);

// An axis-aligned box room: floor, ceiling and walls.
std::vector<Rect> Hallway();  // 2 m wide, 2.5 m high, 12 m long; the left wall has a door gap
std::vector<Rect> Office();   // 6 x 5 m room with a 1 x 0.8 x 0.9 m cabinet

// A true rectangle's plane in the sensor frame, normal towards the sensor: n . p + d = 0.
void TruePlane(const Rect& rect, const Eigen::Isometry3d& world_from_sensor,
               Eigen::Vector3d* normal, double* d);

struct Score {
  int true_planes = 0;  // rectangles with at least `min_points` hits
  int recalled = 0;
  int detected = 0;
  int correct = 0;  // detections that match some rectangle
  double median_angle_deg = 0.0;
  double median_offset_m = 0.0;
  double Precision() const { return detected ? static_cast<double>(correct) / detected : 1.0; }
  double Recall() const { return true_planes ? static_cast<double>(recalled) / true_planes : 1.0; }
};

// Matches detections to rectangles: normals within 5 degrees, offsets within 0.1 m and the
// detection's centroid on the rectangle (0.2 m margin). Errors are taken over the recalled
// rectangles, each against its best-supported matching detection.
Score Evaluate(const std::vector<DetectedPlane>& planes, const std::vector<Rect>& world,
               const Scan& scan, const Sensor& sensor, int min_points = 300);

}  // namespace relplane::segmenter::testing
