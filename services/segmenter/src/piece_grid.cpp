#include "piece_grid.hpp"

#include <algorithm>
#include <cmath>

#if defined(__SSE2__)
#include <immintrin.h>
#endif

namespace relplane::segmenter {
namespace {

int32_t Find(std::vector<int32_t>* parent, int32_t c) {
  std::vector<int32_t>& p = *parent;
  while (p[c] != c) {
    p[c] = p[p[c]];  // path halving
    c = p[c];
  }
  return c;
}

// A cell's moments of the `count` points order[0..count) about the first of them, as
// LocalMoments::Add takes them one by one, and the range of their distances e to the EM plane.
// With SSE a point's x, y, z, e sit in one register: its sums, squares and cross products
// (x y, y z, z x) are three lanes of one operation each, the same floats added in the same
// order, and e's lane keeps the minimum and maximum.
void SumCell(const float* x, const float* y, const float* z, const float* e, const int32_t* order,
             int32_t count, CellMoments* m) {
  LocalMoments& all = m->all;
  all = LocalMoments{};
  all.ref = Eigen::Vector3f(x[order[0]], y[order[0]], z[order[0]]);
#if defined(__SSE2__)
  const __m128 ref = _mm_setr_ps(all.ref.x(), all.ref.y(), all.ref.z(), 0.0f);
  __m128 sum = _mm_setzero_ps(), square = _mm_setzero_ps(), cross = _mm_setzero_ps();
  __m128 lo = _mm_set1_ps(kInf), hi = _mm_set1_ps(-kInf);
  for (int32_t k = 0; k < count; ++k) {
    const int32_t i = order[k];
    const __m128 p = _mm_setr_ps(x[i], y[i], z[i], e[i]);
    const __m128 q = _mm_sub_ps(p, ref);
    sum = _mm_add_ps(sum, q);
    square = _mm_add_ps(square, _mm_mul_ps(q, q));
    cross = _mm_add_ps(cross, _mm_mul_ps(q, _mm_shuffle_ps(q, q, _MM_SHUFFLE(3, 0, 2, 1))));
    lo = _mm_min_ps(p, lo);  // p < lo ? p : lo, as std::min(lo, p)
    hi = _mm_max_ps(p, hi);  // p > hi ? p : hi, as std::max(hi, p)
  }
  alignas(16) float s[4], sq[4], c[4], l[4], h[4];
  _mm_store_ps(s, sum);
  _mm_store_ps(sq, square);
  _mm_store_ps(c, cross);
  _mm_store_ps(l, lo);
  _mm_store_ps(h, hi);
  all.n = count;
  all.sx = s[0];
  all.sy = s[1];
  all.sz = s[2];
  all.sxx = sq[0];
  all.syy = sq[1];
  all.szz = sq[2];
  all.sxy = c[0];
  all.syz = c[1];
  all.sxz = c[2];
  m->e_lo = l[3];
  m->e_hi = h[3];
#else
  float e_lo = kInf, e_hi = -kInf;
  for (int32_t k = 0; k < count; ++k) {
    const int32_t i = order[k];
    all.AddAboutRef(Eigen::Vector3f(x[i], y[i], z[i]));
    e_lo = std::min(e_lo, e[i]);
    e_hi = std::max(e_hi, e[i]);
  }
  m->e_lo = e_lo;
  m->e_hi = e_hi;
#endif
}

}  // namespace

void PlaneAxes(const Eigen::Vector3f& n, bool vertical, Eigen::Vector3f* u, Eigen::Vector3f* v) {
  if (vertical) {
    *u = Eigen::Vector3f::UnitZ().cross(n);
  } else {
    *u = (std::fabs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY()).cross(n);
  }
  u->normalize();
  *v = n.cross(*u);
}

size_t FitStride(size_t n, const Options& options) {
  const size_t most = static_cast<size_t>(std::max(1, options.description.fit_points_max));
  return std::max<size_t>(1, (n + most - 1) / most);
}

void BinPoints(const Cloud& cloud, const std::vector<int32_t>& labels,
               const std::vector<uint8_t>& ambiguous, const std::vector<EmPlane>& planes,
               const Options& options, PieceWorkspace::Buffers* w) {
  const size_t n = cloud.size();
  const float* x = cloud.x.data();
  const float* y = cloud.y.data();
  const float* z = cloud.z.data();
  w->grids.assign(planes.size(), PlaneGrid{});
  for (size_t j = 0; j < planes.size(); ++j) {
    PlaneGrid& g = w->grids[j];
    g.origin = planes[j].centroid;
    g.n = planes[j].normal;
    PlaneAxes(planes[j].normal, std::fabs(planes[j].normal.z()) < options.extents.vertical_max_nz,
              &g.u, &g.v);
  }
  // Each point's coordinates in its plane's grid, then each plane's bounds and point count.
  const size_t k = planes.size();
  PlaneTable& table = w->table;
  table.Reset(k);
  for (size_t j = 0; j < k; ++j) {
    const PlaneGrid& g = w->grids[j];
    for (int c = 0; c < 3; ++c) {
      table.frame[c][j + 1] = g.origin[c];
      table.frame[3 + c][j + 1] = g.u[c];
      table.frame[6 + c][j + 1] = g.v[c];
      table.frame[9 + c][j + 1] = g.n[c];
    }
  }
  w->a.resize(n);
  w->b.resize(n);
  w->e.resize(n);
  ProjectToGrids(n, x, y, z, labels.data(), table, w->a.data(), w->b.data(), w->e.data());
  for (size_t j = 0; j < k; ++j) {
    const GridBounds bounds =
        PlaneBounds(n, labels.data(), static_cast<int32_t>(j), w->a.data(), w->b.data());
    PlaneGrid& g = w->grids[j];
    g.points = bounds.points;
    g.a_lo = bounds.a_lo;
    g.a_hi = bounds.a_hi;
    g.b_lo = bounds.b_lo;
    g.b_hi = bounds.b_hi;
  }
  size_t slots = 0;
  for (PlaneGrid& g : w->grids) {
    g.used = g.points >= options.extents.min_points;
    if (!g.used) continue;
    g.cell = options.extents.cell_size;
    for (;;) {  // coarsen until the grid fits: a bounded cost whatever the plane's extent
      const int64_t gw = static_cast<int64_t>((g.a_hi - g.a_lo) / g.cell) + 1;
      const int64_t gh = static_cast<int64_t>((g.b_hi - g.b_lo) / g.cell) + 1;
      if (gw * gh <= options.extents.max_cells) {
        g.w = static_cast<int>(gw);
        g.h = static_cast<int>(gh);
        break;
      }
      g.cell *= 2.0f;
    }
    g.inv_cell = 1.0f / g.cell;
    g.base = slots;
    slots += static_cast<size_t>(g.w) * g.h;
  }
  w->slot_of.assign(slots, -1);
  w->cells.clear();
  w->cell_of_point.resize(n);
  // Each point's slot in its plane's grid (-1 for none), held in cell_of_point for the pass
  // below.
  for (size_t j = 0; j < k; ++j) {
    const PlaneGrid& g = w->grids[j];
    if (!g.used) continue;
    table.a_lo[j + 1] = g.a_lo;
    table.b_lo[j + 1] = g.b_lo;
    table.inv_cell[j + 1] = g.inv_cell;
    table.w1[j + 1] = g.w - 1;
    table.h1[j + 1] = g.h - 1;
    table.w[j + 1] = g.w;
    table.base[j + 1] = static_cast<int32_t>(g.base);
  }
  GridSlots(n, labels.data(), w->a.data(), w->b.data(), table, w->cell_of_point.data());
  int32_t* __restrict cell_of = w->cell_of_point.data();
  const int32_t* __restrict label = labels.data();
  // Slots become cells, numbered in order of first appearance, and each cell counts its points.
  // Apart from the pass above, so the slots' loads do not wait on the arithmetic, and counted
  // per lane (point index mod kLanes): consecutive points of one cell then add to different
  // counters instead of each waiting on the last one's store.
  constexpr size_t kLanes = 4;
  int32_t* __restrict slot_of = w->slot_of.data();
  // At most one cell per point: sized once, a new cell's counters are zeroed as it appears.
  std::vector<int32_t>& lane_count = w->lane_count;
  if (lane_count.size() < n * kLanes) lane_count.resize(n * kLanes);
  for (size_t i = 0; i < n; ++i) {
    const int32_t s = cell_of[i];
    if (s < 0) continue;
    int32_t& slot = slot_of[s];
    if (slot < 0) {
      slot = static_cast<int32_t>(w->cells.size());
      const int32_t l = label[i];
      const int32_t at = s - table.base[l + 1];
      w->cells.push_back(Cell{l, at % table.w[l + 1], at / table.w[l + 1]});
      std::fill_n(&lane_count[static_cast<size_t>(slot) * kLanes], kLanes, 0);
    }
    const int32_t c = slot;
    cell_of[i] = c;
    ++lane_count[static_cast<size_t>(c) * kLanes + (i & (kLanes - 1))];
  }
  const size_t num_cells = w->cells.size();
  w->counts.resize(num_cells);
  for (size_t c = 0; c < num_cells; ++c) {
    const int32_t* lanes = &lane_count[c * kLanes];
    w->counts[c] = CellCount{lanes[0] + lanes[1] + lanes[2] + lanes[3], 0};
  }
  const bool all_solid = ambiguous.empty();
  const uint8_t* amb = all_solid ? nullptr : ambiguous.data();
  const size_t stride = FitStride(n, options);
  std::vector<int32_t>& fit_start = w->fit_start;
  fit_start.clear();
  if (stride == 1) {
    for (const CellCount& count : w->counts) fit_start.push_back(count.count);
  } else {
    fit_start.assign(num_cells, 0);
    for (size_t i = 0; i < n; i += stride) {
      if (cell_of[i] >= 0) ++fit_start[cell_of[i]];
    }
  }
  // Fourth pass: the fitted points grouped by cell (a counting sort, cloud order kept within a
  // cell), then each cell's moments accumulated in registers: the same sums, in the same order,
  // as adding the points in cloud order.
  int32_t total = 0;
  for (size_t c = 0; c < num_cells; ++c) {
    const int32_t m = fit_start[c];
    fit_start[c] = total;
    total += m;
  }
  fit_start.push_back(total);
  std::vector<int32_t>& order = w->fit_order;
  order.resize(total);
  {
    // The next free place of each cell. While consecutive points share a cell, its place is
    // carried in a register (`run_at`) and written back when the run ends, so a run's points do
    // not each wait on the last one's store; a run's points load a dummy instead of their
    // cell's place, without a branch.
    std::vector<int32_t>& next = w->parent;  // scratch
    next.assign(fit_start.begin(), fit_start.end());
    const int32_t dummy = static_cast<int32_t>(num_cells);  // next's last entry, never a cell
    int32_t run_cell = dummy, run_at = total;
    int32_t* __restrict at = next.data();
    int32_t* __restrict out = order.data();
    for (size_t i = 0; i < n; i += stride) {
      const int32_t c = cell_of[i];
      if (c < 0) continue;
      const bool same = c == run_cell;
      at[run_cell] = run_at;
      const int32_t loaded = at[same ? dummy : c];
      const int32_t place = same ? run_at : loaded;
      out[place] = static_cast<int32_t>(i);
      run_at = place + 1;
      run_cell = c;
    }
  }
  // Whether each cell holds a solid point. With every point fitted they are grouped by cell,
  // and the search stops at the first solid one (nearly always the cell's first point).
  if (all_solid) {
    for (CellCount& count : w->counts) count.solid = 1;
  } else if (stride == 1) {
    for (size_t c = 0; c < num_cells; ++c) {
      int32_t k = fit_start[c];
      while (k < fit_start[c + 1] && amb[order[k]]) ++k;
      w->counts[c].solid = k < fit_start[c + 1];
    }
  } else {
    for (size_t i = 0; i < n; ++i) {
      if (cell_of[i] >= 0 && !amb[i]) w->counts[cell_of[i]].solid = 1;
    }
  }
  w->moments.resize(num_cells);
  const float* __restrict pe = w->e.data();
  for (size_t c = 0; c < num_cells; ++c) {
    CellMoments& m = w->moments[c];
    const int32_t begin = fit_start[c], end = fit_start[c + 1];
    if (begin == end) {
      m = CellMoments{};
      continue;
    }
    SumCell(x, y, z, pe, order.data() + begin, end - begin, &m);
  }
}

int LabelPieces(const std::vector<EmPlane>& planes, const Options& options, float angular_step,
                PieceWorkspace::Buffers* w) {
  const std::vector<Cell>& cells = w->cells;
  const int32_t num_cells = static_cast<int32_t>(cells.size());
  w->parent.resize(num_cells);
  for (int32_t c = 0; c < num_cells; ++c) w->parent[c] = c;
  // Each solid cell's reach: cell_reach, or reach_spacings expected sample spacings at the
  // range of the cell's centre on its plane, at most max_reach.
  std::vector<int32_t>& reach = w->reach;
  reach.resize(num_cells);
  const int base = std::max(1, options.extents.cell_reach);
  if (angular_step <= 0.0f || options.extents.reach_spacings <= 0.0f) {
    std::fill(reach.begin(), reach.end(), base);
  } else {
    PlaneTable& table = w->table;
    for (size_t j = 0; j < planes.size(); ++j) {
      table.cell[j + 1] = w->grids[j].cell;
      table.distance[j + 1] = planes[j].d;
    }
    CellReach(
        cells, table,
        ReachRule{base, options.extents.reach_spacings, options.extents.max_reach, angular_step},
        reach.data());
  }
  for (int32_t c = 0; c < num_cells; ++c) {
    if (w->counts[c].solid == 0) reach[c] = 0;
  }
  // Two cells connect when each lies within the other's reach; the earlier of the two in the
  // grid's row order finds the later one in the half of its neighbourhood that follows it.
  // The root of c is kept at hand: most neighbours already share it (one load and compare).
  // A solid cell right of c (or below it) whose reach is at least c's stands in for c along the
  // rest of the row (or in the rows below): every cell c would join there is at least as close
  // to it and within its reach, and it joins them itself. So an inner cell of a piece joins two
  // neighbours instead of searching its whole reach; the pieces are the same.
  std::vector<int32_t>& parent = w->parent;
  for (int32_t c = 0; c < num_cells; ++c) {
    if (reach[c] == 0) continue;
    const Cell& cell = cells[c];
    const PlaneGrid& g = w->grids[cell.plane];
    const int r = reach[c];
    const int y1 = std::min(g.h - 1, cell.iy + r);
    const int x0 = std::max(0, cell.ix - r), x1 = std::min(g.w - 1, cell.ix + r);
    int32_t root = Find(&parent, c);
    auto join = [&](int32_t other, int dist) {
      if (other < 0 || parent[other] == root || reach[other] == 0 || dist > reach[other]) return;
      const int32_t other_root = Find(&parent, other);
      if (other_root == root) return;
      // The earlier cell is the root.
      if (other_root < root) {
        parent[root] = other_root;
        root = other_root;
      } else {
        parent[other_root] = root;
      }
    };
    const int32_t* row = &w->slot_of[g.base + static_cast<size_t>(cell.iy) * g.w];
    const int32_t right = cell.ix + 1 < g.w ? row[cell.ix + 1] : -1;
    if (right >= 0 && reach[right] >= r) {
      join(right, 1);
    } else {
      for (int xx = cell.ix + 1; xx <= x1; ++xx) join(row[xx], xx - cell.ix);
    }
    const int32_t below = cell.iy + 1 < g.h ? row[g.w + cell.ix] : -1;
    if (below >= 0 && reach[below] >= r) {
      join(below, 1);
      continue;
    }
    for (int yy = cell.iy + 1; yy <= y1; ++yy) {
      row += g.w;
      for (int xx = x0; xx <= x1; ++xx) {
        join(row[xx], std::max(yy - cell.iy, std::abs(xx - cell.ix)));
      }
    }
  }
  w->piece_of.assign(num_cells, -1);
  w->root_piece.assign(num_cells, -1);
  int pieces = 0;
  for (int32_t c = 0; c < num_cells; ++c) {
    if (w->counts[c].solid == 0) continue;
    int32_t& piece = w->root_piece[Find(&w->parent, c)];
    if (piece < 0) piece = pieces++;
    w->piece_of[c] = piece;
  }
  return pieces;
}

void MarkOuterCells(int num_pieces, PieceWorkspace::Buffers* w) {
  w->outer.assign(w->cells.size(), 0);
  uint8_t* outer = w->outer.data();
  const int32_t* slot_of = w->slot_of.data();
  const int32_t* piece_of = w->piece_of.data();
  // Per piece: the line (row or column, numbered across all grids) it was last seen on, and its
  // last cell there.
  std::vector<int64_t> line_of(num_pieces, -1);
  std::vector<int32_t> last(num_pieces, -1);
  std::vector<int32_t> seen;  // pieces seen on the current line
  int64_t line = 0;
  // Walks each line of slots (`count` of them, `step` apart from `first`) and marks the first
  // and last cell of every piece on it.
  auto walk = [&](size_t first, int count, size_t step) {
    seen.clear();
    const int32_t* slot = slot_of + first;
    for (int k = 0; k < count; ++k, slot += step) {
      const int32_t c = *slot;
      if (c < 0 || piece_of[c] < 0) continue;
      const int32_t piece = piece_of[c];
      if (line_of[piece] != line) {
        line_of[piece] = line;
        seen.push_back(piece);
        outer[c] = 1;
      }
      last[piece] = c;
    }
    for (const int32_t piece : seen) outer[last[piece]] = 1;
    ++line;
  };
  for (const PlaneGrid& g : w->grids) {
    if (!g.used) continue;
    for (int iy = 0; iy < g.h; ++iy) walk(g.base + static_cast<size_t>(iy) * g.w, g.w, 1);
    for (int ix = 0; ix < g.w; ++ix) walk(g.base + ix, g.h, g.w);
  }
}

}  // namespace relplane::segmenter
