#pragma once
// Test helpers: walls as a sensor with a regular grid of rays samples them, and a frustum that
// has learnt its angular step from such walls (LearnedFrustum::ObserveSampling).

#include "localisation/frustum.hpp"
#include "plane_store/observation.hpp"

namespace relplane::mapper::testing {

// A wall observation in the sensor frame: the line with normal angle `normal_angle`, offset
// d, visible from `along0` to `along1`, fitted to `support` points with residual `rms`.
Observation WallOnLine(double normal_angle, double d, double along0, double along1, int support,
                       double rms);

// A wall from `along0` to `along1` on its line (normal angle `normal_angle`, offset d), from
// z0 to z1 in the sensor frame, as a sensor whose rays lie on a grid of `step` in azimuth and
// elevation samples it: its support is the rays that hit it, counted (not from its solid angle).
Observation SampledWall(double normal_angle, double d, double along0, double along1, double z0,
                        double z1, double step);

// A frustum 45 degrees either side that has learnt an angular step of 6 mrad from walls ahead.
LearnedFrustum SampledFrustum();

}  // namespace relplane::mapper::testing
