#include "relplane/segmenter/assign.hpp"

#include <algorithm>
#include <cmath>
#include <vector>

#include "simd.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#define RELPLANE_AVX2_AMBIGUOUS 1
#include <immintrin.h>
#endif

namespace relplane::segmenter {
namespace {

// Points are ranked in groups of kGroup: a group's best and second-best scores and planes stay
// in registers while every plane is scored against it.
constexpr size_t kGroup = 8;

// Up to this many planes, a plane's crossing planes fit in the bits of one word.
constexpr size_t kMaskBits = 32;

struct PlaneScore {
  float nx, ny, nz, d;
  float var;  // sigma^2
  float inv;  // 1 / (t^2 sigma^2)
};

// Scores kGroup points against every plane and keeps the best and second-best plane per point.
// A score is the squared distance in units of the point's threshold. Masks and min/max instead
// of branches so the loop over the group vectorises (best <= second always holds). Inlined, so
// it is built for each clone of AssignPoints.
template <bool kRangeNoise>
[[gnu::always_inline]] inline void RankGroup(const float* __restrict x, const float* __restrict y,
                                             const float* __restrict z, const float* __restrict q,
                                             const PlaneScore* planes, size_t k, float t2,
                                             int32_t* __restrict label,
                                             int32_t* __restrict second_label) {
  float b[kGroup], s2[kGroup];
  int32_t l[kGroup], l2[kGroup];
  for (size_t i = 0; i < kGroup; ++i) {
    b[i] = 1.0f;
    s2[i] = 1.0f;
    l[i] = -1;
    l2[i] = -1;
  }
  for (size_t j = 0; j < k; ++j) {
    const PlaneScore p = planes[j];
    const int32_t id = static_cast<int32_t>(j);
    for (size_t i = 0; i < kGroup; ++i) {
      const float s = p.nx * x[i] + p.ny * y[i] + p.nz * z[i] + p.d;
      const float sc = kRangeNoise ? s * s / (t2 * (p.var + q[i])) : s * s * p.inv;
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
  for (size_t i = 0; i < kGroup; ++i) {
    label[i] = l[i];
    second_label[i] = l2[i];
  }
}

#if RELPLANE_AVX2_AMBIGUOUS
// The bit lookups of AssignPoints eight points at once: a gather of their planes' rows, the
// same shift and mask, the results packed to bytes. Returns how many points it did.
[[gnu::target("avx2")]] size_t AmbiguousAvx2(size_t n, const int32_t* label, const int32_t* other,
                                             const uint32_t* row, uint8_t* amb) {
  const __m256i one = _mm256_set1_epi32(1), five_bits = _mm256_set1_epi32(31);
  const __m256i minus_one = _mm256_set1_epi32(-1);
  const int* rows = reinterpret_cast<const int*>(row);
  size_t i = 0;
  for (; i + 8 <= n; i += 8) {
    const __m256i j =
        _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(label + i)), one);
    const __m256i o = _mm256_loadu_si256(reinterpret_cast<const __m256i*>(other + i));
    const __m256i bits =
        _mm256_srlv_epi32(_mm256_i32gather_epi32(rows, j, 4), _mm256_and_si256(o, five_bits));
    const __m256i has_other = _mm256_cmpgt_epi32(o, minus_one);  // all ones where o >= 0
    const __m256i v = _mm256_and_si256(_mm256_and_si256(bits, one), has_other);
    const __m128i words =
        _mm_packs_epi32(_mm256_castsi256_si128(v), _mm256_extracti128_si256(v, 1));
    _mm_storel_epi64(reinterpret_cast<__m128i*>(amb + i), _mm_packus_epi16(words, words));
  }
  return i;
}
#endif

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
  const float cos_crossing =
      std::cos(options.assignment.crossing_angle_deg * static_cast<float>(M_PI) / 180.0f);
  std::vector<uint8_t> crossing(k * k);
  for (size_t a = 0; a < k; ++a) {
    for (size_t b = 0; b < k; ++b) {
      crossing[a * k + b] = std::fabs(planes[a].normal.dot(planes[b].normal)) < cos_crossing;
    }
  }
  // Scores are squared distances in units of the point's threshold,
  // d^2 / (t^2 (sigma^2 + (k r^2)^2)): below 1 is an inlier, the smallest wins.
  const float t2 = options.assignment.inlier_sigmas * options.assignment.inlier_sigmas;
  const bool point_noise = HasPointNoise(options.sensor, options.noise.range_noise);
  std::vector<PlaneScore> scores(k);
  for (size_t j = 0; j < k; ++j) {
    const EmPlane& p = planes[j];
    const float var = p.sigma * p.sigma;
    scores[j] = PlaneScore{p.normal.x(), p.normal.y(), p.normal.z(), p.d, var, 1.0f / (t2 * var)};
  }
  std::vector<int32_t> second(n);
  alignas(64) float q[kGroup] = {};
  alignas(64) float px[kGroup], py[kGroup], pz[kGroup];
  alignas(64) int32_t pl[kGroup], pl2[kGroup];
  for (size_t start = 0; start < n; start += kGroup) {
    const size_t m = std::min(kGroup, n - start);
    const float* x = cloud.x.data() + start;
    const float* y = cloud.y.data() + start;
    const float* z = cloud.z.data() + start;
    int32_t* l = labels->data() + start;
    int32_t* l2 = second.data() + start;
    if (m < kGroup) {  // the last points, padded to a whole group
      for (size_t i = 0; i < kGroup; ++i) {
        px[i] = i < m ? x[i] : 0.0f;
        py[i] = i < m ? y[i] : 0.0f;
        pz[i] = i < m ? z[i] : 0.0f;
      }
      x = px;
      y = py;
      z = pz;
      l = pl;
      l2 = pl2;
    }
    if (point_noise) {
      for (size_t i = 0; i < kGroup; ++i) {
        q[i] = PointNoiseVariance(options.sensor, options.noise.range_noise, x[i], y[i], z[i]);
      }
      RankGroup<true>(x, y, z, q, scores.data(), k, t2, l, l2);
    } else {
      RankGroup<false>(x, y, z, q, scores.data(), k, t2, l, l2);
    }
    if (m < kGroup) {
      std::copy(pl, pl + m, labels->data() + start);
      std::copy(pl2, pl2 + m, second.data() + start);
    }
  }
  if (!ambiguous) return;
  uint8_t* __restrict amb = ambiguous->data();
  const int32_t* __restrict label = labels->data();
  const int32_t* __restrict other = second.data();
  if (k < kMaskBits) {
    // Each plane's row of `crossing` as bits, entry 0 for unlabelled points: a point is then a
    // lookup, a shift and a mask, without a branch (the loop vectorises).
    std::vector<uint32_t> rows(k + 1, 0);
    for (size_t a = 0; a < k; ++a) {
      for (size_t b = 0; b < k; ++b) rows[a + 1] |= static_cast<uint32_t>(crossing[a * k + b]) << b;
    }
    const uint32_t* __restrict row = rows.data();
#if RELPLANE_AVX2_AMBIGUOUS
    const size_t done =
        __builtin_cpu_supports("avx2") ? AmbiguousAvx2(n, label, other, row, amb) : 0;
#else
    const size_t done = 0;
#endif
    for (size_t i = done; i < n; ++i) {
      // other is -1 (no second plane) or below k: shifting by (other & 31) is in range, and the
      // mask clears the -1 case.
      const uint32_t bits = row[label[i] + 1] >> (other[i] & 31);
      amb[i] = static_cast<uint8_t>(bits & static_cast<uint32_t>(other[i] >= 0));
    }
    return;
  }
  for (size_t i = 0; i < n; ++i) {
    amb[i] = label[i] >= 0 && other[i] >= 0 && crossing[label[i] * k + other[i]];
  }
}

}  // namespace relplane::segmenter
