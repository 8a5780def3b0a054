#pragma once
// How far apart the sensor's samples land, learnt from the cloud itself (no image grid, no
// intrinsics): connected pieces must bridge the sampling gaps of a wall seen at a grazing angle.

#include <algorithm>
#include <cmath>
#include <cstddef>

#include "relplane/segmenter/cloud.hpp"

namespace relplane::segmenter {

// The sensor's angular sampling step (radians): the density of viewing directions around a few
// probe points of `sample`, a uniform subsample of a cloud of `cloud_size` points, gives the
// solid angle per point of the full cloud; its square root is the step. Probes are taken where
// the directions are dense (the upper quartile), so the edge of the view or a patch with no
// returns does not inflate it. 0 when the sample is too small to tell.
float EstimateAngularStep(const Cloud& sample, size_t cloud_size);

// Expected distance between neighbouring samples on a plane at distance `plane_distance` from
// the sensor, at range `range`: the step times the range, stretched by 1 / cos(incidence) =
// range / plane_distance (bounded: a plane through the sensor is seen edge-on).
// Inline: it is evaluated for every cell of every piece.
constexpr float kMinCosIncidence = 0.05f;
inline float SampleSpacing(float angular_step, float range, float plane_distance) {
  const float cos_incidence =
      std::max(kMinCosIncidence, range > 0.0f ? std::fabs(plane_distance) / range : 1.0f);
  return angular_step * range / std::min(1.0f, cos_incidence);
}

}  // namespace relplane::segmenter
