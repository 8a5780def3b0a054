#include "convert.hpp"

namespace relplane::segmenter {
namespace {

bool Consistent(const point_cloud_t& msg, std::string* reason) {
  const size_t n = msg.num_points < 0 ? 0 : static_cast<size_t>(msg.num_points);
  if (msg.num_points < 0 || msg.x.size() != n || msg.y.size() != n || msg.z.size() != n) {
    *reason = "num_points " + std::to_string(msg.num_points) + " disagrees with its arrays";
    return false;
  }
  return true;
}

}  // namespace

bool FromPointCloud(const point_cloud_t& msg, Cloud* cloud, std::string* reason) {
  if (!Consistent(msg, reason)) return false;
  cloud->x = msg.x;
  cloud->y = msg.y;
  cloud->z = msg.z;
  return true;
}

bool TakePointCloud(point_cloud_t* msg, Cloud* cloud, std::string* reason) {
  if (!Consistent(*msg, reason)) return false;
  cloud->x.swap(msg->x);
  cloud->y.swap(msg->y);
  cloud->z.swap(msg->z);
  return true;
}

plane_set_t ToPlaneSet(const Result& result, int64_t utime, int64_t seq) {
  plane_set_t msg;
  ToPlaneSet(result, utime, seq, &msg);
  return msg;
}

void ToPlaneSet(const Result& result, int64_t utime, int64_t seq, plane_set_t* msg) {
  msg->utime = utime;
  msg->seq = seq;
  msg->num_planes = static_cast<int32_t>(result.planes.size());
  msg->planes.resize(result.planes.size());
  for (size_t k = 0; k < result.planes.size(); ++k) {
    const DetectedPlane& p = result.planes[k];
    plane_t& out = msg->planes[k];
    out.id = static_cast<int64_t>(k);
    for (int a = 0; a < 3; ++a) {
      out.normal[a] = p.normal[a];
      out.centroid[a] = p.centroid[a];
    }
    out.d = p.d;
    out.num_vertices = static_cast<int32_t>(p.vertices.size());
    out.vertices.resize(p.vertices.size());
    for (size_t v = 0; v < p.vertices.size(); ++v) {
      out.vertices[v].assign({p.vertices[v].x(), p.vertices[v].y(), p.vertices[v].z()});
    }
    out.num_points = p.num_points;
    out.rms = p.rms;
  }
}

}  // namespace relplane::segmenter
