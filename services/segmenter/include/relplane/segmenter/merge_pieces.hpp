#pragma once
// Pieces of different mixture planes that are one surface: coplanar and touching.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// A described piece plus what merging needs: its scatter matrix about its centroid, and the sum
// of d d^T over its points' unit sensor rays d (RayNoiseFit), both as if every point was fitted.
struct PieceStats {
  DetectedPlane plane;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  Eigen::Matrix3d rays = Eigen::Matrix3d::Zero();
  bool vertical = false;
};

// A depth sensor's noise moves each point along its own ray. Its share of the scatter,
// s^2 sum d d^T, is not isotropic, and for a piece seen off to one side its rays lean the same
// way: the smallest eigenvector of the raw scatter tilts towards the rays by about
// s^2 sum (n.d)(u.d) / (n L^2 / 12) for a piece of length L (a 0.15 m wall piece beside a door
// at s = 1 cm: 1-2 degrees). The fit takes that share out: s^2 from the residual along the
// least-squares normal (at most `max_variance`), then the smallest eigenvector of
// scatter - s^2 rays. It keeps the least-squares normal where the scatter left along the piece
// would not stay positive (the piece is too small to tell from its noise). `n` points.
struct RayNoiseFit {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();  // unit; its sign is the caller's to set
  double rms = 0.0;                                   // RMS distance to the plane
};
RayNoiseFit FitOutRayNoise(const Eigen::Matrix3d& scatter, const Eigen::Matrix3d& rays, double n,
                           double max_variance);

// Merges pieces whose planes agree (normals within options.merge.piece_angle_deg, each centroid
// within options.merge.distance of the other plane) and whose extents touch (within cell_reach
// cells). EM keeps such surfaces apart when the data bend slightly (a depth camera's distortion
// puts a strip of floor 1-2 cm off the rest); pieces split by a gap (a door) do not touch and stay
// apart. Vertical pieces lying over each other (along the wall and up it, over half the smaller
// one), each centroid within merge.distance of the other's plane, merge within the wider
// options.merge.overlap_angle_deg: a depth sensor sees one surface there, which EM split between
// two planes. `merged_into[k]` receives the index of the piece k ended up in.
std::vector<PieceStats> MergeTouchingPieces(std::vector<PieceStats> pieces, const Options& options,
                                            std::vector<int32_t>* merged_into);

// Distance between two convex polygons (0 when they overlap).
float ConvexPolygonDistance(const std::vector<Eigen::Vector2f>& a,
                            const std::vector<Eigen::Vector2f>& b);

}  // namespace relplane::segmenter
