#include "relplane/plane_truth/accuracy.hpp"

#include <algorithm>
#include <cmath>

namespace relplane::plane_truth {
namespace {

double Median(std::vector<double> v) {
  if (v.empty()) return 0.0;
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

}  // namespace

double PlaneAngleDeg(const Eigen::Vector3d& a, const Eigen::Vector3d& b) {
  return std::atan2(a.cross(b).norm(), std::fabs(a.dot(b))) * 180.0 / M_PI;
}

void AccuracyTally::AddRecalled(double angle_deg, double offset_m) {
  ++acc_.true_planes;
  ++acc_.recalled;
  angles_.push_back(angle_deg);
  offsets_.push_back(offset_m);
}

Accuracy AccuracyTally::Summary() const {
  Accuracy a = acc_;
  a.median_angle_deg = Median(angles_);
  a.median_offset_m = Median(offsets_);
  if (!rms_ratios_.empty()) {
    a.min_rms_to_camera = *std::min_element(rms_ratios_.begin(), rms_ratios_.end());
  }
  return a;
}

}  // namespace relplane::plane_truth
