#pragma once
// Placements of walls in a frame: a group's relative map (§II.D) or the world.

#include <Eigen/Core>
#include <cstdint>
#include <map>
#include <vector>

namespace relplane::mapper {

// How much of a wall's placement is known: its orientation only, its line, or also the position
// of one of its edges (`ref`) along the line.
enum class Known : int { kAngle = 0, kLine = 1, kPoint = 2 };

// A wall placed in a frame (a group's relative frame or the world): frame angle alpha (x along
// the wall), a point on its line (the `ref` edge when known == kPoint).
struct Placement {
  double alpha = 0.0;
  Eigen::Vector2d point = Eigen::Vector2d::Zero();
  int ref = -1;  // Index(Edge) of the edge `point` is, or -1
  Known known = Known::kAngle;
  // The other edge, when a later group found it static (global map only), and that group.
  bool has_other = false;
  Eigen::Vector2d other = Eigen::Vector2d::Zero();
  int64_t other_by = -1;
  // Relative maps only: variance (m^2) of `point` from the basis, summed over the chain of
  // static pairings that placed it (each pairing's spread over its interval, §II.C).
  double variance = 0.0;
};

// §II.D relative map of one group, in the frame of its basis rltplane.
struct RelativeMap {
  int64_t basis = -1;
  std::map<int64_t, Placement> members;

  // The basis's reference edge (the frame's origin), -1 when it has none or is not placed.
  int BasisRef() const {
    auto it = members.find(basis);
    return it == members.end() ? -1 : it->second.ref;
  }
};

// §II.F the comparison order of a group: the basis, the edge its frame starts at, and which
// placed member each other member is placed from, in placement order.
struct ChainLink {
  int64_t from = -1;
  int64_t to = -1;
};
struct ChainOrder {
  int64_t basis = -1;
  int basis_ref = -1;
  std::vector<ChainLink> links;
};

}  // namespace relplane::mapper
