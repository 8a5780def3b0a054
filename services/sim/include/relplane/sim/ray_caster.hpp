#pragma once
// Ray casting against every rectangle of a world, with occlusion: each ray returns its nearest
// hit. A level sensor that only yaws (DESIGN.md "Frames") has rays in columns that each lie in
// one vertical plane, so walls are culled and ordered once per column in the floor plan
// (2½D, like a column renderer) and each ray then tests only the walls its column crosses, in
// order of distance, stopping at the first hit. Floor, ceiling and other non-vertical
// rectangles are tested per ray. Results equal brute force over every rectangle bit for bit:
// both use one intersection routine and one tie rule, and the culling is conservative.

#include <Eigen/Core>
#include <vector>

#include "relplane/sim/world.hpp"

namespace relplane::sim {

// The nearest hit of one ray: range along the ray (metres) and the rectangle's index in the
// world, or rect = -1 when nothing is hit within the maximum range.
struct Hit {
  double range = 0.0;
  int rect = -1;
};

// The rays of a sensor, in its frame (x forward, y left, z up), column by column (leftmost
// column first, top row first within a column): the caster walks a column at a time, so this
// order keeps its memory access sequential. All rays of one column share one horizontal
// direction.
struct RayGrid {
  int width = 0;
  int height = 0;
  std::vector<Eigen::Vector3d> directions;         // unit, index col * height + row
  std::vector<Eigen::Vector2d> column_directions;  // unit horizontal direction per column
  std::vector<double> horizontal;  // per ray: length of the direction's x-y part (> 0)

  // A pinhole (depth camera) grid: pixel centres of a width x height image spanning the
  // horizontal and vertical fields of view (radians, each < pi).
  static RayGrid Pinhole(int width, int height, double hfov, double vfov);
};

class RayCaster {
 public:
  explicit RayCaster(const World& world);

  // Casts every ray of `grid` from a level sensor at `origin` (world frame) turned by `yaw`
  // about z. `hits` gets one entry per ray, in the grid's order.
  void Cast(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid, double max_range,
            std::vector<Hit>* hits);

  // The reference: every ray tested against every rectangle.
  void CastBruteForce(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid,
                      double max_range, std::vector<Hit>* hits) const;

  // One ray in the world frame against every rectangle.
  Hit CastOneBruteForce(const Eigen::Vector3d& origin, const Eigen::Vector3d& direction,
                        double max_range) const;

 private:
  // A rectangle with what the intersection test needs, computed once.
  struct Prepared {
    Eigen::Vector3d normal;
    double d = 0.0;
    Eigen::Vector3d origin;
    Eigen::Vector3d u_scaled;  // u / |u|^2, so (p - origin) . u_scaled is in [0, 1] inside
    Eigen::Vector3d v_scaled;
  };
  // A vertical rectangle seen from above: a segment of the floor plan.
  struct Footprint {
    int rect = 0;
    Eigen::Vector2d a;
    Eigen::Vector2d b;
    double margin = 0.0;  // tolerance covering the test's edge slack and non-verticality
    double z_min = 0.0;   // height extent of the rectangle, widened by that tolerance
    double z_max = 0.0;
  };
  struct Candidate {
    double s_low;   // lower bound of the horizontal distance at which the ray can hit it
    double s_high;  // upper bound (infinity when unknown)
    double z_min;
    double z_max;
    int rect;
    bool operator<(const Candidate& o) const {
      return s_low < o.s_low || (s_low == o.s_low && rect < o.rect);
    }
  };

  static bool Intersect(const Prepared& r, const Eigen::Vector3d& o, const Eigen::Vector3d& dir,
                        double max_range, double* t);
  static void Consider(const Prepared& r, int index, const Eigen::Vector3d& o,
                       const Eigen::Vector3d& dir, double max_range, Hit* best);
  void CullForFrame(const Eigen::Vector3d& origin, double yaw, const RayGrid& grid,
                    double max_range);
  void ColumnCandidates(const Eigen::Vector2d& o2, const Eigen::Vector2d& c);

  std::vector<Prepared> rects_;
  std::vector<Footprint> walls_;  // vertical rectangles
  std::vector<int> others_;       // everything else (floor, ceiling, tilted)
  // Per-frame and per-column scratch.
  std::vector<const Footprint*> frame_walls_;
  std::vector<int> frame_others_;
  std::vector<Candidate> column_;
};

// Rotates a sensor-frame direction about z; the one rotation both casting paths use.
inline Eigen::Vector3d RotateYaw(double cos_yaw, double sin_yaw, const Eigen::Vector3d& v) {
  return {cos_yaw * v.x() - sin_yaw * v.y(), sin_yaw * v.x() + cos_yaw * v.y(), v.z()};
}

}  // namespace relplane::sim
