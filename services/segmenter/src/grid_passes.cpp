#include "grid_passes.hpp"

#include <algorithm>

#include "simd.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#define RELPLANE_AVX2_LOOKUP 1
#include <immintrin.h>
#endif

namespace relplane::segmenter {
namespace {

constexpr size_t kChunk = 8;      // table entries per AVX2 register
constexpr size_t kMaxChunks = 4;  // tables of up to 32 entries are looked up in registers

// The scalar passes: the fallback, and the last points after whole blocks of kChunk.
void ProjectScalar(size_t begin, size_t n, const float* __restrict x, const float* __restrict y,
                   const float* __restrict z, const int32_t* __restrict label, const PlaneTable& t,
                   float* __restrict a, float* __restrict b, float* __restrict e) {
  const std::vector<float>* f = t.frame;
  for (size_t i = begin; i < n; ++i) {
    const int32_t j = label[i] + 1;
    const float qx = x[i] - f[0][j], qy = y[i] - f[1][j], qz = z[i] - f[2][j];
    a[i] = f[3][j] * qx + f[4][j] * qy + f[5][j] * qz;
    b[i] = f[6][j] * qx + f[7][j] * qy + f[8][j] * qz;
    e[i] = f[9][j] * qx + f[10][j] * qy + f[11][j] * qz;
  }
}

void SlotsScalar(size_t begin, size_t n, const int32_t* __restrict label, const float* __restrict a,
                 const float* __restrict b, const PlaneTable& t, int32_t* __restrict slot) {
  for (size_t i = begin; i < n; ++i) {
    const int32_t j = label[i] + 1;
    const int32_t ix = std::min(static_cast<int32_t>((a[i] - t.a_lo[j]) * t.inv_cell[j]), t.w1[j]);
    const int32_t iy = std::min(static_cast<int32_t>((b[i] - t.b_lo[j]) * t.inv_cell[j]), t.h1[j]);
    // base is -1 without a grid: its sign bits make the slot -1 (a mask, not a branch).
    slot[i] = (t.base[j] + iy * t.w[j] + ix) | (t.base[j] >> 31);
  }
}

#if RELPLANE_AVX2_LOOKUP
// The table lookups of eight points at once: a table of up to kMaxChunks * 8 entries sits in
// registers and each point's entry is picked by a permute (vpermps takes the index's low three
// bits) from every chunk, then blended by the chunk the index falls in. Gathers from memory
// would cost several times as much. The arithmetic is the scalar passes', operation for
// operation (no FMA), so the results are the same bits.
template <size_t kChunks>
struct Lookup {
  __m256 in_chunk[kChunks];  // per chunk c > 0: all ones where the index is in chunk c

  [[gnu::target("avx2")]] explicit Lookup(__m256i j) {
    for (size_t c = 1; c < kChunks; ++c) {
      const __m256i first = _mm256_set1_epi32(static_cast<int32_t>(c * kChunk) - 1);
      in_chunk[c] = _mm256_castsi256_ps(_mm256_cmpgt_epi32(j, first));
    }
  }
  [[gnu::target("avx2")]] __m256 Pick(const __m256 (&table)[kChunks], __m256i j) const {
    __m256 v = _mm256_permutevar8x32_ps(table[0], j);
    for (size_t c = 1; c < kChunks; ++c) {
      v = _mm256_blendv_ps(v, _mm256_permutevar8x32_ps(table[c], j), in_chunk[c]);
    }
    return v;
  }
  [[gnu::target("avx2")]] __m256i Pick(const __m256 (&table)[kChunks], __m256i j, int) const {
    return _mm256_castps_si256(Pick(table, j));
  }
};

template <size_t kChunks, typename T>
[[gnu::target("avx2")]] void LoadTable(const std::vector<T>& v, __m256 (&table)[kChunks]) {
  for (size_t c = 0; c < kChunks; ++c) {
    table[c] = _mm256_loadu_ps(reinterpret_cast<const float*>(v.data() + c * kChunk));
  }
}

// The table entries of eight points: their labels plus one.
[[gnu::target("avx2")]] inline __m256i Entries(const int32_t* label) {
  return _mm256_add_epi32(_mm256_loadu_si256(reinterpret_cast<const __m256i*>(label)),
                          _mm256_set1_epi32(1));
}

// (fx qx + fy qy) + fz qz, as the scalar pass adds them.
[[gnu::target("avx2")]] inline __m256 Dot(__m256 fx, __m256 fy, __m256 fz, __m256 qx, __m256 qy,
                                          __m256 qz) {
  return _mm256_add_ps(_mm256_add_ps(_mm256_mul_ps(fx, qx), _mm256_mul_ps(fy, qy)),
                       _mm256_mul_ps(fz, qz));
}

template <size_t kChunks>
[[gnu::target("avx2")]] size_t ProjectAvx2(size_t n, const float* x, const float* y, const float* z,
                                           const int32_t* label, const PlaneTable& t, float* a,
                                           float* b, float* e) {
  __m256 table[12][kChunks];
  for (int f = 0; f < 12; ++f) LoadTable<kChunks>(t.frame[f], table[f]);
  size_t i = 0;
  for (; i + kChunk <= n; i += kChunk) {
    const __m256i j = Entries(label + i);
    const Lookup<kChunks> at(j);
    const __m256 qx = _mm256_sub_ps(_mm256_loadu_ps(x + i), at.Pick(table[0], j));
    const __m256 qy = _mm256_sub_ps(_mm256_loadu_ps(y + i), at.Pick(table[1], j));
    const __m256 qz = _mm256_sub_ps(_mm256_loadu_ps(z + i), at.Pick(table[2], j));
    _mm256_storeu_ps(
        a + i, Dot(at.Pick(table[3], j), at.Pick(table[4], j), at.Pick(table[5], j), qx, qy, qz));
    _mm256_storeu_ps(
        b + i, Dot(at.Pick(table[6], j), at.Pick(table[7], j), at.Pick(table[8], j), qx, qy, qz));
    _mm256_storeu_ps(
        e + i, Dot(at.Pick(table[9], j), at.Pick(table[10], j), at.Pick(table[11], j), qx, qy, qz));
  }
  return i;
}

template <size_t kChunks>
[[gnu::target("avx2")]] size_t SlotsAvx2(size_t n, const int32_t* label, const float* a,
                                         const float* b, const PlaneTable& t, int32_t* slot) {
  __m256 a_lo[kChunks], b_lo[kChunks], inv_cell[kChunks];
  __m256 w1[kChunks], h1[kChunks], w[kChunks], base[kChunks];
  LoadTable<kChunks>(t.a_lo, a_lo);
  LoadTable<kChunks>(t.b_lo, b_lo);
  LoadTable<kChunks>(t.inv_cell, inv_cell);
  LoadTable<kChunks>(t.w1, w1);
  LoadTable<kChunks>(t.h1, h1);
  LoadTable<kChunks>(t.w, w);
  LoadTable<kChunks>(t.base, base);
  size_t i = 0;
  for (; i + kChunk <= n; i += kChunk) {
    const __m256i j = Entries(label + i);
    const Lookup<kChunks> at(j);
    const __m256 inv = at.Pick(inv_cell, j);
    const __m256i fx = _mm256_cvttps_epi32(
        _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(a + i), at.Pick(a_lo, j)), inv));
    const __m256i fy = _mm256_cvttps_epi32(
        _mm256_mul_ps(_mm256_sub_ps(_mm256_loadu_ps(b + i), at.Pick(b_lo, j)), inv));
    const __m256i ix = _mm256_min_epi32(fx, at.Pick(w1, j, 0));
    const __m256i iy = _mm256_min_epi32(fy, at.Pick(h1, j, 0));
    const __m256i g = at.Pick(base, j, 0);
    const __m256i s =
        _mm256_add_epi32(_mm256_add_epi32(g, _mm256_mullo_epi32(iy, at.Pick(w, j, 0))), ix);
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(slot + i),
                        _mm256_or_si256(s, _mm256_srai_epi32(g, 31)));
  }
  return i;
}

// Chunks of the table in registers, 0 when the lookups cannot run there.
size_t Avx2Chunks(const PlaneTable& t) {
  const size_t chunks = t.base.size() / kChunk;
  return chunks <= kMaxChunks && __builtin_cpu_supports("avx2") ? chunks : 0;
}
#endif

}  // namespace

void PlaneTable::Reset(size_t planes) {
  const size_t size = (planes + 1 + kChunk - 1) / kChunk * kChunk;
  for (std::vector<float>& v : frame) v.assign(size, 0.0f);
  for (std::vector<float>* v : {&a_lo, &b_lo, &inv_cell}) v->assign(size, 0.0f);
  for (std::vector<int32_t>* v : {&w1, &h1, &w}) v->assign(size, 0);
  base.assign(size, -1);
}

void ProjectToGrids(size_t n, const float* x, const float* y, const float* z, const int32_t* label,
                    const PlaneTable& table, float* a, float* b, float* e) {
  size_t done = 0;
#if RELPLANE_AVX2_LOOKUP
  switch (Avx2Chunks(table)) {
    case 1:
      done = ProjectAvx2<1>(n, x, y, z, label, table, a, b, e);
      break;
    case 2:
      done = ProjectAvx2<2>(n, x, y, z, label, table, a, b, e);
      break;
    case 3:
      done = ProjectAvx2<3>(n, x, y, z, label, table, a, b, e);
      break;
    case 4:
      done = ProjectAvx2<4>(n, x, y, z, label, table, a, b, e);
      break;
    default:
      break;
  }
#endif
  ProjectScalar(done, n, x, y, z, label, table, a, b, e);
}

// One pass per plane over the whole cloud, in kLanes independent lanes so it vectorises: min
// and max are exact, so the bounds are those of any order.
RELPLANE_SIMD_CLONES GridBounds PlaneBounds(size_t n, const int32_t* __restrict label,
                                            int32_t plane, const float* __restrict a,
                                            const float* __restrict b) {
  constexpr size_t kLanes = 8;
  constexpr float kInf = std::numeric_limits<float>::infinity();
  float a_lo[kLanes], a_hi[kLanes], b_lo[kLanes], b_hi[kLanes];
  int32_t count[kLanes];
  for (size_t l = 0; l < kLanes; ++l) {
    a_lo[l] = b_lo[l] = kInf;
    a_hi[l] = b_hi[l] = -kInf;
    count[l] = 0;
  }
  const size_t whole = n / kLanes * kLanes;
  for (size_t i = 0; i < whole; i += kLanes) {
    for (size_t l = 0; l < kLanes; ++l) {
      // Selects on locals: std::min on the lanes' references would compile to masked stores.
      const bool in = label[i + l] == plane;
      const float pa = a[i + l], pb = b[i + l];
      const float lo_a = in ? pa : kInf, hi_a = in ? pa : -kInf;
      const float lo_b = in ? pb : kInf, hi_b = in ? pb : -kInf;
      count[l] += in;
      a_lo[l] = lo_a < a_lo[l] ? lo_a : a_lo[l];
      a_hi[l] = a_hi[l] < hi_a ? hi_a : a_hi[l];
      b_lo[l] = lo_b < b_lo[l] ? lo_b : b_lo[l];
      b_hi[l] = b_hi[l] < hi_b ? hi_b : b_hi[l];
    }
  }
  for (size_t i = whole; i < n; ++i) {
    if (label[i] != plane) continue;
    ++count[0];
    a_lo[0] = std::min(a_lo[0], a[i]);
    a_hi[0] = std::max(a_hi[0], a[i]);
    b_lo[0] = std::min(b_lo[0], b[i]);
    b_hi[0] = std::max(b_hi[0], b[i]);
  }
  GridBounds g;
  for (size_t l = 0; l < kLanes; ++l) {
    g.points += count[l];
    g.a_lo = std::min(g.a_lo, a_lo[l]);
    g.a_hi = std::max(g.a_hi, a_hi[l]);
    g.b_lo = std::min(g.b_lo, b_lo[l]);
    g.b_hi = std::max(g.b_hi, b_hi[l]);
  }
  return g;
}

void GridSlots(size_t n, const int32_t* label, const float* a, const float* b,
               const PlaneTable& table, int32_t* slot) {
  size_t done = 0;
#if RELPLANE_AVX2_LOOKUP
  switch (Avx2Chunks(table)) {
    case 1:
      done = SlotsAvx2<1>(n, label, a, b, table, slot);
      break;
    case 2:
      done = SlotsAvx2<2>(n, label, a, b, table, slot);
      break;
    case 3:
      done = SlotsAvx2<3>(n, label, a, b, table, slot);
      break;
    case 4:
      done = SlotsAvx2<4>(n, label, a, b, table, slot);
      break;
    default:
      break;
  }
#endif
  SlotsScalar(done, n, label, a, b, table, slot);
}

}  // namespace relplane::segmenter
