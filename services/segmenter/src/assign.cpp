#include "relplane/segmenter/assign.hpp"

#include <cmath>

namespace relplane::segmenter {
namespace {

// Two planes whose normals differ by more than this meet in a line (a corner, not a step).
constexpr float kCrossingAngleDeg = 20.0f;

}  // namespace

std::vector<int32_t> AssignPoints(const Cloud& cloud, const std::vector<EmPlane>& planes,
                                  const Options& options, std::vector<uint8_t>* ambiguous) {
  const size_t n = cloud.size();
  std::vector<int32_t> label(n, -1);
  // Scores below 1 are inliers; the smallest score wins.
  std::vector<float> best(n, 1.0f);
  std::vector<float> second(n, 1.0f);
  std::vector<int32_t> second_label(n, -1);
  float* s2 = second.data();
  int32_t* l2 = second_label.data();
  const float* x = cloud.x.data();
  const float* y = cloud.y.data();
  const float* z = cloud.z.data();
  float* b = best.data();
  int32_t* l = label.data();
  // Planes outer, points inner: the inner loop is branch-free and vectorises.
  // Scores are squared, in units of the point's variance: (d / t)^2 / (sigma^2 + q r^4).
  const float t2 = options.inlier_sigmas * options.inlier_sigmas;
  const float k2 = options.range_noise * options.range_noise;
  for (size_t j = 0; j < planes.size(); ++j) {
    const float nx = planes[j].normal.x(), ny = planes[j].normal.y();
    const float nz = planes[j].normal.z(), d = planes[j].d;
    const float var_j = planes[j].sigma * planes[j].sigma;
    const int32_t id = static_cast<int32_t>(j);
    for (size_t i = 0; i < n; ++i) {
      const float s = nx * x[i] + ny * y[i] + nz * z[i] + d;
      const float r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
      const float score = s * s / (t2 * (var_j + k2 * r2 * r2));
      const bool closer = score < b[i];
      const bool second_closer = !closer && score < s2[i];
      l2[i] = closer ? l[i] : (second_closer ? id : l2[i]);
      s2[i] = closer ? b[i] : (second_closer ? score : s2[i]);
      b[i] = closer ? score : b[i];
      l[i] = closer ? id : l[i];
    }
  }
  if (ambiguous) {
    ambiguous->resize(n);
    // Only planes that cross count: near-parallel neighbours (a box lid just above the floor)
    // overlap in a band but do not meet in a line.
    const float cos_crossing = std::cos(kCrossingAngleDeg * static_cast<float>(M_PI) / 180.0f);
    for (size_t i = 0; i < n; ++i) {
      (*ambiguous)[i] =
          l2[i] >= 0 && l[i] >= 0 &&
          std::fabs(planes[l[i]].normal.dot(planes[l2[i]].normal)) < cos_crossing;
    }
  }
  return label;
}

}  // namespace relplane::segmenter
