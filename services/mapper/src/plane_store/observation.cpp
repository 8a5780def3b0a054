#include "plane_store/observation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relplane::mapper {
namespace {

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

SeenWall SeenFrom(const Observation& obs, const geometry::Pose2& pose) {
  SeenWall seen;
  seen.valid = true;
  seen.iteration = obs.iteration;
  seen.alpha = geometry::WrapAngle(pose.yaw + obs.Alpha());
  seen.edge[0] = pose * obs.edge[0];
  seen.edge[1] = pose * obs.edge[1];
  seen.foot = pose * Eigen::Vector2d(-obs.d * obs.normal);
  seen.cut[0] = obs.cut[0], seen.cut[1] = obs.cut[1];
  return seen;
}

std::optional<Observation> MakeObservation(const PlaneInput& input, int64_t iteration,
                                           double max_normal_z) {
  if (!Finite(input.normal) || !std::isfinite(input.d) || !Finite(input.centroid)) return {};
  const double norm = input.normal.norm();
  if (norm < 1e-6 || input.vertices.size() < 2) return {};
  for (const auto& v : input.vertices) {
    if (!Finite(v)) return {};
  }
  Eigen::Vector3d n3 = input.normal / norm;
  const double d = input.d / norm;
  if (std::abs(n3.z()) > max_normal_z) return {};
  // 2½D: the wall's line in the x-y plane, through the centroid of its support.
  Observation obs;
  obs.iteration = iteration;
  obs.normal = n3.head<2>().normalized();
  obs.d = -obs.normal.dot(input.centroid.head<2>());
  (void)d;
  if (obs.d < 0.0) {  // keep the normal towards the sensor whatever the producer sent
    obs.normal = -obs.normal;
    obs.d = -obs.d;
    n3 = -n3;
  }
  obs.normal3 = n3;
  obs.centroid = input.centroid;
  const Eigen::Vector2d t = obs.Direction();
  const Eigen::Vector2d foot = -obs.d * obs.normal;  // closest point of the line to the sensor
  double s_min = std::numeric_limits<double>::infinity();
  double s_max = -s_min;
  obs.z_min = s_min;
  obs.z_max = s_max;
  obs.box.setEmpty();
  for (const auto& v : input.vertices) {
    const double s = t.dot(v.head<2>() - foot);
    s_min = std::min(s_min, s);
    s_max = std::max(s_max, s);
    obs.z_min = std::min(obs.z_min, v.z());
    obs.z_max = std::max(obs.z_max, v.z());
    obs.box.extend(v);
  }
  obs.edge[0] = foot + s_min * t;
  obs.edge[1] = foot + s_max * t;
  obs.vertices = input.vertices;
  obs.support = input.support;
  obs.rms = input.rms;
  return obs;
}

namespace {

// Distance along the unit ray u from the sensor to the line of `obs`, or infinity when the ray
// does not meet it in front of the sensor.
double RayToLine(const Observation& obs, const Eigen::Vector2d& u) {
  const double along = obs.normal.dot(u);
  if (along > -1e-6) return std::numeric_limits<double>::infinity();
  return obs.d / -along;
}

}  // namespace

void MarkOccludedEdges(std::vector<Observation>* observations, const RegistrationOptions& options) {
  auto& obs = *observations;
  // Each plane's view, as bearings from its first edge counter-clockwise: worked out once
  // rather than for every edge tested against it (four arctangents a pair, a tenth of the
  // mapper's time at 30 planes in view).
  struct View {
    double lo = 0.0, span = 0.0;
    bool swapped = false;  // edge 1 is the first counter-clockwise
  };
  std::vector<View> views(obs.size());
  for (size_t b = 0; b < obs.size(); ++b) {
    View& v = views[b];
    v.lo = std::atan2(obs[b].edge[0].y(), obs[b].edge[0].x());
    v.span = std::remainder(std::atan2(obs[b].edge[1].y(), obs[b].edge[1].x()) - v.lo, 2 * M_PI);
    if (v.span < 0.0) v.lo += v.span, v.span = -v.span, v.swapped = true;
  }
  for (size_t a = 0; a < obs.size(); ++a) {
    for (int e = 0; e < 2; ++e) {
      const Eigen::Vector2d& p = obs[a].edge[e];
      const double range = p.norm();
      if (range < 1e-6) continue;
      const Eigen::Vector2d u = p / range;
      const double bearing = std::atan2(p.y(), p.x());
      for (size_t b = 0; b < obs.size() && !obs[a].cut[e]; ++b) {
        if (b == a) continue;
        // The edge is seen past a nearer plane: past its end, or through a hole in it (a door
        // in a wall the segmenter reports as one rectangle). A wall end is never seen there.
        const View& v = views[b];
        const double off = std::remainder(bearing - v.lo, 2 * M_PI);
        if (off < -options.occlusion_bearing || off > v.span + options.occlusion_bearing) continue;
        const Eigen::Vector2d& first = obs[b].edge[v.swapped ? 1 : 0];
        const Eigen::Vector2d& last = obs[b].edge[v.swapped ? 0 : 1];
        // Within the plane's view: its line on this ray; just beside it: its edge there.
        const double nearest = off < 0.0      ? first.norm()
                               : off > v.span ? last.norm()
                                              : RayToLine(obs[b], u);
        if (nearest < range - options.occlusion_nearer) obs[a].cut[e] = true;
      }
    }
  }
}

double OrientationSigma(const Observation& obs) {
  if (obs.rms <= 0.0) return 0.0;
  if (obs.support < 3) return std::numeric_limits<double>::infinity();
  const double spread = obs.Length() * std::sqrt(static_cast<double>(obs.support) / 12.0);
  return spread > 0.0 ? obs.rms / spread : std::numeric_limits<double>::infinity();
}

double PieceBlurOfLength(double length, const FitOptions& fit) {
  return std::atan2(fit.piece_blur, std::max(length, 1e-3));
}

double PieceBlur(const Observation& obs, const FitOptions& fit) {
  return PieceBlurOfLength(obs.Length(), fit);
}

double OrientationWeight(const Observation& obs, const FitOptions& fit) {
  const double sigma = std::min(OrientationSigma(obs), 1.0);
  return 1.0 / (sigma * sigma + fit.orientation_floor * fit.orientation_floor);
}

}  // namespace relplane::mapper
