#pragma once
// Pictures of a run: map.svg as the paper's Figures 2, 7 and 8 draw a map (true walls, mapped
// walls, lines from each plane to its group's centroid labelled X1, X2, ..., true and estimated
// trajectories), and error.svg, position error over time. Both carry a legend and units.

#include <string>
#include <vector>

#include "relplane/eval/run_metrics.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

struct MapPicture {
  const MapSnapshot* world = nullptr;  // true planes (SIM_WORLD); may be empty
  const MapSnapshot* map = nullptr;    // mapped planes and groups (MAP)
  const std::vector<PoseSample>* truth = nullptr;
  const std::vector<PoseSample>* estimate = nullptr;
  const RunMetrics* metrics = nullptr;  // for the one-line caption; may be null
  double width_px = 900.0;
};

std::string RenderMapSvg(const MapPicture& picture);

std::string RenderErrorSvg(const TrajectoryMetrics& trajectory, double width_px = 900.0);

// A round step (1, 2 or 5 times a power of ten) near span / target_count.
double NiceStep(double span, double target_count);

}  // namespace relplane::eval
