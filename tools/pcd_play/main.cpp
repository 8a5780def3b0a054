// relplane-pcd-play: publishes PCD files (and TUM-convention 16-bit depth PNGs) in order as
// SENSOR_POINTS (seq 0, 1, ...), so clouds recorded by other tools can drive the pipeline.

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <relplane/point_cloud_t.hpp>
#include <thread>

#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "intrinsics_flags.hpp"  // tools/tum
#include "relplane/pcd/pcd_reader.hpp"
#include "relplane/tum/tum_folder.hpp"

namespace {

relplane::point_cloud_t ToMessage(const relplane::pcd::PcdCloud& cloud, bool drop_invalid,
                                  int64_t seq, double rate_hz) {
  relplane::point_cloud_t msg;
  msg.seq = seq;
  // Simulated time, as relplane-sim does: deterministic and independent of the host clock.
  msg.utime = rate_hz > 0 ? static_cast<int64_t>(std::llround(seq * 1e6 / rate_hz)) : seq;
  for (size_t i = 0; i < cloud.size(); ++i) {
    if (drop_invalid &&
        !(std::isfinite(cloud.x[i]) && std::isfinite(cloud.y[i]) && std::isfinite(cloud.z[i]))) {
      continue;
    }
    msg.x.push_back(cloud.x[i]);
    msg.y.push_back(cloud.y[i]);
    msg.z.push_back(cloud.z[i]);
  }
  msg.num_points = static_cast<int32_t>(msg.x.size());
  return msg;
}

bool IsPng(const std::string& file) {
  return file.size() > 4 && (file.compare(file.size() - 4, 4, ".png") == 0 ||
                             file.compare(file.size() - 4, 4, ".PNG") == 0);
}

}  // namespace

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{
      "relplane-pcd-play: publish PCD files (ascii, binary, binary_compressed) as "
      "SENSOR_POINTS"};
  cli::CommonFlags flags;
  cli::AddCommonFlags(parser, &flags);
  std::vector<std::string> files;
  double rate_hz = 10.0;
  bool optical = false;
  bool drop_invalid = false;
  int loops = 1;
  std::string channel = "SENSOR_POINTS";
  parser.Add("files", &files,
             "PCD files or 16-bit depth PNGs (TUM convention), published in this order")
      .Required();
  parser.Add("--rate", &rate_hz, "clouds per second (0: as fast as possible)").NonNegative();
  parser.AddFlag("--optical", &optical,
                 "the files are in the optical frame (x right, y down, z forward): turn them into "
                 "the sensor frame (x forward, y left, z up)");
  parser.AddFlag("--drop-invalid", &drop_invalid, "leave NaN/inf points out of the messages");
  parser.Add("--loop", &loops, "play the file list this many times").Positive();
  parser.Add("--channel", &channel, "channel to publish on");
  tum::IntrinsicsFlags intrinsics_flags;  // for PNG depth images
  tum::AddIntrinsicsFlags(parser, &intrinsics_flags);
  if (auto code = parser.Parse(argc, argv)) return *code;
  try {
    cli::SetupLogging("relplane-pcd-play", flags.log_level);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-pcd-play: %s\n", e.what());
    return cli::kExitConfig;
  }

  // Read everything first: a bad file is reported before anything is published.
  std::vector<pcd::PcdCloud> clouds;
  for (const auto& file : files) {
    try {
      if (IsPng(file)) {
        // A depth image becomes a cloud in the sensor frame already: --optical is for PCDs.
        clouds.push_back(tum::DepthToCloud(tum::ReadDepthPng(file),
                                           tum::ResolveIntrinsics(intrinsics_flags)));
        continue;
      }
      clouds.push_back(pcd::ReadPcd(file));
    } catch (const std::exception& e) {
      std::fprintf(stderr, "relplane-pcd-play: %s\n", e.what());
      return 1;
    }
    if (optical) pcd::OpticalToSensor(&clouds.back());
  }

  std::unique_ptr<bus::Bus> bus;
  try {
    bus = bus::OpenLcmBus(bus::ResolveUrl(flags.lcm_url));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-pcd-play: %s\n", e.what());
    return 1;
  }
  InstallStopHandlers();
  const int64_t period_us = rate_hz > 0 ? static_cast<int64_t>(1e6 / rate_hz) : 0;
  int64_t next = MonotonicMicros();
  int64_t seq = 0;
  for (int loop = 0; loop < loops && !StopRequested(); ++loop) {
    for (size_t i = 0; i < clouds.size() && !StopRequested(); ++i, ++seq) {
      const auto msg = ToMessage(clouds[i], drop_invalid, seq, rate_hz);
      if (!bus::Publish(*bus, channel, msg)) {
        spdlog::warn("publishing seq {} ({} points) failed", seq, msg.num_points);
      } else {
        spdlog::debug("published {} as seq {} ({} points)", files[i], seq, msg.num_points);
      }
      next += period_us;
      const int64_t wait = next - MonotonicMicros();
      if (wait > 0) std::this_thread::sleep_for(std::chrono::microseconds(wait));
    }
  }
  spdlog::info("published {} clouds", seq);
  return 0;
}
