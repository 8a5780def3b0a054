#include "relplane/segmenter/extent.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>

#include "piece_fit.hpp"
#include "piece_grid.hpp"
#include "relplane/segmenter/dominant_line.hpp"
#include "relplane/segmenter/hull.hpp"
#include "relplane/segmenter/merge_pieces.hpp"
#include "relplane/segmenter/spacing.hpp"
#include "relplane/segmenter/trimmed_fit.hpp"
#include "relplane/segmenter/wall_ends.hpp"

namespace relplane::segmenter {
namespace {

// What the second pass does with a cell's points.
constexpr uint8_t kTrimPoints = 1;  // some may lie beyond the trim: test each, and take out
                                    // the moments of those beyond
constexpr uint8_t kExtremes = 2;    // a boundary cell: its points may shape the extent

// Whether every point of the cell lies within the piece's trim: the distance to the piece's
// plane is linear, so its extremes over the cell's box (grid cell x range of distances to the
// EM plane) are at the box's corners.
bool WithinTrim(const PlaneGrid& g, const Cell& cell, const CellMoments& m, const Piece& p) {
  const Eigen::Vector3f centre = g.origin + (g.a_lo + (cell.ix + 0.5f) * g.cell) * g.u +
                                 (g.b_lo + (cell.iy + 0.5f) * g.cell) * g.v +
                                 0.5f * (m.e_lo + m.e_hi) * g.n;
  const Eigen::Vector3f& n = p.out.normal;
  const float f = n.dot(centre - p.out.centroid);
  const float spread = p.cell_spread + 0.5f * (m.e_hi - m.e_lo) * p.normal_spread;
  constexpr float kSlack = 1e-4f;  // metres: rounding of the cell bounds
  return std::fabs(f) + spread < p.trim - kSlack;
}

// Sets each cell's mode for the second pass; cells whose points all lie within the trim give
// their moments to the trimmed fit at once.
void PlanSecondPass(PieceWorkspace::Buffers* w, std::vector<Piece>* pieces) {
  const size_t num_cells = w->cells.size();
  w->mode.assign(num_cells, 0);
  // Only the cells with a mode are read back: the others' slots keep whatever they held.
  w->finish.resize(num_cells);
  for (size_t s = 0; s < num_cells; ++s) {
    const int32_t piece = w->piece_of[s];
    if (piece < 0 || !(*pieces)[piece].kept) continue;
    Piece& p = (*pieces)[piece];
    const Cell& cell = w->cells[s];
    const CellMoments& m = w->moments[s];
    if (w->outer[s]) w->mode[s] |= kExtremes;
    if (!WithinTrim(w->grids[cell.plane], cell, m, p)) {
      w->mode[s] |= kTrimPoints;
    }
    if (w->mode[s] == 0) continue;
    w->finish[s] = CellFinish{};
    w->finish[s].beyond.ref = m.all.ref;
  }
}

// Second pass over the points, in cloud order, of the cells that need it: the moments of the
// points beyond the trim of the first fit, taken out of the cell's so the final fit ignores
// what the piece caught from a neighbouring surface; extents along each piece's own refitted axes.
// Only the outer cells (MarkOuterCells) are searched for extreme points: the others lie within
// the extent of those to within a cell.
void TrimAndExtend(const Cloud& cloud, const Options& options, PieceWorkspace::Buffers* w,
                   std::vector<Piece>* pieces, std::vector<int32_t>* piece_labels) {
  const float* x = cloud.x.data();
  const float* y = cloud.y.data();
  const float* z = cloud.z.data();
  // Point i of `cell` in a cell with a mode; `fitted`: it entered the cell's moments.
  auto visit = [&](size_t i, int32_t cell, uint8_t mode, bool fitted) {
    Piece& p = (*pieces)[w->piece_of[cell]];
    CellFinish& c = w->finish[cell];
    const Eigen::Vector3f point(x[i], y[i], z[i]);
    const Eigen::Vector3f q = point - p.out.centroid;
    if ((mode & kTrimPoints) && fitted && std::fabs(p.out.normal.dot(q)) > p.trim) {
      c.beyond.AddAboutRef(point);
    }
    if (!(mode & kExtremes)) return;
    const Eigen::Vector2f ab(p.u.dot(q), p.v.dot(q));
    if (p.vertical) {
      p.a_min = std::min(p.a_min, ab.x());
      p.a_max = std::max(p.a_max, ab.x());
      p.b_min = std::min(p.b_min, ab.y());
      p.b_max = std::max(p.b_max, ab.y());
      p.lo_end.Add(-ab.x(), ab.y());  // EstimateWallEnds reads them
      p.hi_end.Add(ab.x(), ab.y());
      return;
    }
    if (ab.x() < c.lo_a.x()) c.lo_a = ab;
    if (ab.x() > c.hi_a.x()) c.hi_a = ab;
    if (ab.y() < c.lo_b.y()) c.lo_b = ab;
    if (ab.y() > c.hi_b.y()) c.hi_b = ab;
  };
  const size_t stride = FitStride(cloud.size(), options);
  if (stride == 1 && piece_labels == nullptr) {
    // Every point entered the fits and BinPoints grouped them by cell (cloud order kept within
    // a cell): only the cells with a mode are visited.
    for (size_t cell = 0; cell < w->cells.size(); ++cell) {
      const uint8_t mode = w->mode[cell];
      if (mode == 0) continue;
      for (int32_t k = w->fit_start[cell]; k < w->fit_start[cell + 1]; ++k) {
        visit(w->fit_order[k], static_cast<int32_t>(cell), mode, true);
      }
    }
    return;
  }
  for (size_t i = 0, phase = 0; i < cloud.size();
       ++i, phase = phase + 1 == stride ? 0 : phase + 1) {
    const int32_t cell = w->cell_of_point[i];
    if (cell < 0) continue;
    if (piece_labels) {
      const int32_t piece = w->piece_of[cell];
      if (piece >= 0 && (*pieces)[piece].kept) (*piece_labels)[i] = piece;  // made global later
    }
    const uint8_t mode = w->mode[cell];
    if (mode == 0 || (mode == kTrimPoints && phase != 0)) continue;
    visit(i, cell, mode, phase == 0);
  }
}

// Each vertical piece's ends along its wall from its points furthest out (EstimateEnd): the
// sensor's columns of rays land `column spacing` apart along the wall at the end (SampleSpacing
// at its horizontal range), its rows the step times that range apart up it. `ray_step`: the
// sensor's own angular step; `share`: of its rays, the described points; `max_spacing` bounds
// the spacing at a grazing angle. Nothing moves without a step.
// An end whose furthest point lies at `range_cut` or beyond is where the sensor's range ran out:
// an arc across the wall, furthest at the sensor's height, not a column of samples, so it keeps
// its extreme point.
void EstimateWallEnds(float ray_step, float share, float max_spacing, float range_cut,
                      std::vector<Piece>* pieces) {
  if (!(ray_step > 0.0f)) return;
  for (Piece& p : *pieces) {
    if (!p.kept || !p.vertical || p.hi_end.Size() == 0) continue;
    const float mid = 0.5f * (p.b_min + p.b_max);
    // The buffer's furthest sample, at coordinate `sign * out` along u.
    auto at_range_cut = [&](const EndBuffer& buffer, float sign) {
      const EndBuffer::Sample* far = std::max_element(
          buffer.begin(), buffer.end(),
          [](const EndBuffer::Sample& x, const EndBuffer::Sample& y) { return x.out < y.out; });
      return (p.out.centroid + sign * far->out * p.u + far->up * p.v).norm() >= range_cut;
    };
    auto sampling = [&](float a) {
      const Eigen::Vector3f end = p.out.centroid + a * p.u + mid * p.v;
      const float along_v = end.dot(p.v);
      const float range = std::sqrt(std::max(0.0f, end.squaredNorm() - along_v * along_v));
      EndSampling s;
      s.column_spacing = std::min(max_spacing, SampleSpacing(ray_step, range, p.out.d));
      s.row_spacing = ray_step * range;
      s.share = share;
      return s;
    };
    if (!at_range_cut(p.hi_end, 1.0f)) p.a_max = EstimateEnd(p.hi_end, sampling(p.a_max));
    if (!at_range_cut(p.lo_end, -1.0f)) p.a_min = -EstimateEnd(p.lo_end, sampling(p.a_min));
  }
}

// The kept pieces, described: trimmed refit and extent polygon. `index` receives each piece's
// index in `out` (-1 when dropped).
void Describe(const Cloud& cloud, const Options& options, PieceWorkspace::Buffers* w,
              std::vector<Piece>* pieces, std::vector<PieceStats>* out,
              std::vector<int32_t>* index) {
  const double max_variance =
      static_cast<double>(options.noise.sigma_max) * options.noise.sigma_max;
  const size_t num_cells = w->cells.size();
  std::vector<std::vector<Eigen::Vector2f>> hull_points(pieces->size());
  for (size_t s = 0; s < num_cells; ++s) {
    const int32_t piece = w->piece_of[s];
    if (piece < 0) continue;
    Piece& p = (*pieces)[piece];
    if (!p.kept) continue;
    const CellFinish& c = w->finish[s];
    const LocalMoments& all = w->moments[s].all;
    const LocalMoments trimmed = (w->mode[s] & kTrimPoints) ? all.Minus(c.beyond) : all;
    trimmed.AddTo(p.out.centroid, &p.trimmed_count, &p.trimmed_sum, &p.trimmed_sum_sq);
    if (p.vertical || !(w->mode[s] & kExtremes)) continue;
    for (const auto& e : {c.lo_a, c.hi_a, c.lo_b, c.hi_b}) hull_points[piece].push_back(e);
  }
  for (Piece& p : *pieces) {
    if (p.kept) TrimmedMoments(&p);
  }
  IterateVerticalFits(cloud, options, w, pieces);
  // The sensor's noise along its rays, pooled over the frame's pieces (the large ones weigh
  // most): a short piece's own residual also holds what is not noise (a corner's other face,
  // a bend), and a piece seen at a grazing angle divides it by little.
  double residual = 0.0, along = 0.0;
  for (Piece& p : *pieces) {
    if (!p.kept || p.trimmed_count < 3) continue;
    residual += p.trimmed_normal.dot(p.scatter * p.trimmed_normal);
    along += p.trimmed_normal.dot(p.rays * p.trimmed_normal);
  }
  const double ray_variance = along > 0.0 ? std::min(max_variance, residual / along) : 0.0;
  for (Piece& p : *pieces) {
    if (!p.kept) continue;
    // A known camera's noise along the rays is its own at the piece's range (far pieces are
    // noisier than the frame's pool, which the near ones dominate).
    TrimmedRefit(options.sensor.Known() ? RangeVariance(options, p.trimmed_centroid.cast<double>())
                                        : ray_variance,
                 &p);
  }
  index->assign(pieces->size(), -1);
  for (size_t i = 0; i < pieces->size(); ++i) {
    Piece& p = (*pieces)[i];
    if (!p.kept) continue;
    (*index)[i] = static_cast<int32_t>(out->size());
    auto lift = [&p](float pa, float pb) {
      return Eigen::Vector3f(p.out.centroid + pa * p.u + pb * p.v);
    };
    if (p.vertical) {
      p.out.vertices = {lift(p.a_min, p.b_min), lift(p.a_max, p.b_min), lift(p.a_max, p.b_max),
                        lift(p.a_min, p.b_max)};
    } else {
      for (const auto& corner : ConvexHull(std::move(hull_points[i]))) {
        p.out.vertices.push_back(lift(corner.x(), corner.y()));
      }
    }
    for (auto& v : p.out.vertices) v -= (p.out.normal.dot(v) + p.out.d) * p.out.normal;
    if (p.trimmed_count >= 3) p.out.centroid = p.trimmed_centroid;
    out->push_back(PieceStats{std::move(p.out), p.scatter, p.rays, p.vertical});
  }
}

// Per mixture plane, its largest piece fitted to a line (DominantLineFit): the plane to assign
// the frame again with.
std::vector<LineRefit> LineRefits(const std::vector<EmPlane>& planes,
                                  const std::vector<Piece>& pieces, const Options& options) {
  std::vector<LineRefit> refits;
  std::vector<int> largest(planes.size(), -1);
  for (const Piece& p : pieces) {
    if (!p.kept || !p.line_refit || p.trimmed_count < 3) continue;
    if (largest[p.plane] >= 0 && largest[p.plane] >= p.support) continue;
    largest[p.plane] = p.support;
    const EmPlane& was = planes[p.plane];
    Eigen::Vector3f n = p.trimmed_normal.cast<float>();
    if (n.dot(was.normal) < 0.0f) n = -n;
    EmPlane refit = was;
    refit.normal = n;
    refit.d = -n.dot(p.trimmed_centroid);
    // Never a wider band than EM gave it: the line is to take in less, not more.
    refit.sigma = std::clamp(p.trimmed_rms, options.noise.sigma_min,
                             std::max(options.noise.sigma_min, was.sigma));
    refit.centroid = p.trimmed_centroid;
    auto same = std::find_if(refits.begin(), refits.end(),
                             [&](const LineRefit& r) { return r.plane == p.plane; });
    if (same != refits.end()) {
      same->refit = refit;
    } else {
      refits.push_back({p.plane, refit});
    }
  }
  return refits;
}

// Per mixture plane: whether it formed a kept piece (Description::plane_has_piece).
std::vector<uint8_t> PlanesWithPieces(const std::vector<Piece>& pieces, size_t num_planes) {
  std::vector<uint8_t> has_piece(num_planes, 0);
  for (const Piece& p : pieces) {
    if (p.kept) has_piece[p.plane] = 1;
  }
  return has_piece;
}

}  // namespace

PieceWorkspace::PieceWorkspace() : buffers_(std::make_unique<Buffers>()) {}
PieceWorkspace::~PieceWorkspace() = default;
PieceWorkspace::PieceWorkspace(PieceWorkspace&&) noexcept = default;
PieceWorkspace& PieceWorkspace::operator=(PieceWorkspace&&) noexcept = default;

std::vector<uint8_t> FormPieces(const DescribeRequest& request, const Options& options,
                                PieceWorkspace* workspace) {
  const Cloud& cloud = request.cloud;
  const std::vector<EmPlane>& planes = request.planes;
  PieceWorkspace::Buffers& w = workspace->Get();
  BinPoints(cloud, request.labels, request.ambiguous, planes, options, &w);
  std::vector<Piece>& pieces = w.pieces;
  pieces.assign(
      static_cast<size_t>(LabelPieces(planes, options, request.sampling.angular_step, &w)),
      Piece{});
  const double stride = static_cast<double>(FitStride(cloud.size(), options));
  for (size_t s = 0; s < w.cells.size(); ++s) {
    if (w.piece_of[s] < 0) continue;
    Piece& p = pieces[w.piece_of[s]];
    p.plane = w.cells[s].plane;
    p.support += w.counts[s].count;
    p.stride = stride;
    w.moments[s].all.AddTo(w.grids[p.plane].origin, &p.count, &p.sum, &p.sum_sq);
  }
  for (Piece& p : pieces) {
    p.kept = p.support >= options.extents.min_points && p.count >= 3;
    if (!p.kept) continue;
    Refit(w.grids[p.plane].origin, &p);
    p.vertical = std::fabs(p.out.normal.z()) < options.extents.vertical_max_nz;
    PlaneAxes(p.out.normal, p.vertical, &p.u, &p.v);
    p.trim = options.extents.trim_sigmas * std::max(p.out.rms, options.noise.sigma_min);
    const PlaneGrid& g = w.grids[p.plane];
    const float half = 0.5f * g.cell;
    p.cell_spread = half * (std::fabs(p.out.normal.dot(g.u)) + std::fabs(p.out.normal.dot(g.v)));
    p.normal_spread = std::fabs(p.out.normal.dot(g.n));
  }
  return PlanesWithPieces(pieces, planes.size());
}

Description DescribePieces(const DescribeRequest& request, const Options& options,
                           PieceWorkspace* workspace) {
  PieceWorkspace local;
  PieceWorkspace* ws = workspace ? workspace : &local;
  FormPieces(request, options, ws);
  return DescribeFormedPieces(request, options, ws);
}

Description DescribeFormedPieces(const DescribeRequest& request, const Options& options,
                                 PieceWorkspace* workspace) {
  const Cloud& cloud = request.cloud;
  const std::vector<EmPlane>& planes = request.planes;
  Description result;
  std::vector<int32_t>* piece_labels = request.want_piece_labels ? &result.piece_labels : nullptr;
  PieceWorkspace::Buffers& w = workspace->Get();
  std::vector<Piece>& pieces = w.pieces;
  if (piece_labels) piece_labels->assign(cloud.size(), -1);
  result.plane_has_piece = PlanesWithPieces(pieces, planes.size());
  MarkOuterCells(static_cast<int>(pieces.size()), &w);
  PlanSecondPass(&w, &pieces);
  TrimAndExtend(cloud, options, &w, &pieces, piece_labels);
  // The cloud's furthest point is about the sensor's range (a wall cut by it reaches it).
  float furthest2 = 0.0f;
  for (size_t i = 0; i < cloud.size(); ++i) {
    furthest2 = std::max(
        furthest2, cloud.x[i] * cloud.x[i] + cloud.y[i] * cloud.y[i] + cloud.z[i] * cloud.z[i]);
  }
  EstimateWallEnds(request.sampling.ray_step, std::clamp(request.sampling.share, 1e-3f, 1.0f),
                   options.extents.max_end_spacing,
                   options.extents.range_cut_share * std::sqrt(furthest2), &pieces);
  std::vector<PieceStats> described;
  std::vector<int32_t> index;
  Describe(cloud, options, &w, &pieces, &described, &index);
  result.line_refits = LineRefits(planes, pieces, options);
  std::vector<int32_t> merged_into;
  std::vector<PieceStats> merged = MergeTouchingPieces(std::move(described), options, &merged_into);
  std::vector<int32_t> order(merged.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int32_t>(i);
  std::stable_sort(order.begin(), order.end(), [&merged](int32_t a, int32_t b) {
    return merged[a].plane.num_points > merged[b].plane.num_points;
  });
  std::vector<int32_t> rank(order.size());
  for (size_t r = 0; r < order.size(); ++r) {
    rank[order[r]] = static_cast<int32_t>(r);
    result.planes.push_back(std::move(merged[order[r]].plane));
  }
  if (piece_labels) {
    for (int32_t& l : *piece_labels) {
      if (l >= 0) l = rank[merged_into[index[l]]];
    }
  }
  return result;
}

}  // namespace relplane::segmenter
