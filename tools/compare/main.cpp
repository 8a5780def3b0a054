// relplane-compare: relplane's segmenter side by side with PCL's organized multi-plane
// segmentation and its RANSAC plane fitting, on the same frames with truth (issue 53 item 5).

#include <cstdio>
#include <exception>
#include <iostream>

#include "options_yaml.hpp"  // services/sim: the scenario's `sim` section
#include "relplane/common/cli.hpp"
#include "relplane/compare/labelled_frames.hpp"
#include "relplane/compare/methods.hpp"
#include "relplane/compare/report.hpp"
#include "relplane/plane_truth/sim_truth.hpp"
#include "relplane/sim/simulation.hpp"

namespace {

using namespace relplane;

std::vector<compare::MethodStats> NewStats(const compare::Methods& methods) {
  std::vector<compare::MethodStats> stats;
  for (const std::string& name : methods.Names()) stats.push_back({name, {}, 0, {}});
  return stats;
}

void Count(const compare::MethodRun& run, compare::MethodStats* stats) {
  stats->seconds.push_back(run.seconds);
  stats->planes += static_cast<int>(run.detections.planes.size());
}

std::string LabelledTable(const std::vector<compare::LabelledFrame>& frames,
                          compare::MethodsOptions options) {
  // A label is found by the detection that holds most of its points: relplane keeps its labels.
  options.relplane.keep_labels = true;
  compare::Methods methods(options);
  std::vector<compare::MethodStats> stats = NewStats(methods);
  for (const compare::LabelledFrame& frame : frames) {
    std::fprintf(stderr, "relplane-compare: %s\n", frame.name.c_str());
    compare::OrganizedFrame grid{frame.cloud.width, frame.cloud.height, {}};
    grid.points.x = frame.cloud.x;
    grid.points.y = frame.cloud.y;
    grid.points.z = frame.cloud.z;
    const std::vector<compare::MethodRun> runs = methods.Run(grid.points, grid);
    for (size_t m = 0; m < runs.size(); ++m) {
      Count(runs[m], &stats[m]);
      plane_truth::Tally(plane_truth::ScoreLabels(frame.labels, runs[m].detections.planes,
                                                  runs[m].detections.labels),
                         &stats[m].tally);
    }
  }
  return compare::Table(stats);
}

std::string SimulatedTable(const sim::SimOptions& options, int step, int max_frames,
                           const compare::MethodsOptions& methods_options) {
  sim::Simulation simulation(options);
  compare::Methods methods(methods_options);
  std::vector<compare::MethodStats> stats = NewStats(methods);
  const plane_truth::SimScorer scorer(simulation.TruePlanes(), options.sensor.camera);
  const int64_t total = (simulation.NumIterations() + step - 1) / step;
  const int64_t frames = max_frames > 0 ? std::min<int64_t>(max_frames, total) : total;
  for (int64_t f = 0; f < frames; ++f) {
    const int64_t k = f * step;
    if (f % 10 == 0) {
      std::fprintf(stderr, "relplane-compare: simulated frame %lld of %lld\n",
                   static_cast<long long>(f + 1), static_cast<long long>(frames));
    }
    const sim::Scan scan = simulation.Frame(k);
    const compare::OrganizedFrame grid =
        compare::FromScan(scan, options.sensor.width, options.sensor.height);
    const std::vector<compare::MethodRun> runs = methods.Run(plane_truth::CloudOf(scan), grid);
    for (size_t m = 0; m < runs.size(); ++m) {
      Count(runs[m], &stats[m]);
      scorer.AddFrame(scan, simulation.SensorPose(k), runs[m].detections.planes, &stats[m].tally);
    }
  }
  return compare::Table(stats);
}

}  // namespace

int main(int argc, char** argv) {
  cli::Parser parser{
      "Runs relplane's segmenter and PCL's OrganizedMultiPlaneSegmentation (integral-image "
      "normals) and SACSegmentation (RANSAC, plane by plane) on the same frames with truth: "
      "real Kinect frames with hand-labelled planes and a simulated Kinect v1 scenario. Prints "
      "a table per input set: median time per frame (one thread), planes per frame, precision "
      "and recall against truth, median angle and offset errors, time over relplane's.",
      "relplane-compare"};
  std::string frames_dir = std::string(RELPLANE_SHARED_DIR) + "/data/kinect";
  std::string labels_dir = std::string(RELPLANE_SOURCE_DIR) + "/tests/segmenter/data/kinect_truth";
  std::string scenario = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/office_kinect_v1.yaml";
  std::string sensor = "kinect_v1", only, normals = "covariance";
  int step = 10, max_frames = 0;
  bool no_sac = false;
  parser.Add("--frames-dir", &frames_dir, "Real organized PCD frames (optical frame)")
      .ShowDefault();
  parser.Add("--labels-dir", &labels_dir, "Their labels: NAME.json for each NAME.pcd")
      .ShowDefault();
  parser.Add("--scenario", &scenario, "Scenario whose simulated frames are compared").ShowDefault();
  parser.Add("--step", &step, "Every STEP-th simulated frame").Positive().ShowDefault();
  parser.Add("--max-frames", &max_frames, "At most this many simulated frames (0: all)")
      .NonNegative();
  parser.Add("--sensor", &sensor, "relplane's sensor preset, also SAC's noise model").ShowDefault();
  parser.Add("--only", &only, "One input set: labelled or simulated");
  parser.Add("--pcl-normals", &normals, "Integral-image normals: covariance or gradient")
      .ShowDefault();
  compare::MethodsOptions options;
  parser
      .Add("--pcl-smoothing", &options.organized.normal_smoothing,
           "Integral-image normals' smoothing window, pixels")
      .Positive()
      .ShowDefault();
  parser
      .Add("--pcl-curvature", &options.organized.max_curvature,
           "Organized segmentation's largest curvature of a plane region")
      .Positive()
      .ShowDefault();
  parser.Add("--sac-iterations", &options.sac.max_iterations, "RANSAC's iterations per plane")
      .Positive()
      .ShowDefault();
  parser.AddFlag("--no-sac", &no_sac, "Leave out RANSAC (the slowest method)");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  if (!only.empty() && only != "labelled" && only != "simulated") {
    std::cerr << "relplane-compare: --only takes labelled or simulated, not " << only << "\n";
    return cli::kExitConfig;
  }
  if (normals != "covariance" && normals != "gradient") {
    std::cerr << "relplane-compare: --pcl-normals takes covariance or gradient\n";
    return cli::kExitConfig;
  }

  if (!options.relplane.sensor.SetPreset(sensor)) {
    std::cerr << "relplane-compare: unknown --sensor " << sensor << "\n";
    return cli::kExitConfig;
  }
  options.camera = options.relplane.sensor.model;
  options.organized.covariance_normals = normals == "covariance";
  options.run_sac = !no_sac;
  try {
    if (only.empty() || only == "labelled") {
      const auto frames = compare::LoadLabelledFrames(frames_dir, labels_dir);
      const std::string table = LabelledTable(frames, options);
      std::printf("\nReal frames with labelled planes (%zu, %s):\n%s", frames.size(),
                  frames_dir.c_str(), table.c_str());
    }
    if (only.empty() || only == "simulated") {
      const sim::ServiceOptions sim_options = sim::LoadServiceOptions(scenario);
      const std::string table = SimulatedTable(sim_options.sim, step, max_frames, options);
      std::printf("\nSimulated frames with true planes (%s, step %d):\n%s", scenario.c_str(), step,
                  table.c_str());
    }
  } catch (const std::exception& e) {
    std::cerr << "relplane-compare: " << e.what() << "\n";
    return 1;
  }
  return 0;
}
