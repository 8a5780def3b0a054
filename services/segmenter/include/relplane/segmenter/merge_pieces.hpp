#pragma once
// Pieces of different mixture planes that are one surface: coplanar and touching.

#include <Eigen/Core>
#include <cstdint>
#include <vector>

#include "relplane/segmenter/cloud.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter {

// A described piece plus what merging needs: its scatter matrix about its centroid.
struct PieceStats {
  DetectedPlane plane;
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  bool vertical = false;
};

// Merges pieces whose planes agree (normals within options.piece_merge_angle_deg, each centroid
// within options.merge_distance of the other plane) and whose extents touch (within cell_reach
// cells). EM keeps such surfaces apart when the data bend slightly (a depth camera's distortion
// puts a strip of floor 1-2 cm off the rest); pieces split by a gap (a door) do not touch and stay
// apart. `merged_into[k]` receives the index of the piece k ended up in.
std::vector<PieceStats> MergeTouchingPieces(std::vector<PieceStats> pieces, const Options& options,
                                            std::vector<int32_t>* merged_into);

// Distance between two convex polygons (0 when they overlap).
float ConvexPolygonDistance(const std::vector<Eigen::Vector2f>& a,
                            const std::vector<Eigen::Vector2f>& b);

}  // namespace relplane::segmenter
