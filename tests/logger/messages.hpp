#pragma once
// Hand-made bus messages for the recorder, eval and logger tests.

#include <relplane/map_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>
#include <string>
#include <vector>

#include "relplane/eval/types.hpp"

namespace relplane::testing {

template <class M>
std::vector<uint8_t> Encode(const M& msg) {
  std::vector<uint8_t> buffer(static_cast<size_t>(msg.getEncodedSize()));
  msg.encode(buffer.data(), 0, static_cast<int>(buffer.size()));
  return buffer;
}

inline relplane::pose_t PoseMessage(const eval::PoseSample& p) {
  relplane::pose_t msg;
  msg.utime = p.utime;
  msg.seq = p.seq;
  for (int i = 0; i < 3; ++i) msg.position[i] = p.position[i];
  msg.orientation[0] = p.orientation.w();
  msg.orientation[1] = p.orientation.x();
  msg.orientation[2] = p.orientation.y();
  msg.orientation[3] = p.orientation.z();
  msg.status = static_cast<int8_t>(p.status);
  for (int r = 0; r < 3; ++r) {
    for (int k = 0; k < 3; ++k) msg.covariance[3 * r + k] = p.covariance(r, k);
  }
  return msg;
}

inline relplane::map_t MapMessage(const eval::MapSnapshot& map) {
  relplane::map_t msg;
  msg.utime = map.utime;
  msg.seq = map.seq;
  for (const eval::PlaneRecord& p : map.planes) {
    relplane::plane_t plane;
    plane.id = p.id;
    for (int i = 0; i < 3; ++i) {
      plane.normal[i] = static_cast<float>(p.normal[i]);
      plane.centroid[i] = static_cast<float>(p.centroid[i]);
    }
    plane.d = static_cast<float>(p.d);
    for (const Eigen::Vector3d& v : p.vertices) {
      plane.vertices.push_back(
          {static_cast<float>(v.x()), static_cast<float>(v.y()), static_cast<float>(v.z())});
    }
    plane.num_vertices = static_cast<int32_t>(plane.vertices.size());
    plane.num_points = static_cast<int32_t>(p.observations);
    plane.rms = 0.0f;
    msg.planes.push_back(plane);
  }
  msg.num_planes = static_cast<int32_t>(msg.planes.size());
  for (const eval::GroupRecord& g : map.groups) {
    relplane::group_t group;
    group.id = g.id;
    group.basis_id = g.basis_id;
    group.members = g.members;
    group.num_members = static_cast<int32_t>(g.members.size());
    msg.groups.push_back(group);
  }
  msg.num_groups = static_cast<int32_t>(msg.groups.size());
  return msg;
}

inline relplane::plane_set_t PlanesMessage(int64_t seq) {
  relplane::plane_set_t msg;
  msg.utime = seq * 100000;
  msg.seq = seq;
  msg.num_planes = 0;
  return msg;
}

inline relplane::status_t StatusMessage(const std::string& service, int64_t processed,
                                        float p99_ms) {
  relplane::status_t msg;
  msg.utime = 0;
  msg.service = service;
  msg.frames_processed = processed;
  msg.frames_dropped = 2;
  msg.inputs_rejected = 0;
  msg.p50_ms = p99_ms / 2;
  msg.p99_ms = p99_ms;
  msg.max_ms = p99_ms + 1;
  msg.last_seq = processed - 1;
  msg.detail = "";
  return msg;
}

}  // namespace relplane::testing
