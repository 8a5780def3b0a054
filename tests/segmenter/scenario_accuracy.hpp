#pragma once
// Segmenter accuracy on the simulator's scenarios (relplane_sim) against the true world:
// precision and recall of detected planes, normal-angle and offset errors (the rules:
// relplane/plane_truth/sim_truth.hpp).

#include <Eigen/Core>
#include <cstdint>
#include <string>
#include <vector>

#include "relplane/plane_truth/accuracy.hpp"
#include "relplane/segmenter/options.hpp"

namespace relplane::segmenter::testing {

using ScenarioAccuracy = plane_truth::Accuracy;

// Runs the scenario's simulator (its `sim` section, range noise replaced by `noise_sigma`) and
// segments every `step`-th frame with one streaming Segmenter with default options.
ScenarioAccuracy MeasureScenario(const std::string& scenario_file, double noise_sigma, int step);

// The scenario's own sensor (its camera model and noise) and `options`, every `step`-th frame.
ScenarioAccuracy MeasureCameraScenario(const std::string& scenario_file, const Options& options,
                                       int step);

// Frames first..last of the scenario (sensor noise `noise_sigma`, noise seed `seed`), segmented
// in order by one Segmenter with `options`, in which two walls lie over each other: vertical
// detections facing within 20 degrees of each other with centroids within 0.1 m.
int FramesWithAWallTwice(const std::string& scenario_file, double noise_sigma, uint32_t seed,
                         int64_t first, int64_t last, const Options& options);

// One sighting of a true wall: the angle (degrees) between its normal and the wall's, and its
// length along the wall (m); infinity and 0 when no detection was seen on the wall.
struct WallSighting {
  double angle_deg = 0.0;
  double length_m = 0.0;
};

// Frames 0..last segmented in order by one Segmenter with `options`: for each frame from `first`
// with at least 150 of its samples on the true wall whose centroid lies within 5 cm of
// `centroid` (x, y in the world), the detection seen on it (centroid within 5 cm of its plane,
// normal within 20 degrees, extents overlapping).
std::vector<WallSighting> WallSightings(const std::string& scenario_file, double noise_sigma,
                                        uint32_t seed, int64_t first, int64_t last,
                                        const Options& options, const Eigen::Vector2d& centroid);

}  // namespace relplane::segmenter::testing
