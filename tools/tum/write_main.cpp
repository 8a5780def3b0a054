// relplane-tum-write: runs a scenario's simulator and writes its frames as a TUM RGB-D style
// folder: depth/NNNNNN.png (16-bit, depth x scale), depth.txt, calibration.txt and
// groundtruth.txt (the true sensor poses, TUM format, relplane's sensor frame).

#include <cstdio>
#include <filesystem>
#include <fstream>

#include "options_yaml.hpp"  // services/sim: the scenario's `sim` section
#include "relplane/common/cli.hpp"
#include "relplane/sim/simulation.hpp"
#include "relplane/tum/sim_frames.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-tum-write: write a scenario's simulated depth frames as a TUM-style "
                     "folder (depth.txt + depth/*.png)"};
  std::string config, out;
  int64_t iterations = -1;
  int every = 1;
  double scale = 5000.0;
  parser.Add("--config", &config, "scenario file (its sim section)").Required();
  parser.Add("--out", &out, "folder to write").Required();
  parser.Add("--iterations", &iterations, "simulate the first N iterations only").NonNegative();
  parser.Add("--every", &every, "write every k-th frame").Positive();
  parser.Add("--depth-scale", &scale, "PNG value per metre").Positive();
  if (auto code = parser.Parse(argc, argv)) return *code;

  sim::ServiceOptions options;
  try {
    options = sim::LoadServiceOptions(config);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-tum-write: %s\n", e.what());
    return cli::kExitConfig;
  }
  try {
    std::filesystem::create_directories(out + "/depth");
    sim::Simulation simulation(options.sim);
    const int64_t total = iterations >= 0 ? std::min(iterations, simulation.NumIterations())
                                          : simulation.NumIterations();
    tum::WriteCalibration(out + "/calibration.txt", tum::SimIntrinsics(options.sim.sensor, scale));
    std::ofstream list(out + "/depth.txt"), truth(out + "/groundtruth.txt");
    list << "# depth maps of " << config << "\n# timestamp filename\n";
    truth << "# true sensor poses (x forward, y left, z up)\n# timestamp tx ty tz qx qy qz qw\n";
    list.precision(6);
    truth.precision(9);
    int written = 0, clipped_total = 0;
    for (int64_t k = 0; k < total; k += every) {
      int clipped = 0;
      const tum::DepthImage image = tum::ScanToDepthImage(
          simulation.Frame(k), options.sim.sensor, scale, &clipped);
      clipped_total += clipped;
      char name[32];
      std::snprintf(name, sizeof name, "depth/%06lld.png", static_cast<long long>(k));
      tum::WriteDepthPng(out + "/" + name, image);
      const double t = static_cast<double>(simulation.Utime(k)) * 1e-6;
      list << std::fixed << t << ' ' << name << '\n';
      const Eigen::Isometry3d pose = simulation.SensorPose(k);
      const Eigen::Quaterniond q(pose.rotation());
      const Eigen::Vector3d p = pose.translation();
      truth << std::fixed << t << ' ' << p.x() << ' ' << p.y() << ' ' << p.z() << ' ' << q.x()
            << ' ' << q.y() << ' ' << q.z() << ' ' << q.w() << '\n';
      ++written;
    }
    if (!list || !truth) throw tum::DepthImageError(out + ": writing the lists failed");
    std::printf("relplane-tum-write: %d frames to %s%s\n", written, out.c_str(),
                clipped_total > 0 ? (" (" + std::to_string(clipped_total) +
                                     " depths beyond 16 bits left out)").c_str()
                                  : "");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-tum-write: %s\n", e.what());
    return 1;
  }
  return 0;
}
