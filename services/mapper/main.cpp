// relplane-mapper: the Relative Plane algorithm as a service. Subscribes PLANES (untransformed
// planes per iteration), publishes POSE for every plane set (same utime/seq) and MAP when the
// map changed, at most 10 times per simulated second and once more at shutdown. With
// --checkpoint it journals every plane set it processed and, started again, replays the journal
// first (journal.hpp), so a restarted mapper goes on with the map it had.

#include <spdlog/spdlog.h>

#include <algorithm>
#include <iostream>

#include "convert.hpp"
#include "journal.hpp"
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
    // After Process: an input that crashes the mapper is not replayed into the next crash.
    Journal(msg.seq, std::move(planes));
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

  // Replays the journal at `path` (if any) through the fresh mapper and opens it for appending.
  // False when the journal cannot be read or written.
  bool Resume(const std::string& path) {
    mapper::JournalContents journal;
    std::string error;
    if (!mapper::ReadJournal(path, &journal, &error)) {
      spdlog::error("{}", error);
      return false;
    }
    if (!journal.problem.empty()) {
      spdlog::warn("{}: {}; {} bytes after {} intact records discarded", path, journal.problem,
                   journal.discarded_bytes, journal.records.size());
    }
    if (!journal.records.empty()) {
      const int64_t t0 = MonotonicMicros();
      for (const mapper::JournalRecord& record : journal.records) {
        mapper_.Process(record.iteration, record.planes);
      }
      const double seconds = static_cast<double>(MonotonicMicros() - t0) / 1e6;
      last_seq_ = journal.records.back().iteration;
      stats_.AcceptSeq(last_seq_);  // later frames continue from here; older ones are refused
      map_pending_ = true;
      spdlog::info("resumed from {}: {} iterations restored (up to seq {}) in {:.3f} s ({:.0f} "
                   "iterations/s); {} planes, {} groups",
                   path, journal.records.size(), last_seq_, seconds,
                   static_cast<double>(journal.records.size()) / std::max(seconds, 1e-9),
                   mapper_.State().global.size(), mapper_.State().groups.size());
    }
    if (!journal_.Open(path, journal.valid_bytes, &error)) {
      spdlog::error("{}", error);
      return false;
    }
    return true;
  }

  ServiceStats& Stats() { return stats_; }

 private:
  void Journal(int64_t seq, std::vector<mapper::PlaneInput> planes) {
    if (!journal_.IsOpen()) return;
    std::string error;
    const mapper::JournalRecord record{seq, std::move(planes)};
    if (!journal_.Append(record, MonotonicMicros(), &error)) {
      stats_.Rejected("checkpoint: " + error);  // counted and said; mapping goes on
    }
  }

  bus::Bus& bus_;
  ServiceStats stats_;
  mapper::Mapper mapper_;
  mapper::JournalWriter journal_;
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
  std::string checkpoint;
  app.add_option("--checkpoint", checkpoint,
                 "Journal of the processed plane sets: replayed on start when it exists, then "
                 "appended to (the launcher gives RUN/mapper.journal)");
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
  if (!checkpoint.empty() && !service.Resume(checkpoint)) return 1;
  bus::Subscribe<plane_set_t>(
      *bus, "PLANES", [&](const plane_set_t& msg) { service.OnPlanes(msg); },
      [&](const std::string& reason) { service.Stats().Rejected("PLANES: " + reason); });
  spdlog::info("listening on PLANES");
  const int result = RunService(*bus, service.Stats());
  service.PublishMap();  // once more at shutdown
  return result;
}
