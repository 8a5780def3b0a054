#include "relplane/compare/detections.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>

#include "relplane/segmenter/hull.hpp"

namespace relplane::compare {
namespace {

segmenter::DetectedPlane DescribeOne(const segmenter::Cloud& frame, const PlaneFit& fit) {
  segmenter::DetectedPlane p;
  Eigen::Vector3f n(fit.nx, fit.ny, fit.nz);
  float d = fit.d;
  const float norm = n.norm();
  n /= norm;
  d /= norm;
  if (d < 0.0f) {  // relplane's convention: the normal faces the sensor, d >= 0
    n = -n;
    d = -d;
  }
  p.normal = n;
  p.d = d;
  p.num_points = static_cast<int>(fit.indices.size());
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  double squares = 0.0;
  for (int i : fit.indices) {
    const Eigen::Vector3f q = frame.Point(static_cast<size_t>(i));
    sum += q.cast<double>();
    const double r = n.dot(q) + d;
    squares += r * r;
  }
  const double count = std::max<double>(1.0, static_cast<double>(fit.indices.size()));
  p.centroid = (sum / count).cast<float>();
  p.rms = static_cast<float>(std::sqrt(squares / count));
  // The extent: the points' convex hull in a basis of the plane, lifted back onto it.
  const Eigen::Vector3f u = n.unitOrthogonal(), v = n.cross(u);
  std::vector<Eigen::Vector2f> flat;
  flat.reserve(fit.indices.size());
  for (int i : fit.indices) {
    const Eigen::Vector3f q = frame.Point(static_cast<size_t>(i)) - p.centroid;
    flat.emplace_back(u.dot(q), v.dot(q));
  }
  const Eigen::Vector3f origin = p.centroid - n * (n.dot(p.centroid) + d);
  for (const Eigen::Vector2f& h : segmenter::ConvexHull(std::move(flat))) {
    p.vertices.push_back(origin + u * h.x() + v * h.y());
  }
  return p;
}

}  // namespace

Detections Describe(const segmenter::Cloud& frame, std::vector<PlaneFit> fits) {
  // Decreasing support, as the segmenter reports: a true plane is recalled by the best-supported
  // detection that matches it. Ties keep the method's order.
  std::stable_sort(fits.begin(), fits.end(), [](const PlaneFit& a, const PlaneFit& b) {
    return a.indices.size() > b.indices.size();
  });
  Detections out;
  out.labels.assign(frame.size(), -1);
  for (const PlaneFit& fit : fits) {
    const auto label = static_cast<int32_t>(out.planes.size());
    for (int i : fit.indices) out.labels[static_cast<size_t>(i)] = label;
    out.planes.push_back(DescribeOne(frame, fit));
  }
  return out;
}

}  // namespace relplane::compare
