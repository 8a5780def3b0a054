#include "relplane/segmenter/merge_pieces.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <limits>

#include "relplane/segmenter/hull.hpp"

namespace relplane::segmenter {
namespace {

float Cross(const Eigen::Vector2f& o, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
  return (a.x() - o.x()) * (b.y() - o.y()) - (a.y() - o.y()) * (b.x() - o.x());
}

bool Inside(const Eigen::Vector2f& p, const std::vector<Eigen::Vector2f>& poly) {
  if (poly.size() < 3) return false;
  bool pos = false, neg = false;
  for (size_t i = 0; i < poly.size(); ++i) {
    const float c = Cross(poly[i], poly[(i + 1) % poly.size()], p);
    pos |= c > 0;
    neg |= c < 0;
  }
  return !(pos && neg);
}

float PointSegment(const Eigen::Vector2f& p, const Eigen::Vector2f& a, const Eigen::Vector2f& b) {
  const Eigen::Vector2f ab = b - a;
  const float len2 = ab.squaredNorm();
  const float t = len2 > 0 ? std::clamp((p - a).dot(ab) / len2, 0.0f, 1.0f) : 0.0f;
  return (a + t * ab - p).norm();
}

bool SegmentsCross(const Eigen::Vector2f& a, const Eigen::Vector2f& b, const Eigen::Vector2f& c,
                   const Eigen::Vector2f& d) {
  return Cross(a, b, c) * Cross(a, b, d) < 0 && Cross(c, d, a) * Cross(c, d, b) < 0;
}

void Axes(const Eigen::Vector3f& n, Eigen::Vector3f* u, Eigen::Vector3f* v) {
  *u = (std::fabs(n.x()) < 0.9f ? Eigen::Vector3f::UnitX() : Eigen::Vector3f::UnitY()).cross(n);
  u->normalize();
  *v = n.cross(*u);
}

std::vector<Eigen::Vector2f> Project(const std::vector<Eigen::Vector3f>& pts,
                                     const Eigen::Vector3f& origin, const Eigen::Vector3f& u,
                                     const Eigen::Vector3f& v) {
  std::vector<Eigen::Vector2f> out;
  for (const auto& p : pts) out.emplace_back(u.dot(p - origin), v.dot(p - origin));
  return out;
}

// b joins a: pooled centroid, scatter and rays, refit, extent over both extents.
void Absorb(const PieceStats& b, const Options& options, PieceStats* a) {
  const double na = a->plane.num_points, nb = b.plane.num_points, n = na + nb;
  const Eigen::Vector3d ca = a->plane.centroid.cast<double>();
  const Eigen::Vector3d cb = b.plane.centroid.cast<double>();
  const Eigen::Vector3d c = (na * ca + nb * cb) / n;
  const Eigen::Matrix3d scatter = a->scatter + b.scatter + na * (ca - c) * (ca - c).transpose() +
                                  nb * (cb - c) * (cb - c).transpose();
  const Eigen::Matrix3d rays = a->rays + b.rays;
  const RayNoiseFit fit = FitOutRayNoise(
      scatter, rays, n, static_cast<double>(options.noise.sigma_max) * options.noise.sigma_max);
  Eigen::Vector3d normal = fit.normal;
  double d = -normal.dot(c);
  if (d < 0) {
    normal = -normal;
    d = -d;
  }
  std::vector<Eigen::Vector3f> corners = a->plane.vertices;
  corners.insert(corners.end(), b.plane.vertices.begin(), b.plane.vertices.end());
  DetectedPlane& p = a->plane;
  p.normal = normal.cast<float>();
  p.d = static_cast<float>(d);
  p.centroid = c.cast<float>();
  p.num_points = static_cast<int>(n);
  p.rms = static_cast<float>(fit.rms);
  a->scatter = scatter;
  a->rays = rays;
  a->vertical = std::fabs(p.normal.z()) < options.extents.vertical_max_nz;
  Eigen::Vector3f u, v;
  if (a->vertical) {
    u = Eigen::Vector3f::UnitZ().cross(p.normal).normalized();
    v = p.normal.cross(u);
  } else {
    Axes(p.normal, &u, &v);
  }
  const auto flat = Project(corners, p.centroid, u, v);
  p.vertices.clear();
  auto lift = [&](const Eigen::Vector2f& q) {
    return Eigen::Vector3f(p.centroid + q.x() * u + q.y() * v);
  };
  if (a->vertical) {  // the rectangle around both rectangles
    Eigen::Vector2f lo = flat[0], hi = flat[0];
    for (const auto& q : flat) {
      lo = lo.cwiseMin(q);
      hi = hi.cwiseMax(q);
    }
    p.vertices = {lift(lo), lift({hi.x(), lo.y()}), lift(hi), lift({lo.x(), hi.y()})};
  } else {
    for (const auto& q : ConvexHull(flat)) p.vertices.push_back(lift(q));
  }
}

// Shared length of [a0, a1] and [b0, b1] over the shorter one's (0 for an empty one).
float OverlapShare(float a0, float a1, float b0, float b1) {
  const float shorter = std::min(a1 - a0, b1 - b0);
  if (!(shorter > 0.0f)) return 0.0f;
  return std::max(0.0f, std::min(a1, b1) - std::max(a0, b0)) / shorter;
}

// Do two vertical pieces lie over each other, along the wall and up it, over most of the
// smaller one? A depth sensor sees one surface where they overlap (a nearer one would hide the
// other), so with each centroid in the other's plane they are one surface that EM split between
// two planes.
bool Overlap(const DetectedPlane& p, const DetectedPlane& q) {
  const Eigen::Vector3f u = Eigen::Vector3f::UnitZ().cross(p.normal).normalized();
  auto extent = [&](const DetectedPlane& r, float* a0, float* a1, float* z0, float* z1) {
    *a0 = *z0 = std::numeric_limits<float>::infinity();
    *a1 = *z1 = -std::numeric_limits<float>::infinity();
    for (const auto& x : r.vertices) {
      *a0 = std::min(*a0, u.dot(x));
      *a1 = std::max(*a1, u.dot(x));
      *z0 = std::min(*z0, x.z());
      *z1 = std::max(*z1, x.z());
    }
  };
  float pa0, pa1, pz0, pz1, qa0, qa1, qz0, qz1;
  extent(p, &pa0, &pa1, &pz0, &pz1);
  extent(q, &qa0, &qa1, &qz0, &qz1);
  constexpr float kMostOfIt = 0.5f;
  return OverlapShare(pa0, pa1, qa0, qa1) >= kMostOfIt &&
         OverlapShare(pz0, pz1, qz0, qz1) >= kMostOfIt;
}

bool Mergeable(const PieceStats& a, const PieceStats& b, const Options& options) {
  const DetectedPlane& p = a.plane;
  const DetectedPlane& q = b.plane;
  const float within = options.sensor.CoplanarDistance(options.merge.distance, p.normal,
                                                        p.centroid, q.normal, q.centroid);
  if (std::fabs(p.normal.dot(q.centroid) + p.d) > within) return false;
  if (std::fabs(q.normal.dot(p.centroid) + q.d) > within) return false;
  const float cosine = p.normal.dot(q.normal);
  const float cos_overlap =
      std::cos(options.merge.overlap_angle_deg * static_cast<float>(M_PI) / 180.0f);
  if (a.vertical && b.vertical && cosine >= cos_overlap && Overlap(p, q)) return true;
  const float cos_merge =
      std::cos(options.merge.piece_angle_deg * static_cast<float>(M_PI) / 180.0f);
  if (cosine < cos_merge) return false;
  Eigen::Vector3f u, v;
  Axes(p.normal, &u, &v);
  const float gap = ConvexPolygonDistance(ConvexHull(Project(p.vertices, p.centroid, u, v)),
                                          ConvexHull(Project(q.vertices, p.centroid, u, v)));
  return gap <= options.extents.cell_reach * options.extents.cell_size;
}

}  // namespace

RayNoiseFit FitOutRayNoise(const Eigen::Matrix3d& scatter, const Eigen::Matrix3d& rays, double n,
                           double max_variance) {
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eig;
  eig.computeDirect(scatter);
  RayNoiseFit fit;
  fit.normal = eig.eigenvectors().col(0).normalized();
  const double residual = std::max(0.0, eig.eigenvalues()(0));
  fit.rms = n > 0 ? std::sqrt(residual / n) : 0.0;
  const double along = fit.normal.dot(rays * fit.normal);
  if (!(along > 0.0) || residual == 0.0) return fit;
  const double s2 = std::min(residual / along, max_variance);
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> corrected;
  corrected.computeDirect(scatter - s2 * rays);
  if (!(corrected.eigenvalues()(1) > 0.0)) return fit;
  fit.normal = corrected.eigenvectors().col(0).normalized();
  fit.rms = n > 0 ? std::sqrt(std::max(0.0, fit.normal.dot(scatter * fit.normal)) / n) : 0.0;
  return fit;
}

float ConvexPolygonDistance(const std::vector<Eigen::Vector2f>& a,
                            const std::vector<Eigen::Vector2f>& b) {
  if (a.empty() || b.empty()) return std::numeric_limits<float>::infinity();
  for (const auto& p : a) {
    if (Inside(p, b)) return 0.0f;
  }
  for (const auto& p : b) {
    if (Inside(p, a)) return 0.0f;
  }
  float best = std::numeric_limits<float>::infinity();
  for (size_t i = 0; i < a.size(); ++i) {
    const auto& a0 = a[i];
    const auto& a1 = a[(i + 1) % a.size()];
    for (size_t j = 0; j < b.size(); ++j) {
      const auto& b0 = b[j];
      const auto& b1 = b[(j + 1) % b.size()];
      if (SegmentsCross(a0, a1, b0, b1)) return 0.0f;
      best = std::min({best, PointSegment(a0, b0, b1), PointSegment(b0, a0, a1)});
    }
  }
  return best;
}

std::vector<PieceStats> MergeTouchingPieces(std::vector<PieceStats> pieces, const Options& options,
                                            std::vector<int32_t>* merged_into) {
  const size_t n = pieces.size();
  std::vector<int32_t> owner(n);
  for (size_t i = 0; i < n; ++i) owner[i] = static_cast<int32_t>(i);
  std::vector<bool> gone(n, false);
  // Larger pieces absorb smaller ones; repeat until nothing changes (a merge moves the plane).
  std::vector<size_t> order(n);
  for (size_t i = 0; i < n; ++i) order[i] = i;
  std::stable_sort(order.begin(), order.end(), [&pieces](size_t x, size_t y) {
    return pieces[x].plane.num_points > pieces[y].plane.num_points;
  });
  for (bool changed = true; changed;) {
    changed = false;
    for (size_t oi = 0; oi < n; ++oi) {
      const size_t i = order[oi];
      if (gone[i]) continue;
      for (size_t oj = oi + 1; oj < n; ++oj) {
        const size_t j = order[oj];
        if (gone[j] || !Mergeable(pieces[i], pieces[j], options)) continue;
        Absorb(pieces[j], options, &pieces[i]);
        gone[j] = true;
        owner[j] = static_cast<int32_t>(i);
        changed = true;
      }
    }
  }
  std::vector<int32_t> index(n, -1);
  std::vector<PieceStats> kept;
  for (size_t i = 0; i < n; ++i) {
    if (gone[i]) continue;
    index[i] = static_cast<int32_t>(kept.size());
    kept.push_back(std::move(pieces[i]));
  }
  if (merged_into) {
    merged_into->resize(n);
    for (size_t i = 0; i < n; ++i) {
      int32_t o = static_cast<int32_t>(i);
      while (owner[o] != o) o = owner[o];
      (*merged_into)[i] = index[o];
    }
  }
  return kept;
}

}  // namespace relplane::segmenter
