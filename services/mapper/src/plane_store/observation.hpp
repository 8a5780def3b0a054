#pragma once
// One untransformed plane as the segmenter reports it, and its 2½D reduction (Fig. 1 row).

#include <Eigen/Core>
#include <Eigen/Geometry>
#include <cstdint>
#include <optional>
#include <vector>

#include "relplane/common/geometry.hpp"
#include "relplane/mapper/options.hpp"
#include "relplane/mapper/types.hpp"

namespace relplane::mapper {

// The two ends of a wall along its direction t (see Observation).
enum class Edge : int { kLo = 0, kHi = 1 };
inline Edge Other(Edge e) { return e == Edge::kLo ? Edge::kHi : Edge::kLo; }
inline int Index(Edge e) { return static_cast<int>(e); }

// A wall observation reduced to 2½D. Frame of a wall: x along t = (-n_y, n_x), y along the normal
// n (towards the sensor). Its frame angle alpha = atan2(t_y, t_x). Both edge points lie on the
// wall's line; edge[kLo] has the smaller coordinate along t.
struct Observation {
  int64_t iteration = 0;
  Eigen::Vector2d normal = Eigen::Vector2d::UnitX();
  double d = 0.0;  // normal . p + d = 0, d >= 0 (the sensor is in front)
  Eigen::Vector3d normal3 = Eigen::Vector3d::UnitX();
  Eigen::Vector3d centroid = Eigen::Vector3d::Zero();
  Eigen::Vector2d edge[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  double z_min = 0.0;
  double z_max = 0.0;
  Eigen::AlignedBox3d box;
  std::vector<Eigen::Vector3d> vertices;
  int support = 0;
  double rms = 0.0;
  // The edge is where the view cuts the wall (field of view, range, or a nearer plane in
  // front), not a wall end: it cannot be a static edge (§II.C).
  bool cut[2] = {false, false};
  // Cut only because the sensor's samples lie too far apart along the wall at the edge to place
  // it by one sighting (Observe): the comparisons, which pool many sightings, still judge it.
  bool coarse[2] = {false, false};
  // Cut by the view, a nearer plane, the range or a jump: the comparisons' cut (§II.C).
  bool ViewCut(int e) const { return cut[e] && !coarse[e]; }

  Eigen::Vector2d Direction() const { return {-normal.y(), normal.x()}; }
  double Alpha() const { return std::atan2(normal.x(), -normal.y()); }
  double Length() const { return (edge[1] - edge[0]).norm(); }
};

// One observation of a wall put into the world with the pose it was made from: all a later
// placement needs of it (frame angle, both visible edges, the foot of the perpendicular from
// the sensor), so the observation itself can be dropped (bounded memory, §II.F storage).
struct SeenWall {
  bool valid = false;
  int64_t iteration = -1;
  double alpha = 0.0;
  Eigen::Vector2d edge[2] = {Eigen::Vector2d::Zero(), Eigen::Vector2d::Zero()};
  Eigen::Vector2d foot = Eigen::Vector2d::Zero();
  bool cut[2] = {false, false};  // the edge was where the view cut the wall, not its end
};

// `obs` as seen from sensor pose `pose` (world <- sensor).
SeenWall SeenFrom(const Observation& obs, const geometry::Pose2& pose);

// Reduces a sensor-frame plane to a wall observation. Returns nothing for a plane that is not a
// wall (|normal.z| > max_normal_z: floor or ceiling, ignored in 2½D) or that is degenerate
// (non-finite numbers, zero normal, fewer than two vertices).
std::optional<Observation> MakeObservation(const PlaneInput& input, int64_t iteration,
                                           double max_normal_z);

// Marks the edges of this iteration's observations that a nearer plane hides: another plane
// has an edge on the same line of sight, closer to the sensor, or lies across that line of
// sight closer to the sensor (the edge is seen through a hole in it, e.g. a door in a wall the
// segmenter reports as one rectangle).
void MarkOccludedEdges(std::vector<Observation>* observations,
                       const RegistrationOptions& options = {});

// The standard deviation (rad) of an observed wall's orientation from its own fit: a line
// fitted to `support` points spread evenly over the visible length L with residual `rms` has
// slope variance rms^2 / (support L^2 / 12). Zero for an exact fit (rms 0), infinite when there
// are too few points to tell.
double OrientationSigma(const Observation& obs);

// The weight 1 / (sigma^2 + floor^2) an observed wall's orientation gets from OrientationSigma,
// with a floor (FitOptions::orientation_floor, the map's own error) so the best-fitting walls do
// not take all the weight.
double OrientationWeight(const Observation& obs, const FitOptions& fit);

// rad: how far a piece's fitted orientation may be off whatever its points' spread says,
// atan(FitOptions::piece_blur / length) (the segmenter gives a short piece some of its
// neighbour's points).
double PieceBlur(const Observation& obs, const FitOptions& fit);
// The same for a piece `length` metres long.
double PieceBlurOfLength(double length, const FitOptions& fit);

// Frame angle of a wall with unit 2D normal n.
inline double AlphaOf(const Eigen::Vector2d& n) { return std::atan2(n.x(), -n.y()); }
// Unit 2D normal of a wall with frame angle alpha.
inline Eigen::Vector2d NormalOf(double alpha) { return {std::sin(alpha), -std::cos(alpha)}; }
inline Eigen::Vector2d DirectionOf(double alpha) { return {std::cos(alpha), std::sin(alpha)}; }

}  // namespace relplane::mapper
