#include "relplane/segmenter/assign.hpp"

#include <algorithm>
#include <cmath>

#include "simd.hpp"

namespace relplane::segmenter {
namespace {

// Two planes whose normals differ by more than this meet in a line (a corner, not a step).
constexpr float kCrossingAngleDeg = 20.0f;

// Points are ranked in blocks that stay in L1 cache while every plane is scored against them.
constexpr size_t kBlock = 512;

// Scores all points against one plane and keeps the best and second-best plane per point, in
// one pass. A score is the squared distance in units of the point's threshold. Masks and
// min/max instead of branches so the loop vectorises (best <= second always holds). Inlined,
// so it is built for each clone of AssignPoints.
template <bool kRangeNoise>
[[gnu::always_inline]] inline void ScoreAndRank(
    size_t n, const float* __restrict x, const float* __restrict y, const float* __restrict z,
    const EmPlane& plane, float t2, const float* __restrict q, int32_t id, float* __restrict b,
    float* __restrict s2, int32_t* __restrict l, int32_t* __restrict l2) {
  const float nx = plane.normal.x(), ny = plane.normal.y(), nz = plane.normal.z(), d = plane.d;
  const float var = plane.sigma * plane.sigma;
  const float inv = 1.0f / (t2 * var);
  for (size_t i = 0; i < n; ++i) {
    const float s = nx * x[i] + ny * y[i] + nz * z[i] + d;
    const float sc = kRangeNoise ? s * s / (t2 * (var + q[i])) : s * s * inv;
    const float bi = b[i], si = s2[i];
    const int32_t li = l[i], l2i = l2[i];
    const int32_t closer = -static_cast<int32_t>(sc < bi);
    const int32_t second_closer = -static_cast<int32_t>(sc < si);
    const int32_t l2_if_not = l2i ^ ((l2i ^ id) & second_closer);
    l2[i] = l2_if_not ^ ((l2_if_not ^ li) & closer);
    l[i] = li ^ ((li ^ id) & closer);
    s2[i] = std::min(std::max(sc, bi), si);
    b[i] = std::min(sc, bi);
  }
}

}  // namespace

RELPLANE_SIMD_CLONES void AssignPoints(const Cloud& cloud, const std::vector<EmPlane>& planes,
                                       const Options& options, std::vector<int32_t>* labels,
                                       std::vector<uint8_t>* ambiguous) {
  const size_t n = cloud.size();
  const size_t k = planes.size();
  labels->resize(n);
  if (ambiguous) ambiguous->resize(n);
  // Only planes that cross count as ambiguous: near-parallel neighbours (a box lid just above
  // the floor) overlap in a band but do not meet in a line.
  const float cos_crossing = std::cos(kCrossingAngleDeg * static_cast<float>(M_PI) / 180.0f);
  std::vector<uint8_t> crossing(k * k);
  for (size_t a = 0; a < k; ++a) {
    for (size_t b = 0; b < k; ++b) {
      crossing[a * k + b] = std::fabs(planes[a].normal.dot(planes[b].normal)) < cos_crossing;
    }
  }
  // Scores are squared distances in units of the point's threshold,
  // d^2 / (t^2 (sigma^2 + (k r^2)^2)): below 1 is an inlier, the smallest wins.
  const float t2 = options.inlier_sigmas * options.inlier_sigmas;
  const float k2 = options.range_noise * options.range_noise;
  alignas(64) float best[kBlock], second[kBlock], q[kBlock];
  alignas(64) int32_t label[kBlock], second_label[kBlock];
  for (size_t start = 0; start < n; start += kBlock) {
    const size_t m = std::min(kBlock, n - start);
    const float* x = cloud.x.data() + start;
    const float* y = cloud.y.data() + start;
    const float* z = cloud.z.data() + start;
    for (size_t i = 0; i < m; ++i) {
      best[i] = 1.0f;
      second[i] = 1.0f;
      label[i] = -1;
      second_label[i] = -1;
    }
    if (k2 > 0.0f) {
      for (size_t i = 0; i < m; ++i) {
        const float r2 = x[i] * x[i] + y[i] * y[i] + z[i] * z[i];
        q[i] = k2 * r2 * r2;
      }
    }
    for (size_t j = 0; j < k; ++j) {
      const int32_t id = static_cast<int32_t>(j);
      if (k2 > 0.0f) {
        ScoreAndRank<true>(m, x, y, z, planes[j], t2, q, id, best, second, label, second_label);
      } else {
        ScoreAndRank<false>(m, x, y, z, planes[j], t2, q, id, best, second, label, second_label);
      }
    }
    std::copy(label, label + m, labels->data() + start);
    if (!ambiguous) continue;
    uint8_t* amb = ambiguous->data() + start;
    for (size_t i = 0; i < m; ++i) {
      amb[i] = label[i] >= 0 && second_label[i] >= 0 && crossing[label[i] * k + second_label[i]];
    }
  }
}

}  // namespace relplane::segmenter
