#pragma once
// Point cloud and plane types of the segmenter: flat arrays per axis, as point_cloud_t carries
// them, so loops over points vectorise.

#include <Eigen/Core>
#include <cstddef>
#include <vector>

namespace relplane::segmenter {

// An unorganized cloud, sensor frame (x forward, y left, z up), metres.
struct Cloud {
  std::vector<float> x, y, z;

  size_t size() const { return x.size(); }
  bool empty() const { return x.empty(); }
  void Reserve(size_t n) {
    x.reserve(n);
    y.reserve(n);
    z.reserve(n);
  }
  void Add(float px, float py, float pz) {
    x.push_back(px);
    y.push_back(py);
    z.push_back(pz);
  }
  void Add(const Eigen::Vector3f& p) { Add(p.x(), p.y(), p.z()); }
  Eigen::Vector3f Point(size_t i) const { return {x[i], y[i], z[i]}; }
};

// One plane found in a cloud: a connected piece of coplanar support.
struct DetectedPlane {
  Eigen::Vector3f normal = Eigen::Vector3f::UnitZ();  // unit, pointing towards the sensor
  float d = 0.0f;                                     // normal . p + d = 0; d >= 0
  Eigen::Vector3f centroid = Eigen::Vector3f::Zero();
  // Boundary polygon in order around the piece: the 4 corners of the visible rectangle for a
  // vertical plane, the convex hull of the support otherwise.
  std::vector<Eigen::Vector3f> vertices;
  int num_points = 0;
  float rms = 0.0f;  // RMS point-to-plane distance of the support, metres
};

}  // namespace relplane::segmenter
