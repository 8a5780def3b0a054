#include "relplane/segmenter/extent.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "relplane/segmenter/hull.hpp"
#include "relplane/segmenter/merge_pieces.hpp"
#include "relplane/segmenter/moments.hpp"

namespace relplane::segmenter {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();
// The final fit of a piece uses its points within this many RMS of the first fit.
constexpr float kTrimSigmas = 2.5f;

// In-plane axes: for a vertical plane u is horizontal and v points up, so the extent rectangle
// follows the wall's vertical edges; otherwise any orthonormal pair.
void PlaneAxes(const Eigen::Vector3f& n, bool vertical, Eigen::Vector3f* u, Eigen::Vector3f* v) {
  if (vertical) {
    *u = Eigen::Vector3f::UnitZ().cross(n);
  } else {
    *u = (std::fabs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY()).cross(n);
  }
  u->normalize();
  *v = n.cross(*u);
}

// Per occupied cell: point count, moments about the plane's centroid, and (second pass) the
// extreme points along the piece's own axes for the hull.
struct Cell {
  int ix = 0, iy = 0;
  int solid = 0;  // points that are not on the strip where two planes meet
  LocalMoments all;
  LocalMoments trimmed;  // second pass: the points near the piece's first fit
  Eigen::Vector2f lo_a{kInf, 0}, hi_a{-kInf, 0}, lo_b{0, kInf}, hi_b{0, -kInf};
};

struct Piece {
  int count = 0;
  Eigen::Vector3d sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d sum_sq = Eigen::Matrix3d::Zero();
  bool kept = false;
  bool vertical = false;
  DetectedPlane out;
  Eigen::Matrix3d scatter;  // about the centroid
  // Second pass: moments of the points close to the first fit, about its centroid.
  int trimmed_count = 0;
  Eigen::Vector3f trimmed_centroid = Eigen::Vector3f::Constant(kInf);
  Eigen::Vector3d trimmed_sum = Eigen::Vector3d::Zero();
  Eigen::Matrix3d trimmed_sum_sq = Eigen::Matrix3d::Zero();
  float trim = 0.0f;  // distance from the first fit within which points are kept
  Eigen::Vector3f u, v;
  float a_min = kInf, a_max = -kInf, b_min = kInf, b_max = -kInf;
};

// Connected components of the solid cells (8-connected within `reach` cells); returns the
// piece index of every cell, numbered in order of the cells' first appearance, -1 for cells
// holding only points on the strip where two planes meet: along a floor, that strip would
// otherwise bridge the door between two walls.
int LabelCells(const std::vector<Cell>& cells, const std::vector<int>& slot_of, int w, int h,
               int reach, std::vector<int>* piece_of) {
  piece_of->assign(cells.size(), -1);
  int pieces = 0;
  std::vector<int> stack;
  for (size_t start = 0; start < cells.size(); ++start) {
    if ((*piece_of)[start] >= 0 || cells[start].solid == 0) continue;
    (*piece_of)[start] = pieces;
    stack.push_back(static_cast<int>(start));
    while (!stack.empty()) {
      const Cell& c = cells[stack.back()];
      stack.pop_back();
      for (int dy = -reach; dy <= reach; ++dy) {
        const int y = c.iy + dy;
        if (y < 0 || y >= h) continue;
        for (int dx = -reach; dx <= reach; ++dx) {
          const int x = c.ix + dx;
          if (x < 0 || x >= w) continue;
          const int other = slot_of[static_cast<size_t>(y) * w + x];
          if (other < 0 || (*piece_of)[other] >= 0 || cells[other].solid == 0) continue;
          (*piece_of)[other] = pieces;
          stack.push_back(other);
        }
      }
    }
    ++pieces;
  }
  return pieces;
}

// A cell whose eight neighbours belong to its piece lies inside the piece: its points cannot
// shape the hull (to within a cell), so they are left out of it.
bool Interior(const Cell& c, const std::vector<int>& slot_of, const std::vector<int>& piece_of,
              int64_t w, int64_t h) {
  if (c.ix == 0 || c.iy == 0 || c.ix == w - 1 || c.iy == h - 1) return false;
  const int piece = piece_of[slot_of[static_cast<size_t>(c.iy) * w + c.ix]];
  for (int dy = -1; dy <= 1; ++dy) {
    for (int dx = -1; dx <= 1; ++dx) {
      const int other = slot_of[static_cast<size_t>(c.iy + dy) * w + c.ix + dx];
      if (other < 0 || piece_of[other] != piece) return false;
    }
  }
  return true;
}

// Least-squares refit of a piece from its moments about `origin`; normal towards the sensor.
void Refit(const Eigen::Vector3f& origin, Piece* piece) {
  const double n = piece->count;
  const Eigen::Vector3d mean = piece->sum / n;
  const Eigen::Matrix3d scatter = piece->sum_sq - n * mean * mean.transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter);
  Eigen::Vector3d normal = eig.eigenvectors().col(0).normalized();
  const Eigen::Vector3d centroid = origin.cast<double>() + mean;
  double d = -normal.dot(centroid);
  if (d < 0.0) {  // the sensor sits at the origin: it must be on the positive side
    normal = -normal;
    d = -d;
  }
  piece->out.normal = normal.cast<float>();
  piece->out.d = static_cast<float>(d);
  piece->out.centroid = centroid.cast<float>();
  piece->out.num_points = piece->count;
  piece->out.rms = static_cast<float>(std::sqrt(std::max(0.0, eig.eigenvalues()(0)) / n));
  piece->scatter = scatter;
}

// Refits the piece to its trimmed moments; the extent's axes (u, v) and centroid frame stay,
// the vertices are lifted onto the new plane afterwards.
void TrimmedRefit(Piece* p) {
  if (p->trimmed_count < 3) return;
  Piece trimmed;
  trimmed.count = p->trimmed_count;
  trimmed.sum = p->trimmed_sum;
  trimmed.sum_sq = p->trimmed_sum_sq;
  Refit(p->out.centroid, &trimmed);
  p->out.normal = trimmed.out.normal;
  p->out.d = trimmed.out.d;
  p->out.rms = trimmed.out.rms;
  p->scatter = trimmed.scatter;
  p->trimmed_centroid = trimmed.out.centroid;
}

void DescribePlane(const Cloud& cloud, const std::vector<int>& idx,
                   const std::vector<uint8_t>& ambiguous, const EmPlane& plane,
                   const Options& options, std::vector<PieceStats>* out,
                   std::vector<int32_t>* piece_labels) {
  // Grid in the EM plane's coordinates, origin at its centroid.
  const Eigen::Vector3f origin = plane.centroid;
  Eigen::Vector3f u, v;
  PlaneAxes(plane.normal, std::fabs(plane.normal.z()) < options.vertical_max_nz, &u, &v);
  std::vector<float> a(idx.size()), b(idx.size());
  float a_lo = kInf, a_hi = -kInf, b_lo = kInf, b_hi = -kInf;
  for (size_t k = 0; k < idx.size(); ++k) {
    const Eigen::Vector3f q = cloud.Point(idx[k]) - origin;
    a[k] = u.dot(q);
    b[k] = v.dot(q);
    a_lo = std::min(a_lo, a[k]);
    a_hi = std::max(a_hi, a[k]);
    b_lo = std::min(b_lo, b[k]);
    b_hi = std::max(b_hi, b[k]);
  }
  float cell = options.cell_size;
  int64_t w = 0, h = 0;
  for (;;) {  // coarsen until the grid fits: a bounded cost whatever the plane's extent
    w = static_cast<int64_t>((a_hi - a_lo) / cell) + 1;
    h = static_cast<int64_t>((b_hi - b_lo) / cell) + 1;
    if (w * h <= options.max_cells) break;
    cell *= 2.0f;
  }
  std::vector<int> slot_of(static_cast<size_t>(w * h), -1);
  std::vector<Cell> cells;
  std::vector<int> cell_of_point(idx.size());
  for (size_t k = 0; k < idx.size(); ++k) {
    const int ix = std::min<int>(w - 1, static_cast<int>((a[k] - a_lo) / cell));
    const int iy = std::min<int>(h - 1, static_cast<int>((b[k] - b_lo) / cell));
    int& slot = slot_of[static_cast<size_t>(iy) * w + ix];
    if (slot < 0) {
      slot = static_cast<int>(cells.size());
      cells.emplace_back();
      cells.back().ix = ix;
      cells.back().iy = iy;
    }
    cell_of_point[k] = slot;
    Cell& c = cells[slot];
    c.solid += ambiguous.empty() || !ambiguous[idx[k]];
    c.all.Add(cloud.Point(idx[k]));
  }
  std::vector<int> piece_of;
  const int num_pieces = LabelCells(cells, slot_of, static_cast<int>(w), static_cast<int>(h),
                                    std::max(1, options.cell_reach), &piece_of);
  std::vector<Piece> pieces(num_pieces);
  for (size_t s = 0; s < cells.size(); ++s) {
    if (piece_of[s] < 0) continue;
    Piece& p = pieces[piece_of[s]];
    cells[s].all.AddTo(origin, &p.count, &p.sum, &p.sum_sq);
  }
  for (Piece& p : pieces) {
    p.kept = p.count >= options.min_points;
    if (!p.kept) continue;
    Refit(origin, &p);
    p.vertical = std::fabs(p.out.normal.z()) < options.vertical_max_nz;
    PlaneAxes(p.out.normal, p.vertical, &p.u, &p.v);
    p.trim = kTrimSigmas * std::max(p.out.rms, options.sigma_min);
  }
  // Second pass: extents along each piece's own refitted axes, and the moments of the points
  // near the fit, so the final fit ignores what the piece caught from a neighbouring surface.
  for (size_t k = 0; k < idx.size(); ++k) {
    Cell& c = cells[cell_of_point[k]];
    const int piece = piece_of[cell_of_point[k]];
    if (piece < 0 || !pieces[piece].kept) continue;
    Piece& p = pieces[piece];
    if (piece_labels) (*piece_labels)[idx[k]] = piece;  // local index, made global below
    const Eigen::Vector3f q = cloud.Point(idx[k]) - p.out.centroid;
    const Eigen::Vector2f ab(p.u.dot(q), p.v.dot(q));
    if (std::fabs(p.out.normal.dot(q)) <= p.trim) c.trimmed.Add(cloud.Point(idx[k]));
    if (p.vertical) {
      p.a_min = std::min(p.a_min, ab.x());
      p.a_max = std::max(p.a_max, ab.x());
      p.b_min = std::min(p.b_min, ab.y());
      p.b_max = std::max(p.b_max, ab.y());
      continue;
    }
    if (ab.x() < c.lo_a.x()) c.lo_a = ab;
    if (ab.x() > c.hi_a.x()) c.hi_a = ab;
    if (ab.y() < c.lo_b.y()) c.lo_b = ab;
    if (ab.y() > c.hi_b.y()) c.hi_b = ab;
  }
  for (size_t s = 0; s < cells.size(); ++s) {
    if (piece_of[s] < 0 || !pieces[piece_of[s]].kept) continue;
    Piece& p = pieces[piece_of[s]];
    cells[s].trimmed.AddTo(p.out.centroid, &p.trimmed_count, &p.trimmed_sum, &p.trimmed_sum_sq);
  }
  std::vector<std::vector<Eigen::Vector2f>> hull_points(num_pieces);
  for (size_t s = 0; s < cells.size(); ++s) {
    if (piece_of[s] < 0) continue;
    const Piece& p = pieces[piece_of[s]];
    if (!p.kept || p.vertical || Interior(cells[s], slot_of, piece_of, w, h)) continue;
    for (const auto& e : {cells[s].lo_a, cells[s].hi_a, cells[s].lo_b, cells[s].hi_b}) {
      hull_points[piece_of[s]].push_back(e);
    }
  }
  std::vector<int32_t> global(num_pieces, -1);
  for (int i = 0; i < num_pieces; ++i) {
    Piece& p = pieces[i];
    if (!p.kept) continue;
    global[i] = static_cast<int32_t>(out->size());
    TrimmedRefit(&p);
    auto lift = [&p](float pa, float pb) {
      return Eigen::Vector3f(p.out.centroid + pa * p.u + pb * p.v);
    };
    if (p.vertical) {
      p.out.vertices = {lift(p.a_min, p.b_min), lift(p.a_max, p.b_min), lift(p.a_max, p.b_max),
                        lift(p.a_min, p.b_max)};
    } else {
      for (const auto& corner : ConvexHull(hull_points[i])) {
        p.out.vertices.push_back(lift(corner.x(), corner.y()));
      }
    }
    for (auto& v : p.out.vertices) v -= (p.out.normal.dot(v) + p.out.d) * p.out.normal;
    if (p.trimmed_count >= 3) p.out.centroid = p.trimmed_centroid;
    out->push_back(PieceStats{std::move(p.out), p.scatter, p.vertical});
  }
  if (piece_labels) {
    for (int i : idx) {
      int32_t& l = (*piece_labels)[i];
      if (l >= 0) l = global[l];
    }
  }
}

}  // namespace

std::vector<DetectedPlane> DescribePieces(const Cloud& cloud, const std::vector<int32_t>& labels,
                                          const std::vector<uint8_t>& ambiguous,
                                          const std::vector<EmPlane>& planes,
                                          const Options& options,
                                          std::vector<int32_t>* piece_labels) {
  if (piece_labels) piece_labels->assign(cloud.size(), -1);
  // Bucket the point indices by label, keeping each bucket in ascending order.
  std::vector<std::vector<int>> members(planes.size());
  for (size_t i = 0; i < labels.size(); ++i) {
    if (labels[i] >= 0) members[labels[i]].push_back(static_cast<int>(i));
  }
  std::vector<PieceStats> described;
  for (size_t j = 0; j < planes.size(); ++j) {
    if (static_cast<int>(members[j].size()) < options.min_points) continue;
    DescribePlane(cloud, members[j], ambiguous, planes[j], options, &described, piece_labels);
  }
  std::vector<int32_t> merged_into;
  std::vector<PieceStats> merged = MergeTouchingPieces(std::move(described), options, &merged_into);
  std::vector<DetectedPlane> result;
  for (auto& m : merged) result.push_back(std::move(m.plane));
  std::vector<int32_t> order(result.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = static_cast<int32_t>(i);
  std::stable_sort(order.begin(), order.end(), [&result](int32_t x, int32_t y) {
    return result[x].num_points > result[y].num_points;
  });
  std::vector<DetectedPlane> sorted;
  std::vector<int32_t> rank(order.size());
  for (size_t r = 0; r < order.size(); ++r) {
    rank[order[r]] = static_cast<int32_t>(r);
    sorted.push_back(std::move(result[order[r]]));
  }
  if (piece_labels) {
    for (int32_t& l : *piece_labels) {
      if (l >= 0) l = rank[merged_into[l]];
    }
  }
  return sorted;
}

}  // namespace relplane::segmenter
