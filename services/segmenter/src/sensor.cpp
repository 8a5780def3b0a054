#include "relplane/segmenter/sensor.hpp"

#include <algorithm>
#include <cmath>

namespace relplane::segmenter {

bool SensorOptions::SetPreset(const std::string& name) {
  const auto found = camera::Preset(name);
  if (!found) return false;
  preset = name;
  model = *found;
  return true;
}

float SensorOptions::VarianceAt(float depth) const {
  // Nearer than the camera's minimum nothing is measured; the floor there is the minimum's.
  const double z = std::max(static_cast<double>(depth), model.min_depth);
  const double s = model.ResolvedSigma(z);
  return static_cast<float>(s * s);
}

float SensorOptions::SigmaAlongNormal(const Eigen::Vector3f& normal,
                                      const Eigen::Vector3f& point) const {
  if (!(point.x() > 0.0f)) return 0.0f;
  return std::sqrt(VarianceAt(point.x())) * std::fabs(normal.dot(point / point.x()));
}

bool SensorOptions::BeyondIncidence(const Eigen::Vector3f& normal,
                                    const Eigen::Vector3f& centroid) const {
  const double limit_deg = model.max_incidence_deg + grazing_margin_deg;
  if (!Known() || limit_deg >= 90.0) return false;
  const float range = centroid.norm();
  if (!(range > 0.0f)) return false;
  const double cos_limit = std::cos(limit_deg * M_PI / 180.0);
  return std::fabs(normal.dot(centroid)) / range < cos_limit;
}

float SensorOptions::CoplanarDistance(float base, const Eigen::Vector3f& normal_a,
                                      const Eigen::Vector3f& centroid_a,
                                      const Eigen::Vector3f& normal_b,
                                      const Eigen::Vector3f& centroid_b) const {
  if (!Known()) return base;
  const float resolved =
      std::max(SigmaAlongNormal(normal_a, centroid_a), SigmaAlongNormal(normal_b, centroid_b));
  return std::max(base, 3.0f * resolved);
}

}  // namespace relplane::segmenter
