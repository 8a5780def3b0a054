#include "relplane/segmenter/assign.hpp"

#include <algorithm>
#include <cmath>

namespace relplane::segmenter {
namespace {

// Two planes whose normals differ by more than this meet in a line (a corner, not a step).
constexpr float kCrossingAngleDeg = 20.0f;

// Best and second-best scores per point. Plain arrays and selects keep the loop branch-free so
// it vectorises; the range-noise variant needs one division per point and plane.
struct Ranking {
  std::vector<float> best, second;
  std::vector<int32_t> label, second_label;
};

// Squared distances of all points to one plane, in units of each point's threshold.
void Scores(const Cloud& cloud, const EmPlane& plane, float t2, const float* q,
            float* __restrict out) {
  const size_t n = cloud.size();
  const float* __restrict x = cloud.x.data();
  const float* __restrict y = cloud.y.data();
  const float* __restrict z = cloud.z.data();
  const float nx = plane.normal.x(), ny = plane.normal.y(), nz = plane.normal.z(), d = plane.d;
  const float var = plane.sigma * plane.sigma;
  if (q == nullptr) {
    const float inv = 1.0f / (t2 * var);
    for (size_t i = 0; i < n; ++i) {
      const float s = nx * x[i] + ny * y[i] + nz * z[i] + d;
      out[i] = s * s * inv;
    }
  } else {
    for (size_t i = 0; i < n; ++i) {
      const float s = nx * x[i] + ny * y[i] + nz * z[i] + d;
      out[i] = s * s / (t2 * (var + q[i]));
    }
  }
}

// Keeps the best and second-best plane per point. Masks and min/max instead of branches so the
// loop vectorises (best <= second always holds).
void Rank(size_t n, const float* __restrict score, int32_t id, float* __restrict b,
          float* __restrict s2, int32_t* __restrict l, int32_t* __restrict l2) {
  for (size_t i = 0; i < n; ++i) {
    const float bi = b[i], si = s2[i], sc = score[i];
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

std::vector<int32_t> AssignPoints(const Cloud& cloud, const std::vector<EmPlane>& planes,
                                  const Options& options, std::vector<uint8_t>* ambiguous) {
  const size_t n = cloud.size();
  // Scores are squared distances in units of the point's threshold,
  // d^2 / (t^2 (sigma^2 + (k r^2)^2)): below 1 is an inlier, the smallest wins.
  Ranking r;
  r.best.assign(n, 1.0f);
  r.second.assign(n, 1.0f);
  r.label.assign(n, -1);
  r.second_label.assign(n, -1);
  const float t2 = options.inlier_sigmas * options.inlier_sigmas;
  const float k2 = options.range_noise * options.range_noise;
  std::vector<float> q;
  if (k2 > 0.0f) {
    q.resize(n);
    for (size_t i = 0; i < n; ++i) {
      const float r2 = cloud.x[i] * cloud.x[i] + cloud.y[i] * cloud.y[i] + cloud.z[i] * cloud.z[i];
      q[i] = k2 * r2 * r2;
    }
  }
  std::vector<float> score(n);
  for (size_t j = 0; j < planes.size(); ++j) {
    Scores(cloud, planes[j], t2, q.empty() ? nullptr : q.data(), score.data());
    Rank(n, score.data(), static_cast<int32_t>(j), r.best.data(), r.second.data(), r.label.data(),
         r.second_label.data());
  }
  if (ambiguous) {
    // Only planes that cross count: near-parallel neighbours (a box lid just above the floor)
    // overlap in a band but do not meet in a line.
    const float cos_crossing = std::cos(kCrossingAngleDeg * static_cast<float>(M_PI) / 180.0f);
    ambiguous->assign(n, 0);
    for (size_t i = 0; i < n; ++i) {
      const int32_t a = r.label[i], b = r.second_label[i];
      if (a < 0 || b < 0) continue;
      (*ambiguous)[i] = std::fabs(planes[a].normal.dot(planes[b].normal)) < cos_crossing;
    }
  }
  return std::move(r.label);
}

}  // namespace relplane::segmenter
