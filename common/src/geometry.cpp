#include "relplane/common/geometry.hpp"

#include <Eigen/Eigenvalues>
#include <algorithm>

namespace relplane::geometry {

double WrapAngle(double angle) {
  angle = std::fmod(angle + M_PI, 2.0 * M_PI);
  if (angle <= 0.0) angle += 2.0 * M_PI;
  return angle - M_PI;
}

Eigen::Vector2d Pose2::operator*(const Eigen::Vector2d& p) const {
  return Rotation() * p + Translation();
}

Pose2 Pose2::operator*(const Pose2& other) const {
  const Eigen::Vector2d t = (*this) * other.Translation();
  return {t.x(), t.y(), WrapAngle(yaw + other.yaw)};
}

Pose2 Pose2::Inverse() const {
  const Eigen::Vector2d t = -(Rotation().inverse() * Translation());
  return {t.x(), t.y(), WrapAngle(-yaw)};
}

Eigen::Isometry3d ToIsometry(const Pose2& pose, double z) {
  Eigen::Isometry3d iso = Eigen::Isometry3d::Identity();
  iso.linear() = Eigen::AngleAxisd(pose.yaw, Eigen::Vector3d::UnitZ()).toRotationMatrix();
  iso.translation() = Eigen::Vector3d(pose.x, pose.y, z);
  return iso;
}

Pose2 ToPose2(const Eigen::Isometry3d& pose) {
  const Eigen::Vector3d x_axis = pose.linear().col(0);
  return {pose.translation().x(), pose.translation().y(), std::atan2(x_axis.y(), x_axis.x())};
}

Eigen::Quaterniond QuaternionFromWxyz(const double wxyz[4]) {
  return Eigen::Quaterniond(wxyz[0], wxyz[1], wxyz[2], wxyz[3]).normalized();
}

void QuaternionToWxyz(const Eigen::Quaterniond& q, double wxyz[4]) {
  wxyz[0] = q.w();
  wxyz[1] = q.x();
  wxyz[2] = q.y();
  wxyz[3] = q.z();
}

double YawOf(const Eigen::Quaterniond& q) {
  const Eigen::Vector3d x_axis = q * Eigen::Vector3d::UnitX();
  return std::atan2(x_axis.y(), x_axis.x());
}

Plane Plane::FacingPoint(const Eigen::Vector3d& viewpoint) const {
  if (SignedDistance(viewpoint) >= 0.0) return *this;
  return {-normal, -d};
}

Plane Plane::Transformed(const Eigen::Isometry3d& pose) const {
  // A point p on the plane maps to q = R p + t, so n' = R n and d' = d - n' . t.
  Plane out;
  out.normal = pose.linear() * normal;
  out.d = d - out.normal.dot(pose.translation());
  return out;
}

double Plane::AngleTo(const Plane& other, bool unsigned_normals) const {
  double c = std::clamp(normal.dot(other.normal), -1.0, 1.0);
  if (unsigned_normals) c = std::abs(c);
  return std::acos(c);
}

bool FitPlane(const std::vector<Eigen::Vector3d>& points, Plane* plane, double* rms) {
  if (points.size() < 3) return false;
  Eigen::Vector3d mean = Eigen::Vector3d::Zero();
  for (const auto& p : points) mean += p;
  mean /= static_cast<double>(points.size());
  Eigen::Matrix3d scatter = Eigen::Matrix3d::Zero();
  for (const auto& p : points) scatter += (p - mean) * (p - mean).transpose();
  Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(scatter);
  if (solver.info() != Eigen::Success) return false;
  // Two non-zero spreads are needed, otherwise the points lie on a line.
  if (solver.eigenvalues()(1) <= 1e-12 * std::max(1.0, solver.eigenvalues()(2))) return false;
  plane->normal = solver.eigenvectors().col(0).normalized();
  plane->d = -plane->normal.dot(mean);
  if (rms != nullptr) *rms = std::sqrt(std::max(0.0, solver.eigenvalues()(0)) / points.size());
  return true;
}

Eigen::Vector2d Segment2::Direction() const {
  const Eigen::Vector2d v = b - a;
  const double n = v.norm();
  return n > 0.0 ? Eigen::Vector2d(v / n) : Eigen::Vector2d::Zero();
}

Eigen::Vector2d Segment2::Normal() const {
  const Eigen::Vector2d u = Direction();
  return {-u.y(), u.x()};
}

double Segment2::DistanceTo(const Eigen::Vector2d& p) const {
  const Eigen::Vector2d v = b - a;
  const double len2 = v.squaredNorm();
  if (len2 == 0.0) return (p - a).norm();
  const double t = std::clamp((p - a).dot(v) / len2, 0.0, 1.0);
  return (a + t * v - p).norm();
}

double LineAngle(const Segment2& s, const Segment2& t) {
  const double c = std::abs(s.Direction().dot(t.Direction()));
  return std::acos(std::clamp(c, 0.0, 1.0));
}

}  // namespace relplane::geometry
