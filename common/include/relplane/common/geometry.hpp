#pragma once
// SE(2)/SE(3) and plane/segment geometry shared by every part of relplane.
// Conventions: metres and radians; world frame z up; sensor frame x forward, y left, z up.

#include <Eigen/Geometry>
#include <cmath>
#include <vector>

namespace relplane::geometry {

// Wraps an angle into (-pi, pi].
double WrapAngle(double angle);

// A planar pose (x, y, yaw) as the 2½D robot moves (DESIGN.md "Frames").
struct Pose2 {
  double x = 0.0;
  double y = 0.0;
  double yaw = 0.0;

  Eigen::Vector2d Translation() const { return {x, y}; }
  Eigen::Rotation2Dd Rotation() const { return Eigen::Rotation2Dd(yaw); }
  // Maps a point given in this pose's frame into the parent frame.
  Eigen::Vector2d operator*(const Eigen::Vector2d& p) const;
  Pose2 operator*(const Pose2& other) const;
  Pose2 Inverse() const;
};

// Lifts a planar pose into 3D at height z.
Eigen::Isometry3d ToIsometry(const Pose2& pose, double z = 0.0);
// Projects a 3D pose onto the x-y plane (yaw from the rotated x axis).
Pose2 ToPose2(const Eigen::Isometry3d& pose);

// Quaternion (w, x, y, z) <-> rotation; pose_t stores w first.
Eigen::Quaterniond QuaternionFromWxyz(const double wxyz[4]);
void QuaternionToWxyz(const Eigen::Quaterniond& q, double wxyz[4]);
double YawOf(const Eigen::Quaterniond& q);

// A plane n . p + d = 0 with unit normal n.
struct Plane {
  Eigen::Vector3d normal = Eigen::Vector3d::UnitZ();
  double d = 0.0;

  double SignedDistance(const Eigen::Vector3d& p) const { return normal.dot(p) + d; }
  Eigen::Vector3d Project(const Eigen::Vector3d& p) const { return p - SignedDistance(p) * normal; }
  // The same plane with its normal pointing towards `viewpoint` (distance >= 0 there).
  Plane FacingPoint(const Eigen::Vector3d& viewpoint) const;
  // The plane expressed in the parent frame of `pose` (pose maps child -> parent).
  Plane Transformed(const Eigen::Isometry3d& pose) const;
  // Angle in radians between the two normals, sign-agnostic when `unsigned_normals`.
  double AngleTo(const Plane& other, bool unsigned_normals = false) const;
};

// Fits a plane to the points by least squares (centroid + smallest eigenvector).
// Returns false for fewer than three points or a degenerate set.
bool FitPlane(const std::vector<Eigen::Vector3d>& points, Plane* plane, double* rms = nullptr);

// A 2D line segment, e.g. a wall seen from above.
struct Segment2 {
  Eigen::Vector2d a = Eigen::Vector2d::Zero();
  Eigen::Vector2d b = Eigen::Vector2d::Zero();

  double Length() const { return (b - a).norm(); }
  Eigen::Vector2d Midpoint() const { return 0.5 * (a + b); }
  Eigen::Vector2d Direction() const;  // unit vector a -> b (zero for a degenerate segment)
  Eigen::Vector2d Normal() const;     // Direction() rotated by +90 degrees
  // Distance from p to the closest point of the segment.
  double DistanceTo(const Eigen::Vector2d& p) const;
};

// Angle between two segments' lines in [0, pi/2].
double LineAngle(const Segment2& s, const Segment2& t);

}  // namespace relplane::geometry
