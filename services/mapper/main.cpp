// relplane-mapper: the Relative Plane algorithm as a service. Subscribes PLANES (untransformed
// planes per iteration), publishes POSE for every plane set (same utime/seq) and MAP when the
// map changed, at most 10 times per simulated second and once more at shutdown.

#include <spdlog/spdlog.h>

#include <iostream>

#include "convert.hpp"
#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/common/service_start.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/mapper/mapper.hpp"

namespace {

using namespace relplane;

constexpr double kBudgetMs = 5.0;         // the mapper's share of the 33.3 ms iteration
constexpr int64_t kMapPeriodUs = 100000;  // MAP at most 10 Hz of simulated time

class MapperService {
 public:
  MapperService(bus::Bus& bus, mapper::MapperOptions options)
      : bus_(bus), stats_("relplane-mapper", kBudgetMs), mapper_(std::move(options)) {}

  void OnPlanes(const plane_set_t& msg) {
    if (!stats_.AcceptSeq(msg.seq)) return;  // repeated or out of order: counted, ignored
    std::vector<mapper::PlaneInput> planes;
    std::string reason;
    if (!mapper::FromPlaneSet(msg, &planes, &reason)) {
      stats_.Rejected("PLANES seq " + std::to_string(msg.seq) + ": " + reason);
      return;
    }
    const int64_t t0 = MonotonicMicros();
    const mapper::PoseEstimate estimate = mapper_.Process(msg.seq, planes);
    stats_.Processed(static_cast<double>(MonotonicMicros() - t0) / 1000.0);
    bus::Publish(bus_, "POSE",
                 mapper::ToPoseMessage(estimate, mapper_.Height(), msg.utime, msg.seq));
    if (mapper_.TakeMapChanged()) map_pending_ = true;
    last_utime_ = msg.utime;
    last_seq_ = msg.seq;
    if (map_pending_ && (last_map_utime_ < 0 || msg.utime - last_map_utime_ >= kMapPeriodUs)) {
      PublishMap();
    }
    stats_.SetDetail(fmt::format("planes {} groups {}", mapper_.State().global.size(),
                                 mapper_.State().groups.size()));
  }

  void PublishMap() {
    if (last_seq_ < 0) return;
    bus::Publish(bus_, "MAP", mapper::ToMapMessage(mapper_.Map(), last_utime_, last_seq_));
    last_map_utime_ = last_utime_;
    map_pending_ = false;
  }

  ServiceStats& Stats() { return stats_; }

 private:
  bus::Bus& bus_;
  ServiceStats stats_;
  mapper::Mapper mapper_;
  bool map_pending_ = false;
  int64_t last_map_utime_ = -1;
  int64_t last_utime_ = 0;
  int64_t last_seq_ = -1;
};

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"relplane-mapper: the Relative Plane algorithm (PLANES -> POSE, MAP)"};
  ServiceStart start;
  AddServiceFlags(app, "mapper", &start);
  if (const auto code = cli::Parse(app, argc, argv)) return *code;

  mapper::MapperOptions options;
  if (const auto code = LoadSectionOptions<mapper::MapperOptions>(
          start, "relplane-mapper", mapper::LoadMapperOptions, &options)) {
    return *code;
  }

  std::unique_ptr<bus::Bus> bus = OpenServiceBus(start);
  if (!bus) return 1;
  InstallStopHandlers();
  MapperService service(*bus, options);
  bus::Subscribe<plane_set_t>(
      *bus, "PLANES", [&](const plane_set_t& msg) { service.OnPlanes(msg); },
      [&](const std::string& reason) { service.Stats().Rejected("PLANES: " + reason); });
  spdlog::info("listening on PLANES");
  const int result = RunService(*bus, service.Stats());
  service.PublishMap();  // once more at shutdown
  return result;
}
