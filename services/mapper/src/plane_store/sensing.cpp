#include "plane_store/sensing.hpp"

#include <cmath>
#include <utility>

#include "plane_store/registration.hpp"

namespace relplane::mapper {

double MaxEndSpacing(double static_std) { return std::sqrt(12.0) * static_std; }

std::vector<Observation> Observe(int64_t iteration, const std::vector<PlaneInput>& planes,
                                 const RegistrationOptions& options, double static_std,
                                 LearnedFrustum* frustum) {
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
  // An edge the sensor does not resolve places nothing by one sighting (§II.C-E): its last
  // sample lies anywhere within a sample spacing of the end, and a spacing wider than
  // √12 static_std (the width of a uniform error with that standard deviation) is coarser than a
  // static end is told by. Such an edge, far ahead on a wall seen at a grazing angle, creeps out
  // to the wall's end as the sensor comes nearer; taken for the wall's end, it was mapped short
  // and the pose along the wall followed it back. The comparisons still judge it, pooled over
  // many sightings (Observation::coarse).
  const double max_spacing = MaxEndSpacing(static_std);
  for (Observation& obs : observations) {
    for (int e = 0; e < 2; ++e) {
      const bool view = obs.cut[e] || frustum->Clipped(obs.edge[e], obs.edge[1 - e]);
      obs.coarse[e] = !view && frustum->EdgeSpacing(obs.edge[e], obs.d) > max_spacing;
      obs.cut[e] = view || obs.coarse[e];
    }
  }
  return observations;
}

}  // namespace relplane::mapper
