#include "plane_store/sensing.hpp"

#include <utility>

#include "plane_store/registration.hpp"

namespace relplane::mapper {

std::vector<Observation> Observe(int64_t iteration, const std::vector<PlaneInput>& planes,
                                 const RegistrationOptions& options, LearnedFrustum* frustum) {
  std::vector<Observation> observations;
  for (const PlaneInput& input : planes) {
    auto obs = MakeObservation(input, iteration, options.max_wall_normal_z);
    if (!obs) continue;
    frustum->Observe(obs->edge[0]);
    frustum->Observe(obs->edge[1]);
    frustum->ObserveSampling(*obs);
    observations.push_back(std::move(*obs));
  }
  // One plane per surface and iteration, as an rltplane stores them.
  DropRepeatedSightings(&observations, options,
                        [frustum](const Eigen::Vector2d& edge) { return frustum->Clipped(edge); });
  MarkOccludedEdges(&observations, options);
  for (Observation& obs : observations) {
    for (int e = 0; e < 2; ++e) {
      obs.cut[e] = obs.cut[e] || frustum->Clipped(obs.edge[e], obs.edge[1 - e]);
    }
  }
  return observations;
}

}  // namespace relplane::mapper
