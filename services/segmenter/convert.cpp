#include "convert.hpp"

namespace relplane::segmenter {

bool FromPointCloud(const point_cloud_t& msg, Cloud* cloud, std::string* reason) {
  const size_t n = msg.num_points < 0 ? 0 : static_cast<size_t>(msg.num_points);
  if (msg.num_points < 0 || msg.x.size() != n || msg.y.size() != n || msg.z.size() != n) {
    *reason = "num_points " + std::to_string(msg.num_points) + " disagrees with its arrays";
    return false;
  }
  cloud->x = msg.x;
  cloud->y = msg.y;
  cloud->z = msg.z;
  return true;
}

plane_set_t ToPlaneSet(const Result& result, int64_t utime, int64_t seq) {
  plane_set_t msg;
  msg.utime = utime;
  msg.seq = seq;
  msg.num_planes = static_cast<int32_t>(result.planes.size());
  for (size_t k = 0; k < result.planes.size(); ++k) {
    const DetectedPlane& p = result.planes[k];
    plane_t out;
    out.id = static_cast<int64_t>(k);
    for (int a = 0; a < 3; ++a) {
      out.normal[a] = p.normal[a];
      out.centroid[a] = p.centroid[a];
    }
    out.d = p.d;
    out.num_vertices = static_cast<int32_t>(p.vertices.size());
    for (const auto& v : p.vertices) out.vertices.push_back({v.x(), v.y(), v.z()});
    out.num_points = p.num_points;
    out.rms = p.rms;
    msg.planes.push_back(out);
  }
  return msg;
}

}  // namespace relplane::segmenter
