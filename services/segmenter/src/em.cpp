#include "relplane/segmenter/em.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

namespace relplane::segmenter {
namespace {

// Beyond this many sigma a plane's density is taken as zero: it saves the exp() for the
// (many) points far from a plane and changes responsibilities by less than 1e-5.
constexpr float kCutoffSigmas = 5.0f;
// Weights below this are skipped in the M-step sums.
constexpr float kMinWeight = 1e-4f;

}  // namespace

std::vector<float> RangeVariance(const Cloud& points, float range_noise) {
  std::vector<float> q(points.size(), 0.0f);
  if (range_noise <= 0.0f) return q;
  const float k2 = range_noise * range_noise;
  for (size_t i = 0; i < points.size(); ++i) {
    const float r2 =
        points.x[i] * points.x[i] + points.y[i] * points.y[i] + points.z[i] * points.z[i];
    q[i] = k2 * r2 * r2;
  }
  return q;
}

void EStep(const Cloud& points, const std::vector<EmPlane>& planes, const Options& options,
           Responsibilities* resp) {
  const float outlier_density = options.outlier_density;
  resp->range_variance = RangeVariance(points, options.range_noise);
  const float* q = resp->range_variance.data();
  const int n = static_cast<int>(points.size());
  const int k = static_cast<int>(planes.size());
  resp->num_points = n;
  resp->num_planes = k;
  resp->r.assign(static_cast<size_t>(k + 1) * n, 0.0f);
  float* total = &resp->r[static_cast<size_t>(k) * n];  // the outlier row doubles as the sum
  std::fill(total, total + n, outlier_density);
  const float* x = points.x.data();
  const float* y = points.y.data();
  const float* z = points.z.data();
  for (int j = 0; j < k; ++j) {
    const EmPlane& p = planes[j];
    const float nx = p.normal.x(), ny = p.normal.y(), nz = p.normal.z(), d = p.d;
    const float var_j = p.sigma * p.sigma;
    const float cutoff2 = kCutoffSigmas * kCutoffSigmas;
    const float inv_sqrt_2pi = 1.0f / std::sqrt(2.0f * static_cast<float>(M_PI));
    float* row = &resp->r[static_cast<size_t>(j) * n];
    for (int i = 0; i < n; ++i) {
      const float dist = nx * x[i] + ny * y[i] + nz * z[i] + d;
      const float var = var_j + q[i];
      if (dist * dist < cutoff2 * var) {
        row[i] = inv_sqrt_2pi / std::sqrt(var) * std::exp(-0.5f * dist * dist / var);
        total[i] += row[i];
      }
    }
  }
  for (int i = 0; i < n; ++i) total[i] = 1.0f / total[i];
  for (int j = 0; j < k; ++j) {
    float* row = &resp->r[static_cast<size_t>(j) * n];
    for (int i = 0; i < n; ++i) row[i] *= total[i];
  }
  for (int i = 0; i < n; ++i) total[i] *= outlier_density;
}

void MStep(const Cloud& points, const Responsibilities& resp, const Options& options,
           std::vector<EmPlane>* planes) {
  const int n = resp.num_points;
  for (int j = 0; j < resp.num_planes; ++j) {
    EmPlane& plane = (*planes)[j];
    const float* r = &resp.r[static_cast<size_t>(j) * n];
    // Heteroscedastic weights: a point's responsibility scaled by its precision relative to
    // the plane's own noise, so noisy far points count less (equal weights without range noise).
    const float var_j = plane.sigma * plane.sigma;
    std::vector<float> weight(n);
    for (int i = 0; i < n; ++i) weight[i] = r[i] * var_j / (var_j + resp.range_variance[i]);
    const float* w = weight.data();
    // One pass of moments about the previous centroid (close to the new one, so the sums stay
    // well conditioned), in double.
    const Eigen::Vector3f ref = plane.centroid;
    double sw = 0.0, support = 0.0;
    double s1[3] = {0, 0, 0}, s2[6] = {0, 0, 0, 0, 0, 0};
    for (int i = 0; i < n; ++i) {
      support += r[i];
      if (w[i] < kMinWeight) continue;
      const double wi = w[i];
      const double x = points.x[i] - ref.x(), y = points.y[i] - ref.y(), z = points.z[i] - ref.z();
      sw += wi;
      s1[0] += wi * x;
      s1[1] += wi * y;
      s1[2] += wi * z;
      s2[0] += wi * x * x;
      s2[1] += wi * x * y;
      s2[2] += wi * x * z;
      s2[3] += wi * y * y;
      s2[4] += wi * y * z;
      s2[5] += wi * z * z;
    }
    plane.support = static_cast<float>(support);
    if (sw < 3.0) continue;  // too little support to fit; pruning decides its fate
    const Eigen::Vector3d m(s1[0] / sw, s1[1] / sw, s1[2] / sw);
    Eigen::Matrix3d scatter;
    scatter << s2[0], s2[1], s2[2], s2[1], s2[3], s2[4], s2[2], s2[4], s2[5];
    scatter -= sw * m * m.transpose();
    const Eigen::Vector3d mean = ref.cast<double>() + m;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(scatter);
    Eigen::Vector3d normal = eig.eigenvectors().col(0);
    if (normal.dot(plane.normal.cast<double>()) < 0.0) normal = -normal;
    plane.normal = normal.normalized().cast<float>();
    plane.d = static_cast<float>(-normal.dot(mean));
    plane.centroid = mean.cast<float>();
    // sum(w d^2) / sum(r) estimates sigma^2 once range noise is normalised out.
    const double variance = std::max(0.0, eig.eigenvalues()(0)) / support;
    plane.sigma =
        std::clamp(static_cast<float>(std::sqrt(variance)), options.sigma_min, options.sigma_max);
  }
}

int RunEm(const Cloud& points, const Options& options, int max_iterations,
          std::vector<EmPlane>* planes, Responsibilities* resp) {
  int iteration = 0;
  while (iteration < max_iterations) {
    const std::vector<EmPlane> before = *planes;
    EStep(points, *planes, options, resp);
    MStep(points, *resp, options, planes);
    ++iteration;
    bool moved = false;
    for (size_t j = 0; j < planes->size() && !moved; ++j) {
      const float cos_angle = std::min(1.0f, before[j].normal.dot((*planes)[j].normal));
      moved = std::acos(cos_angle) > options.converged_angle ||
              std::fabs(before[j].d - (*planes)[j].d) > options.converged_offset;
    }
    if (!moved) break;
  }
  // Leave responsibilities that belong to the planes as they are now.
  EStep(points, *planes, options, resp);
  return iteration;
}

}  // namespace relplane::segmenter
