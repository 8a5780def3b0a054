// relplane-sim: moves a depth sensor through the scenario's world and publishes, per
// iteration, its point cloud (SENSOR_POINTS, on --cloud-url when given) and true pose
// (SIM_TRUTH); the true world (SIM_WORLD) at start and once a second; wheel odometry (ODOMETRY)
// when sim.odometry.enabled. Exits 0 when the trajectory ends.

#include <spdlog/spdlog.h>

#include <chrono>
#include <cmath>
#include <iostream>
#include <thread>

#include "convert.hpp"
#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/common/service_start.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/sim/odometry_stream.hpp"
#include "relplane/sim/simulation.hpp"

namespace {

using namespace relplane;

// The simulator's share of the 33.3 ms iteration budget.
constexpr double kBudgetMs = 10.0;

// Sleeps until the monotonic time `until_us`, waking early when a stop is requested.
void SleepUntil(int64_t until_us) {
  while (!StopRequested()) {
    const int64_t left = until_us - MonotonicMicros();
    if (left <= 0) return;
    std::this_thread::sleep_for(std::chrono::microseconds(std::min<int64_t>(left, 50000)));
  }
}

template <class M>
void Publish(bus::Bus& bus, ServiceStats& stats, const std::string& channel, const M& msg) {
  if (!bus::Publish(bus, channel, msg)) stats.Rejected(channel + ": the transport refused it");
}

int Run(sim::Simulation& simulation, const sim::ServiceOptions& options, double rate,
        int64_t iterations, bus::Bus& bus, bus::Bus& cloud_bus) {
  ServiceStats stats("relplane-sim", kBudgetMs);
  const map_t world_template = sim::ToWorldMap(simulation.TruePlanes(), 0, 0);
  const int64_t total = iterations >= 0 ? std::min(iterations, simulation.NumIterations())
                                        : simulation.NumIterations();
  spdlog::info("{} rectangles, {} iterations at {} Hz simulated, publishing at {}",
               world_template.num_planes, total, options.sim.rate_hz,
               rate > 0.0 ? fmt::format("{} Hz", rate) : std::string("full speed"));

  SleepUntil(MonotonicMicros() + static_cast<int64_t>(options.start_delay * 1e6));
  const int64_t start = MonotonicMicros();
  int64_t next_second = start;
  int64_t next_progress = start + 5000000;
  sim::OdometryStream odometry(options.odometry, simulation);
  int64_t k = 0;
  for (; k < total && !StopRequested(); ++k) {
    if (rate > 0.0) SleepUntil(start + static_cast<int64_t>(static_cast<double>(k) * 1e6 / rate));
    const int64_t utime = simulation.Utime(k);
    if (MonotonicMicros() >= next_second) {
      map_t world = world_template;
      world.seq = k;
      world.utime = utime;
      Publish(bus, stats, "SIM_WORLD", world);
      if (k > 0) PublishStatus(bus, stats);
      next_second += 1000000;
    }
    // Wheel odometry up to this iteration's time, before its cloud: a mapper gets the motion
    // before the planes it goes with.
    for (const sim::TimedOdometry& due : odometry.UpTo(k)) {
      Publish(bus, stats, "ODOMETRY", sim::ToOdometry(due.reading, due.utime));
    }
    const int64_t t0 = MonotonicMicros();
    const sim::Scan scan = simulation.Frame(k);
    const point_cloud_t cloud = sim::ToPointCloud(scan, k, utime);
    stats.AcceptSeq(k);
    stats.Processed(static_cast<double>(MonotonicMicros() - t0) / 1000.0);
    // A dropped frame is still simulated (the noise stream stays the same) and its truth is
    // still published; only the cloud is not.
    if (sim::DropFrame(options.sim.sensor.seed, k, options.drop_fraction)) {
      stats.CountDropped(1);
      stats.SetDetail(fmt::format("dropped {} of {} SENSOR_POINTS (drop_fraction {})",
                                  stats.Dropped(), k + 1, options.drop_fraction));
    } else {
      Publish(cloud_bus, stats, "SENSOR_POINTS", cloud);
    }
    Publish(bus, stats, "SIM_TRUTH", sim::ToTruthPose(simulation.SensorPose(k), k, utime));
    if (MonotonicMicros() >= next_progress) {
      spdlog::info("iteration {}/{}", k + 1, total);
      next_progress += 5000000;
    }
  }
  PublishStatus(bus, stats);
  spdlog::info("{} after {}/{} iterations", StopRequested() ? "stopped" : "done", k, total);
  if (options.drop_fraction > 0.0) {
    spdlog::info("dropped {} of {} SENSOR_POINTS frames (drop_fraction {})", stats.Dropped(), k,
                 options.drop_fraction);
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  cli::Parser parser{"relplane-sim: simulated depth sensor in a world of rectangles"};
  ServiceStart start;
  AddServiceFlags(parser, "sim", &start);
  AddCloudUrlFlag(parser, &start);
  double rate = -1.0;
  int64_t iterations = -1;
  parser
      .Add("--rate", &rate,
           "Publishing pace in iterations/s (0: as fast as possible; default: the "
           "scenario's sim.rate_hz). Simulated time always steps by 1/sim.rate_hz")
      .NonNegative();
  parser.Add("--iterations", &iterations, "Stop after N iterations").NonNegative();
  if (const auto code = parser.Parse(argc, argv)) return *code;

  sim::ServiceOptions options;
  if (const auto code = LoadSectionOptions<sim::ServiceOptions>(
          start, "relplane-sim", sim::LoadServiceOptions, &options)) {
    return *code;
  }
  if (rate < 0.0) rate = options.sim.rate_hz;

  sim::Simulation simulation(options.sim);
  std::optional<ServiceBuses> buses = OpenServiceBuses(start);
  if (!buses) return 1;
  InstallStopHandlers();
  return Run(simulation, options, rate, iterations, *buses->main, buses->Cloud());
}
