#include "relplane/segmenter/em.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstring>

#include "simd.hpp"

namespace relplane::segmenter {
namespace {

// Beyond this many sigma a plane's density is taken as zero: it saves the exp() for the
// (many) points far from a plane and changes responsibilities by less than 1e-5.
constexpr float kCutoffSigmas = 5.0f;
// Weights below this are skipped in the M-step sums.
constexpr float kMinWeight = 1e-4f;

// Lanes of the hand-split reductions below: independent partial sums per lane let the
// compiler vectorise a sum without reassociating it.
constexpr int kLanes = 8;
constexpr int kBlock = 256;  // points per block of the M-step's float sums

int32_t Bits(float f) {
  int32_t b;
  std::memcpy(&b, &f, sizeof b);
  return b;
}
float Float(int32_t b) {
  float f;
  std::memcpy(&f, &b, sizeof f);
  return f;
}

// exp(-u / 2) for u in [0, kCutoffSigmas^2], branch-free so loops over it vectorise:
// -u / 2 = n ln2 + r with |r| <= ln2 / 2, exp(r) by its degree-6 Taylor polynomial (relative
// error below 2e-7, about float rounding), 2^n assembled in the exponent bits.
float ExpHalfNegative(float u) {
  const float x = -0.5f * u;
  constexpr float kRound = 12582912.0f;  // 1.5 * 2^23: adding and removing it rounds to integer
  const float n = (x * 1.44269504f + kRound) - kRound;
  const float r = (x - n * 0.693145752f) - n * 1.42860677e-6f;  // Cody-Waite: ln2 in two parts
  float p = 1.0f / 720.0f;
  p = p * r + 1.0f / 120.0f;
  p = p * r + 1.0f / 24.0f;
  p = p * r + 1.0f / 6.0f;
  p = p * r + 0.5f;
  p = p * r + 1.0f;
  p = p * r + 1.0f;
  return p * Float((static_cast<int32_t>(n) + 127) << 23);
}

// peak * exp(-u / 2) within the cut-off (u < cutoff), 0 beyond. u >= 0, so its bits order as
// integers do: integer min and masks keep the loop free of branches.
float Density(float peak, float u, int32_t cutoff_bits) {
  const int32_t ub = Bits(u);
  const int32_t within = -static_cast<int32_t>(ub < cutoff_bits);
  return Float(Bits(peak * ExpHalfNegative(Float(std::min(ub, cutoff_bits)))) & within);
}

// Sums over n points, n a multiple of kLanes, in kLanes partial sums.
float Sum(const float* __restrict a, int n) {
  float lane[kLanes] = {};
  for (int i = 0; i < n; i += kLanes) {
    for (int l = 0; l < kLanes; ++l) lane[l] += a[i + l];
  }
  float s = 0.0f;
  for (float v : lane) s += v;
  return s;
}
// The moments of one block of n points, n a multiple of kLanes, added to sums (support, w,
// wx, wy, wz, wxx, wxy, wxz, wyy, wyz, wzz; p about the reference point): one pass with
// kLanes partial sums each. Heteroscedastic weights: a point's responsibility scaled by its
// precision relative to the plane's own noise var, so noisy far points count less (equal
// weights without range noise); weights below kMinWeight count as zero. Every product is
// formed as (w * p) * p', as separate dot products over the block would, in the same order.
// Inlined, so it is built for each clone of MStep.
[[gnu::always_inline]] inline void AddBlockMoments(
    const float* __restrict r, const float* __restrict q, const float* __restrict x,
    const float* __restrict y, const float* __restrict z, int n, const Eigen::Vector3f& ref,
    float var, double* sums) {
  const float rx = ref.x(), ry = ref.y(), rz = ref.z();
  float lane[11][kLanes] = {};
  for (int i = 0; i < n; i += kLanes) {
    for (int l = 0; l < kLanes; ++l) {
      const int g = i + l;
      const float wr = r[g] * var / (var + q[g]);
      const float wi = Float(Bits(wr) & -static_cast<int32_t>(wr >= kMinWeight));
      const float px = x[g] - rx, py = y[g] - ry, pz = z[g] - rz;
      const float wx = wi * px, wy = wi * py, wz = wi * pz;
      lane[0][l] += r[g];
      lane[1][l] += wi;
      lane[2][l] += wx;
      lane[3][l] += wy;
      lane[4][l] += wz;
      lane[5][l] += wx * px;
      lane[6][l] += wx * py;
      lane[7][l] += wx * pz;
      lane[8][l] += wy * py;
      lane[9][l] += wy * pz;
      lane[10][l] += wz * pz;
    }
  }
  for (int m = 0; m < 11; ++m) {
    float s = 0.0f;
    for (float v : lane[m]) s += v;
    sums[m] += s;
  }
}

void RangeVariance(const Cloud& points, const Options& options, std::vector<float>* q) {
  q->assign(points.size(), 0.0f);
  if (!HasPointNoise(options.sensor, options.noise.range_noise)) return;
  for (size_t i = 0; i < points.size(); ++i) {
    (*q)[i] = PointNoiseVariance(options.sensor, options.noise.range_noise, points.x[i], points.y[i],
                                 points.z[i]);
  }
}

}  // namespace

RELPLANE_SIMD_CLONES void EStep(const Cloud& points, const std::vector<EmPlane>& planes,
                                const Options& options, Responsibilities* resp,
                                const std::vector<uint8_t>* refit) {
  const float outlier_density = options.noise.outlier_density;
  const int n = static_cast<int>(points.size());
  const int k = static_cast<int>(planes.size());
  if (refit == nullptr) RangeVariance(points, options, &resp->range_variance);
  const bool range_noise = HasPointNoise(options.sensor, options.noise.range_noise);
  const float* q = resp->range_variance.data();
  resp->num_points = n;
  resp->num_planes = k;
  resp->r.resize(static_cast<size_t>(k + 1) * n);
  resp->density.resize(static_cast<size_t>(k) * n);
  float* total = &resp->r[static_cast<size_t>(k) * n];  // the outlier row doubles as the sum
  std::fill(total, total + n, outlier_density);
  const float* __restrict x = points.x.data();
  const float* __restrict y = points.y.data();
  const float* __restrict z = points.z.data();
  const int32_t cutoff_bits = Bits(kCutoffSigmas * kCutoffSigmas);
  const float inv_sqrt_2pi = 1.0f / std::sqrt(2.0f * static_cast<float>(M_PI));
  // Each row is added to the total as it is computed (a frozen plane's kept row, after).
  for (int j = 0; j < k; ++j) {
    float* __restrict row = &resp->density[static_cast<size_t>(j) * n];
    if (refit != nullptr && !(*refit)[j]) {
      for (int i = 0; i < n; ++i) total[i] += row[i];
      continue;
    }
    const EmPlane& p = planes[j];
    const float nx = p.normal.x(), ny = p.normal.y(), nz = p.normal.z(), d = p.d;
    const float var_j = p.sigma * p.sigma;
    if (!range_noise) {
      const float inv_var = 1.0f / var_j;
      const float peak = inv_sqrt_2pi / std::sqrt(var_j);
      for (int i = 0; i < n; ++i) {
        const float dist = nx * x[i] + ny * y[i] + nz * z[i] + d;
        row[i] = Density(peak, dist * dist * inv_var, cutoff_bits);
        total[i] += row[i];
      }
    } else {
      for (int i = 0; i < n; ++i) {
        const float dist = nx * x[i] + ny * y[i] + nz * z[i] + d;
        const float inv_var = 1.0f / (var_j + q[i]);
        row[i] = Density(inv_sqrt_2pi * std::sqrt(inv_var), dist * dist * inv_var, cutoff_bits);
        total[i] += row[i];
      }
    }
  }
  for (int i = 0; i < n; ++i) total[i] = 1.0f / total[i];
  for (int j = 0; j < k; ++j) {
    const float* __restrict density = &resp->density[static_cast<size_t>(j) * n];
    float* __restrict row = &resp->r[static_cast<size_t>(j) * n];
    for (int i = 0; i < n; ++i) row[i] = density[i] * total[i];
  }
  for (int i = 0; i < n; ++i) total[i] *= outlier_density;
}

RELPLANE_SIMD_CLONES void MStep(const Cloud& points, const Responsibilities& resp,
                                const Options& options, std::vector<EmPlane>* planes,
                                const std::vector<uint8_t>* refit) {
  const int n = resp.num_points;
  const float* __restrict x = points.x.data();
  const float* __restrict y = points.y.data();
  const float* __restrict z = points.z.data();
  const float* __restrict q = resp.range_variance.data();
  for (int j = 0; j < resp.num_planes; ++j) {
    EmPlane& plane = (*planes)[j];
    const float* __restrict r = &resp.r[static_cast<size_t>(j) * n];
    if (refit != nullptr && !(*refit)[j]) {  // a converged plane: its support only
      const int whole = n / kLanes * kLanes;
      double support = Sum(r, whole);
      for (int i = whole; i < n; ++i) support += r[i];
      plane.support = static_cast<float>(support);
      continue;
    }
    const float var_j = plane.sigma * plane.sigma;
    // Moments about the previous centroid (close to the new one, so the sums stay well
    // conditioned): float sums over blocks of kBlock points (vectorised), in double across
    // blocks. The last block is padded to whole lanes with points that add nothing (no
    // responsibility, at the reference point).
    double sums[11] = {0, 0, 0, 0, 0, 0, 0, 0, 0, 0, 0};
    const int whole = n / kBlock * kBlock;
    for (int start = 0; start < whole; start += kBlock) {
      AddBlockMoments(r + start, q + start, x + start, y + start, z + start, kBlock, plane.centroid,
                      var_j, sums);
    }
    if (whole < n) {
      const int m = n - whole;
      const int padded = (m + kLanes - 1) / kLanes * kLanes;
      alignas(64) float rb[kBlock], qb[kBlock], xb[kBlock], yb[kBlock], zb[kBlock];
      for (int i = 0; i < padded; ++i) {
        const bool in = i < m;
        rb[i] = in ? r[whole + i] : 0.0f;
        qb[i] = in ? q[whole + i] : 0.0f;
        xb[i] = in ? x[whole + i] : plane.centroid.x();
        yb[i] = in ? y[whole + i] : plane.centroid.y();
        zb[i] = in ? z[whole + i] : plane.centroid.z();
      }
      AddBlockMoments(rb, qb, xb, yb, zb, padded, plane.centroid, var_j, sums);
    }
    const double support = sums[0], sw = sums[1];
    plane.support = static_cast<float>(support);
    if (sw < 3.0) continue;  // too little support to fit; pruning decides its fate
    const Eigen::Vector3d m(sums[2] / sw, sums[3] / sw, sums[4] / sw);
    Eigen::Matrix3d scatter;
    scatter << sums[5], sums[6], sums[7], sums[6], sums[8], sums[9], sums[7], sums[9], sums[10];
    scatter -= sw * m * m.transpose();
    const Eigen::Vector3d mean = plane.centroid.cast<double>() + m;
    Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
    eig.computeDirect(scatter);
    Eigen::Vector3d normal = eig.eigenvectors().col(0);
    if (normal.dot(plane.normal.cast<double>()) < 0.0) normal = -normal;
    plane.normal = normal.normalized().cast<float>();
    plane.d = static_cast<float>(-normal.dot(mean));
    plane.centroid = mean.cast<float>();
    // sum(w d^2) / sum(r) estimates sigma^2 once range noise is normalised out.
    const double variance = std::max(0.0, eig.eigenvalues()(0)) / support;
    plane.sigma = std::clamp(static_cast<float>(std::sqrt(variance)), options.noise.sigma_min,
                             options.noise.sigma_max);
  }
}

int RunEm(const Cloud& points, const Options& options, int max_iterations,
          std::vector<EmPlane>* planes, Responsibilities* resp) {
  // A plane that moved less than the convergence limits in one iteration is frozen for the rest
  // of the run: its density row is kept and it is not refitted, so the iterations that a few
  // slow planes still need cost only what those planes cost.
  std::vector<uint8_t> active(planes->size(), 1);
  int iteration = 0;
  bool first = true;
  while (iteration < max_iterations) {
    const std::vector<EmPlane> before = *planes;
    EStep(points, *planes, options, resp, first ? nullptr : &active);
    first = false;
    MStep(points, *resp, options, planes, &active);
    ++iteration;
    bool moved = false;
    for (size_t j = 0; j < planes->size(); ++j) {
      if (!active[j]) continue;
      // The sine from the cross product: acos of a float dot product cannot resolve angles
      // below about 3e-4 rad, so EM would never see itself converge.
      const float sin_angle = before[j].normal.cross((*planes)[j].normal).norm();
      active[j] = sin_angle > options.em.converged_angle ||
                  std::fabs(before[j].d - (*planes)[j].d) > options.em.converged_offset;
      moved = moved || active[j];
    }
    // Converged: the last E-step's responsibilities belong to planes that have since moved by
    // less than the limits, so they stand for the final planes.
    if (!moved) return iteration;
  }
  // Out of iterations: responsibilities of the planes as they are now.
  EStep(points, *planes, options, resp, first ? nullptr : &active);
  return iteration;
}

}  // namespace relplane::segmenter
