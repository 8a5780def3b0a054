#include "relplane/segment/plane_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <limits>

#include "relplane/eval/json_writer.hpp"

namespace relplane::segment {
namespace {

std::string Format(const char* format, ...) __attribute__((format(printf, 1, 2)));
std::string Format(const char* format, ...) {
  char line[256];
  va_list args;
  va_start(args, format);
  std::vsnprintf(line, sizeof line, format, args);
  va_end(args);
  return line;
}

}  // namespace

Eigen::Vector2f ExtentSize(const segmenter::DetectedPlane& plane) {
  if (plane.vertices.empty()) return Eigen::Vector2f::Zero();
  const Eigen::Vector3f n = plane.normal.normalized();
  // The plane's horizontal direction; a horizontal plane has none, so use the sensor's x.
  Eigen::Vector3f along = Eigen::Vector3f::UnitZ().cross(n);
  if (along.norm() < 1e-3f) along = Eigen::Vector3f::UnitX() - n * n.x();
  along.normalize();
  const Eigen::Vector3f across = n.cross(along);
  float lo[2] = {std::numeric_limits<float>::max(), std::numeric_limits<float>::max()};
  float hi[2] = {std::numeric_limits<float>::lowest(), std::numeric_limits<float>::lowest()};
  for (const Eigen::Vector3f& v : plane.vertices) {
    const float c[2] = {v.dot(along), v.dot(across)};
    for (int k = 0; k < 2; ++k) lo[k] = std::min(lo[k], c[k]), hi[k] = std::max(hi[k], c[k]);
  }
  return {hi[0] - lo[0], hi[1] - lo[1]};
}

std::string PlaneTable(const FramePlanes& frame) {
  std::string s = Format("%s: %zu planes, %lld points (%lld invalid)\n", frame.name.c_str(),
                         frame.planes.size(), static_cast<long long>(frame.points),
                         static_cast<long long>(frame.invalid_points));
  if (frame.planes.empty()) return s;
  s += "   #   normal x   normal y   normal z     d (m)    points  rms (mm)  extent (m)\n";
  for (size_t k = 0; k < frame.planes.size(); ++k) {
    const segmenter::DetectedPlane& p = frame.planes[k];
    const Eigen::Vector2f size = ExtentSize(p);
    s += Format("%4zu  %9.4f  %9.4f  %9.4f  %8.4f  %8d  %8.1f  %.2f x %.2f\n", k, p.normal.x(),
                p.normal.y(), p.normal.z(), p.d, p.num_points, 1000.0 * p.rms, size.x(), size.y());
  }
  return s;
}

std::string PlanesJson(const std::vector<FramePlanes>& frames) {
  eval::JsonWriter json;
  json.BeginObject().Field("schema", "relplane-segment/1");
  json.Key("frames").BeginArray();
  for (const FramePlanes& frame : frames) {
    json.BeginObject().Field("file", frame.name).Field("points", frame.points);
    json.Field("invalid_points", frame.invalid_points);
    json.Key("planes").BeginArray();
    for (const segmenter::DetectedPlane& p : frame.planes) {
      const Eigen::Vector3d n = p.normal.cast<double>();
      const Eigen::Vector3d c = p.centroid.cast<double>();
      const Eigen::Vector2d size = ExtentSize(p).cast<double>();
      json.BeginObject();
      json.Key("normal").Vector(n.data(), 3);
      json.Field("d", static_cast<double>(p.d));
      json.Key("centroid").Vector(c.data(), 3);
      json.Field("points", p.num_points).Field("rms", static_cast<double>(p.rms));
      json.Key("extent_size").Vector(size.data(), 2);
      json.Key("vertices").BeginArray();
      for (const Eigen::Vector3f& v : p.vertices) {
        const Eigen::Vector3d vd = v.cast<double>();
        json.Vector(vd.data(), 3);
      }
      json.EndArray().EndObject();
    }
    json.EndArray().EndObject();
  }
  json.EndArray().EndObject();
  return json.Str() + "\n";
}

}  // namespace relplane::segment
