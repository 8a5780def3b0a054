#include "convert.hpp"

#include <cmath>

#include "relplane/common/covariance.hpp"
#include "relplane/common/geometry.hpp"

namespace relplane::mapper {
namespace {

bool Finite3(const float v[3]) {
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

int8_t StatusCode(PoseStatus status) {
  switch (status) {
    case PoseStatus::kTracking: return pose_t::STATUS_TRACKING;
    case PoseStatus::kMotionModel: return pose_t::STATUS_MOTION_MODEL;
    case PoseStatus::kInitializing: return pose_t::STATUS_INITIALIZING;
    case PoseStatus::kLost: return pose_t::STATUS_LOST;
  }
  return pose_t::STATUS_LOST;
}

}  // namespace

bool FromPlaneSet(const plane_set_t& msg, std::vector<PlaneInput>* planes, std::string* reason) {
  planes->clear();
  if (msg.num_planes < 0 || static_cast<size_t>(msg.num_planes) != msg.planes.size()) {
    *reason = "plane count does not match the planes";
    return false;
  }
  for (const plane_t& p : msg.planes) {
    if (!Finite3(p.normal) || !std::isfinite(p.d) || !Finite3(p.centroid)) {
      *reason = "plane " + std::to_string(p.id) + " has a non-finite number";
      return false;
    }
    const double norm = std::sqrt(p.normal[0] * p.normal[0] + p.normal[1] * p.normal[1] +
                                  p.normal[2] * p.normal[2]);
    if (norm < 1e-6) {
      *reason = "plane " + std::to_string(p.id) + " has a zero normal";
      return false;
    }
    if (p.num_vertices < 0 || static_cast<size_t>(p.num_vertices) != p.vertices.size()) {
      *reason = "plane " + std::to_string(p.id) + " vertex count does not match";
      return false;
    }
    PlaneInput in;
    in.normal = Eigen::Vector3d(p.normal[0], p.normal[1], p.normal[2]);
    in.d = p.d;
    in.centroid = Eigen::Vector3d(p.centroid[0], p.centroid[1], p.centroid[2]);
    for (const auto& v : p.vertices) {
      if (!Finite3(v.data())) {
        *reason = "plane " + std::to_string(p.id) + " has a non-finite vertex";
        return false;
      }
      in.vertices.emplace_back(v[0], v[1], v[2]);
    }
    in.support = p.num_points;
    in.rms = p.rms;
    planes->push_back(std::move(in));
  }
  return true;
}

bool FromOdometry(const odometry_t& msg, OdometryReading* reading, std::string* reason) {
  for (const double v : msg.position) {
    if (!std::isfinite(v)) {
      *reason = "non-finite position";
      return false;
    }
  }
  const Eigen::Quaterniond q = geometry::QuaternionFromWxyz(msg.orientation);
  const double norm = q.norm();
  if (!std::isfinite(norm) || norm < 1e-9) {
    *reason = "invalid orientation quaternion";
    return false;
  }
  if (!geometry::ValidCovariance(msg.covariance, reason)) return false;
  reading->utime = msg.utime;
  reading->seq = msg.seq;
  reading->pose = {msg.position[0], msg.position[1], geometry::YawOf(q.normalized())};
  reading->covariance = geometry::CovarianceFromRowMajor(msg.covariance);
  return true;
}

pose_t ToPoseMessage(const PoseEstimate& estimate, const Eigen::Matrix3d& covariance, double z,
                     int64_t utime, int64_t seq) {
  pose_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.position[0] = estimate.pose.x;
  msg.position[1] = estimate.pose.y;
  msg.position[2] = z;
  const Eigen::Quaterniond q(Eigen::AngleAxisd(estimate.pose.yaw, Eigen::Vector3d::UnitZ()));
  geometry::QuaternionToWxyz(q, msg.orientation);
  msg.status = StatusCode(estimate.status);
  geometry::CovarianceToRowMajor(covariance, msg.covariance);
  return msg;
}

map_t ToMapMessage(const MapSnapshot& map, int64_t utime, int64_t seq) {
  map_t msg;
  msg.utime = utime;
  msg.seq = seq;
  for (const MappedPlane& m : map.planes) {
    plane_t p;
    p.id = m.id;
    for (int k = 0; k < 3; ++k) {
      p.normal[k] = static_cast<float>(m.normal[k]);
      p.centroid[k] = static_cast<float>(m.centroid[k]);
    }
    p.d = static_cast<float>(m.d);
    for (const auto& v : m.vertices) {
      p.vertices.push_back({static_cast<float>(v.x()), static_cast<float>(v.y()),
                            static_cast<float>(v.z())});
    }
    p.num_vertices = static_cast<int32_t>(p.vertices.size());
    p.num_points = static_cast<int32_t>(m.observations);
    p.rms = 0.0f;
    msg.planes.push_back(std::move(p));
  }
  msg.num_planes = static_cast<int32_t>(msg.planes.size());
  for (const MappedGroup& g : map.groups) {
    group_t out;
    out.id = g.id;
    out.basis_id = g.basis;
    out.members = g.members;
    out.num_members = static_cast<int32_t>(out.members.size());
    msg.groups.push_back(std::move(out));
  }
  msg.num_groups = static_cast<int32_t>(msg.groups.size());
  return msg;
}

}  // namespace relplane::mapper
