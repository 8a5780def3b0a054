#include "relplane/mapper/observation.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

namespace relplane::mapper {
namespace {

bool Finite(const Eigen::Vector3d& v) { return v.allFinite(); }

}  // namespace

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

void MarkOccludedEdges(std::vector<Observation>* observations) {
  constexpr double kBearing = 0.0175;  // rad: same line of sight
  constexpr double kNearer = 0.05;     // m
  auto& obs = *observations;
  for (size_t a = 0; a < obs.size(); ++a) {
    for (int e = 0; e < 2; ++e) {
      const Eigen::Vector2d& p = obs[a].edge[e];
      const double bearing = std::atan2(p.y(), p.x()), range = p.norm();
      for (size_t b = 0; b < obs.size() && !obs[a].cut[e]; ++b) {
        if (b == a) continue;
        for (const Eigen::Vector2d& q : obs[b].edge) {
          const double db = std::abs(std::remainder(std::atan2(q.y(), q.x()) - bearing, 2 * M_PI));
          if (db < kBearing && q.norm() < range - kNearer) obs[a].cut[e] = true;
        }
      }
    }
  }
}

}  // namespace relplane::mapper
