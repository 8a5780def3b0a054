#include "relplane/segmenter/spacing.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "simd.hpp"

namespace relplane::segmenter {
namespace {

constexpr int kProbes = 48;
constexpr float kConeRadians = 0.1f;  // half angle of the cone counted around a probe
constexpr int kMinCount = 8;          // fewer sample points in the cone: too sparse to tell

}  // namespace

RELPLANE_SIMD_CLONES float EstimateAngularStep(const Cloud& sample, size_t cloud_size) {
  const size_t n = sample.size();
  if (n < static_cast<size_t>(4 * kMinCount) || cloud_size < n) return 0.0f;
  std::vector<float> ux(n), uy(n), uz(n);
  for (size_t i = 0; i < n; ++i) {
    const float r2 =
        sample.x[i] * sample.x[i] + sample.y[i] * sample.y[i] + sample.z[i] * sample.z[i];
    const float inv = r2 > 0.0f ? 1.0f / std::sqrt(r2) : 0.0f;  // 0: matches no probe
    ux[i] = sample.x[i] * inv;
    uy[i] = sample.y[i] * inv;
    uz[i] = sample.z[i] * inv;
  }
  const float cos_cone = std::cos(kConeRadians);
  std::vector<int> counts;
  for (int k = 0; k < kProbes; ++k) {
    const size_t p = (2 * static_cast<size_t>(k) + 1) * n / (2 * kProbes);
    const float px = ux[p], py = uy[p], pz = uz[p];
    int count = 0;
    for (size_t i = 0; i < n; ++i) count += px * ux[i] + py * uy[i] + pz * uz[i] > cos_cone;
    counts.push_back(count - 1);  // not the probe itself
  }
  const auto quartile = counts.begin() + (3 * counts.size()) / 4;
  std::nth_element(counts.begin(), quartile, counts.end());
  if (*quartile < kMinCount) return 0.0f;
  const double cone = 2.0 * M_PI * (1.0 - std::cos(static_cast<double>(kConeRadians)));
  const double points_in_cone = *quartile * static_cast<double>(cloud_size) / n;
  return static_cast<float>(std::sqrt(cone / points_in_cone));
}

}  // namespace relplane::segmenter
