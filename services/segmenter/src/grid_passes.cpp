#include "grid_passes.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

#include "relplane/segmenter/spacing.hpp"
#include "simd.hpp"

#if defined(__GNUC__) && defined(__x86_64__)
#define RELPLANE_AVX2_LOOKUP 1
#include <immintrin.h>
#endif

namespace relplane::segmenter {
namespace {

constexpr size_t kChunk = 8;  // table entries per AVX2 register

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

int32_t ReachScalar(const Cell& c, const PlaneTable& t, const ReachRule& rule) {
  const size_t j = static_cast<size_t>(c.plane) + 1;
  const float* f[9];
  for (int k = 0; k < 9; ++k) f[k] = t.frame[k].data();
  const float sa = t.a_lo[j] + (c.ix + 0.5f) * t.cell[j];
  const float sb = t.b_lo[j] + (c.iy + 0.5f) * t.cell[j];
  // The cell's centre and its range, added in the order Eigen adds g.origin + sa g.u + sb g.v
  // and its norm (x x + (y y + z z)).
  const float cx = (f[0][j] + sa * f[3][j]) + sb * f[6][j];
  const float cy = (f[1][j] + sa * f[4][j]) + sb * f[7][j];
  const float cz = (f[2][j] + sa * f[5][j]) + sb * f[8][j];
  const float range = std::sqrt(cx * cx + (cy * cy + cz * cz));
  const float spacing = SampleSpacing(rule.angular_step, range, t.distance[j]);
  const float reach = std::min(rule.max_reach, rule.reach_spacings * spacing);
  // ceil of a non-negative float: the baseline x86-64 build has no rounding instruction and
  // would emulate std::ceil in several.
  const float cells = reach / t.cell[j];
  const int32_t whole = static_cast<int32_t>(cells);
  return std::max(rule.cell_reach, whole + (static_cast<float>(whole) < cells));
}

#if RELPLANE_AVX2_LOOKUP
// The table lookups of eight points at once: a table of up to 32 entries (4 chunks) sits in
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

// ReachScalar for eight cells at once, operation for operation.
template <size_t kChunks>
[[gnu::target("avx2")]] size_t ReachAvx2(const std::vector<Cell>& cells, const PlaneTable& t,
                                         const ReachRule& rule, int32_t* reach) {
  __m256 frame[9][kChunks], a_lo[kChunks], b_lo[kChunks], cell[kChunks], distance[kChunks];
  for (int f = 0; f < 9; ++f) LoadTable<kChunks>(t.frame[f], frame[f]);
  LoadTable<kChunks>(t.a_lo, a_lo);
  LoadTable<kChunks>(t.b_lo, b_lo);
  LoadTable<kChunks>(t.cell, cell);
  LoadTable<kChunks>(t.distance, distance);
  static_assert(sizeof(Cell) == 3 * sizeof(int32_t), "cells are read as int32 triples");
  const __m256i stride = _mm256_setr_epi32(0, 3, 6, 9, 12, 15, 18, 21);
  const __m256 half = _mm256_set1_ps(0.5f), zero = _mm256_setzero_ps();
  const __m256 one = _mm256_set1_ps(1.0f), min_cos = _mm256_set1_ps(kMinCosIncidence);
  const __m256 step = _mm256_set1_ps(rule.angular_step);
  const __m256 spacings = _mm256_set1_ps(rule.reach_spacings);
  const __m256 max_reach = _mm256_set1_ps(rule.max_reach);
  const __m256i cell_reach = _mm256_set1_epi32(rule.cell_reach);
  const __m256 sign = _mm256_set1_ps(-0.0f);
  size_t c = 0;
  for (; c + kChunk <= cells.size(); c += kChunk) {
    const int* first = &cells[c].plane;
    const __m256i j =
        _mm256_add_epi32(_mm256_i32gather_epi32(first, stride, 4), _mm256_set1_epi32(1));
    const __m256 ix = _mm256_cvtepi32_ps(_mm256_i32gather_epi32(first + 1, stride, 4));
    const __m256 iy = _mm256_cvtepi32_ps(_mm256_i32gather_epi32(first + 2, stride, 4));
    const Lookup<kChunks> at(j);
    const __m256 size = at.Pick(cell, j);
    const __m256 sa = _mm256_add_ps(at.Pick(a_lo, j), _mm256_mul_ps(_mm256_add_ps(ix, half), size));
    const __m256 sb = _mm256_add_ps(at.Pick(b_lo, j), _mm256_mul_ps(_mm256_add_ps(iy, half), size));
    __m256 centre[3];
    for (int k = 0; k < 3; ++k) {
      centre[k] = _mm256_add_ps(
          _mm256_add_ps(at.Pick(frame[k], j), _mm256_mul_ps(sa, at.Pick(frame[3 + k], j))),
          _mm256_mul_ps(sb, at.Pick(frame[6 + k], j)));
    }
    const __m256 range = _mm256_sqrt_ps(_mm256_add_ps(
        _mm256_mul_ps(centre[0], centre[0]),
        _mm256_add_ps(_mm256_mul_ps(centre[1], centre[1]), _mm256_mul_ps(centre[2], centre[2]))));
    // SampleSpacing: max and min in the operand order of std::max / std::min.
    const __m256 ratio = _mm256_div_ps(_mm256_andnot_ps(sign, at.Pick(distance, j)), range);
    const __m256 cos_incidence = _mm256_max_ps(
        _mm256_blendv_ps(one, ratio, _mm256_cmp_ps(range, zero, _CMP_GT_OQ)), min_cos);
    const __m256 spacing =
        _mm256_div_ps(_mm256_mul_ps(step, range), _mm256_min_ps(cos_incidence, one));
    const __m256 metres = _mm256_min_ps(_mm256_mul_ps(spacings, spacing), max_reach);
    const __m256 whole_cells = _mm256_div_ps(metres, size);
    const __m256i whole = _mm256_cvttps_epi32(whole_cells);
    const __m256i up =
        _mm256_castps_si256(_mm256_cmp_ps(_mm256_cvtepi32_ps(whole), whole_cells, _CMP_LT_OQ));
    _mm256_storeu_si256(reinterpret_cast<__m256i*>(reach + c),
                        _mm256_max_epi32(cell_reach, _mm256_sub_epi32(whole, up)));
  }
  return c;
}

// Runs kernel(chunks) with the table's chunks as a compile-time constant when the CPU has AVX2
// and the table fits in registers; returns how many items it did (0: none, the scalar pass
// does them all).
template <typename Kernel>
size_t OnAvx2(const PlaneTable& t, Kernel&& kernel) {
  if (!__builtin_cpu_supports("avx2")) return 0;
  switch (t.base.size() / kChunk) {
    case 1:
      return kernel(std::integral_constant<size_t, 1>{});
    case 2:
      return kernel(std::integral_constant<size_t, 2>{});
    case 3:
      return kernel(std::integral_constant<size_t, 3>{});
    case 4:
      return kernel(std::integral_constant<size_t, 4>{});
    default:
      return 0;
  }
}
#endif

}  // namespace

void PlaneTable::Reset(size_t planes) {
  const size_t size = (planes + 1 + kChunk - 1) / kChunk * kChunk;
  for (std::vector<float>& v : frame) v.assign(size, 0.0f);
  for (std::vector<float>* v : {&a_lo, &b_lo, &inv_cell, &cell, &distance}) v->assign(size, 0.0f);
  for (std::vector<int32_t>* v : {&w1, &h1, &w}) v->assign(size, 0);
  base.assign(size, -1);
}

void CellReach(const std::vector<Cell>& cells, const PlaneTable& table, const ReachRule& rule,
               int32_t* reach) {
#if RELPLANE_AVX2_LOOKUP
  const size_t done = OnAvx2(table, [&](auto chunks) {
    return ReachAvx2<decltype(chunks)::value>(cells, table, rule, reach);
  });
#else
  const size_t done = 0;
#endif
  for (size_t c = done; c < cells.size(); ++c) reach[c] = ReachScalar(cells[c], table, rule);
}

void ProjectToGrids(size_t n, const float* x, const float* y, const float* z, const int32_t* label,
                    const PlaneTable& table, float* a, float* b, float* e) {
#if RELPLANE_AVX2_LOOKUP
  const size_t done = OnAvx2(table, [&](auto chunks) {
    return ProjectAvx2<decltype(chunks)::value>(n, x, y, z, label, table, a, b, e);
  });
#else
  const size_t done = 0;
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
#if RELPLANE_AVX2_LOOKUP
  const size_t done = OnAvx2(table, [&](auto chunks) {
    return SlotsAvx2<decltype(chunks)::value>(n, label, a, b, table, slot);
  });
#else
  const size_t done = 0;
#endif
  SlotsScalar(done, n, label, a, b, table, slot);
}

}  // namespace relplane::segmenter
