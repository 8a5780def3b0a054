// relplane-tum-play: publishes a TUM RGB-D style folder (depth.txt + depth/*.png) as
// SENSOR_POINTS at its own timestamps (utime = timestamp in microseconds, seq = line order),
// paced by them unless --speed 0.

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <relplane/point_cloud_t.hpp>
#include <thread>

#include "intrinsics_flags.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/tum/tum_folder.hpp"

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-tum-play: publish a TUM-style depth folder as SENSOR_POINTS"};
  cli::CommonFlags flags;
  cli::AddCommonFlags(parser, &flags);
  tum::IntrinsicsFlags intrinsics_flags;
  tum::AddIntrinsicsFlags(parser, &intrinsics_flags);
  std::string folder;
  double speed = 1.0;
  bool keep_invalid = false;
  std::string channel = "SENSOR_POINTS";
  parser.Add("folder", &folder, "folder with depth.txt and the PNGs it names").Required();
  parser.Add("--speed", &speed, "playback speed over the timestamps (0: as fast as possible)")
      .NonNegative();
  parser.AddFlag("--keep-invalid", &keep_invalid,
                 "publish the pixels without depth as NaN points (organized clouds)");
  parser.Add("--channel", &channel, "channel to publish on");
  if (auto code = parser.Parse(argc, argv)) return *code;
  try {
    cli::SetupLogging("relplane-tum-play", flags.log_level);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-tum-play: %s\n", e.what());
    return cli::kExitConfig;
  }
  std::vector<tum::DepthFrame> frames;
  tum::Intrinsics intrinsics;
  try {
    intrinsics = tum::ResolveIntrinsics(intrinsics_flags, folder + "/calibration.txt");
    frames = tum::ReadDepthList(folder);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-tum-play: %s\n", e.what());
    return 1;
  }
  if (frames.empty()) {
    std::fprintf(stderr, "relplane-tum-play: %s/depth.txt names no frame\n", folder.c_str());
    return 1;
  }
  std::unique_ptr<bus::Bus> bus;
  try {
    bus = bus::OpenLcmBus(bus::ResolveUrl(flags.lcm_url));
  } catch (const std::exception& e) {
    std::fprintf(stderr, "relplane-tum-play: %s\n", e.what());
    return 1;
  }
  InstallStopHandlers();
  const int64_t start = MonotonicMicros();
  int64_t seq = 0, failed = 0;
  for (const tum::DepthFrame& frame : frames) {
    if (StopRequested()) break;
    point_cloud_t msg;
    try {
      const pcd::PcdCloud cloud = tum::DepthToCloud(tum::ReadDepthPng(frame.path), intrinsics);
      for (size_t i = 0; i < cloud.size(); ++i) {
        if (!keep_invalid && !std::isfinite(cloud.x[i])) continue;
        msg.x.push_back(cloud.x[i]);
        msg.y.push_back(cloud.y[i]);
        msg.z.push_back(cloud.z[i]);
      }
    } catch (const std::exception& e) {
      // A bad frame is reported and skipped; the stream goes on.
      spdlog::warn("{}", e.what());
      ++failed;
      continue;
    }
    msg.num_points = static_cast<int32_t>(msg.x.size());
    msg.utime = static_cast<int64_t>(std::llround(frame.timestamp * 1e6));
    msg.seq = seq;
    if (speed > 0.0) {
      const double offset = (frame.timestamp - frames.front().timestamp) / speed;
      const int64_t wait = start + static_cast<int64_t>(offset * 1e6) - MonotonicMicros();
      if (wait > 0) std::this_thread::sleep_for(std::chrono::microseconds(wait));
    }
    if (!bus::Publish(*bus, channel, msg)) {
      spdlog::warn("publishing seq {} ({} points) failed", seq, msg.num_points);
    }
    ++seq;
  }
  spdlog::info("published {} of {} frames", seq, frames.size());
  return failed > 0 && seq == 0 ? 1 : 0;
}
