#include "sampled_walls.hpp"

#include <cmath>

namespace relplane::mapper::testing {

using Eigen::Vector2d;

Observation WallOnLine(double normal_angle, double d, double along0, double along1, int support,
                       double rms) {
  Observation obs;
  obs.normal = {std::cos(normal_angle), std::sin(normal_angle)};
  obs.d = d;
  const Vector2d foot = -d * obs.normal, t = obs.Direction();
  obs.edge[0] = foot + along0 * t;
  obs.edge[1] = foot + along1 * t;
  obs.support = support;
  obs.rms = rms;
  return obs;
}

Observation SampledWall(double normal_angle, double d, double along0, double along1, double z0,
                        double z1, double step) {
  Observation obs = WallOnLine(normal_angle, d, along0, along1, 0, 0.005);
  obs.z_min = z0;
  obs.z_max = z1;
  int hits = 0;
  for (double az = -M_PI; az < M_PI; az += step) {
    const Vector2d u(std::cos(az), std::sin(az));
    const double towards = -obs.normal.dot(u);
    if (towards <= 1e-9) continue;
    const double r = d / towards;  // horizontal range to the wall's line along this azimuth
    const double s = obs.Direction().dot(r * u - obs.edge[0]);
    if (s < 0.0 || s > (obs.edge[1] - obs.edge[0]).norm()) continue;
    for (double el = -M_PI / 2; el < M_PI / 2; el += step) {
      const double z = r * std::tan(el);
      hits += z >= z0 && z <= z1;
    }
  }
  obs.support = hits;
  return obs;
}

LearnedFrustum SampledFrustum() {
  LearnedFrustum frustum;
  for (int k = 0; k < 64; ++k) {
    frustum.ObserveSampling(SampledWall(M_PI, 1.0 + 0.05 * k, -1.0, 1.0, -1.2, 1.4, 0.006));
  }
  frustum.Observe({1.0, 1.0});
  frustum.Observe({1.0, -1.0});
  return frustum;
}

}  // namespace relplane::mapper::testing
