#include "convert.hpp"

#include <algorithm>
#include <iterator>

#include "relplane/common/covariance.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::sim {

point_cloud_t ToPointCloud(const Scan& scan, int64_t seq, int64_t utime) {
  point_cloud_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.num_points = static_cast<int32_t>(scan.points.size());
  msg.x.resize(scan.points.size());
  msg.y.resize(scan.points.size());
  msg.z.resize(scan.points.size());
  for (size_t i = 0; i < scan.points.size(); ++i) {
    msg.x[i] = scan.points[i].x();
    msg.y[i] = scan.points[i].y();
    msg.z[i] = scan.points[i].z();
  }
  return msg;
}

pose_t ToTruthPose(const Eigen::Isometry3d& pose, int64_t seq, int64_t utime) {
  pose_t msg;
  msg.utime = utime;
  msg.seq = seq;
  for (int i = 0; i < 3; ++i) msg.position[i] = pose.translation()[i];
  geometry::QuaternionToWxyz(Eigen::Quaterniond(pose.rotation()), msg.orientation);
  msg.status = pose_t::STATUS_TRUTH;
  std::fill(std::begin(msg.covariance), std::end(msg.covariance), 0.0);  // the truth is exact
  return msg;
}

odometry_t ToOdometry(const OdometryReading& reading, int64_t utime) {
  odometry_t msg;
  msg.utime = utime;
  msg.seq = reading.seq;
  msg.position[0] = reading.pose.x;
  msg.position[1] = reading.pose.y;
  msg.position[2] = 0.0;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(reading.pose.yaw, Eigen::Vector3d::UnitZ()));
  geometry::QuaternionToWxyz(q, msg.orientation);
  geometry::CovarianceToRowMajor(reading.covariance, msg.covariance);
  return msg;
}

map_t ToWorldMap(const std::vector<TruePlane>& planes, int64_t seq, int64_t utime) {
  map_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.num_planes = static_cast<int32_t>(planes.size());
  msg.planes.resize(planes.size());
  for (size_t i = 0; i < planes.size(); ++i) {
    const TruePlane& p = planes[i];
    plane_t& out = msg.planes[i];
    out.id = p.id;
    for (int k = 0; k < 3; ++k) {
      out.normal[k] = static_cast<float>(p.normal[k]);
      out.centroid[k] = static_cast<float>(p.centroid[k]);
    }
    out.d = static_cast<float>(p.d);
    out.num_vertices = 4;
    out.vertices.assign(4, std::vector<float>(3));
    for (int c = 0; c < 4; ++c) {
      for (int k = 0; k < 3; ++k) out.vertices[c][k] = static_cast<float>(p.corners[c][k]);
    }
    out.num_points = 0;
    out.rms = 0.0f;
  }
  msg.num_groups = 0;
  return msg;
}

}  // namespace relplane::sim
