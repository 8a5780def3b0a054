#include "service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "convert.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/mapper/pose_covariance.hpp"

namespace relplane::mapper {
namespace {

constexpr double kBudgetMs = 5.0;  // the mapper's share of the 33.3 ms iteration

}  // namespace

MapperService::MapperService(bus::Bus& bus, MapperOptions options)
    : bus_(bus), stats_("relplane-mapper", kBudgetMs), mapper_(std::move(options)) {}

void MapperService::Subscribe() {
  bus::Subscribe<plane_set_t>(
      bus_, "PLANES", [this](const plane_set_t& msg) { OnPlanes(msg); },
      [this](const std::string& reason) { stats_.Rejected("PLANES: " + reason); });
  bus::Subscribe<odometry_t>(
      bus_, "ODOMETRY", [this](const odometry_t& msg) { OnOdometry(msg); },
      [this](const std::string& reason) { stats_.Rejected("ODOMETRY: " + reason); });
}

void MapperService::OnOdometry(const odometry_t& msg) {
  OdometryReading reading;
  std::string reason;
  if (!FromOdometry(msg, &reading, &reason)) {
    stats_.Rejected("ODOMETRY seq " + std::to_string(msg.seq) + ": " + reason);
    return;
  }
  if (!odometry_.Add(reading)) {
    stats_.Rejected("ODOMETRY seq " + std::to_string(msg.seq) + ": utime not after the last");
  }
}

void MapperService::OnPlanes(const plane_set_t& msg) {
  std::vector<PlaneInput> planes;
  std::string reason;
  if (!FromPlaneSet(msg, &planes, &reason)) {
    stats_.Rejected("PLANES seq " + std::to_string(msg.seq) + ": " + reason);
    return;
  }
  if (!stats_.AcceptSeq(msg.seq)) return;  // repeated or out of order: counted, ignored
  const int64_t t0 = MonotonicMicros();
  const std::optional<OdometryIncrement> odometry = odometry_.TakeUntil(msg.utime);
  const PoseEstimate estimate = mapper_.Process(msg.seq, planes, odometry);
  if (estimate.odometry_refused) {
    stats_.Rejected("ODOMETRY before PLANES seq " + std::to_string(msg.seq) +
                    ": moved farther than the platform can; the planes were used without it");
  }
  stats_.Processed(static_cast<double>(MonotonicMicros() - t0) / 1000.0);
  const Observability observability = ObservabilityOf(estimate);
  bus::Publish(bus_, "POSE", ToPoseMessage(estimate, observability.covariance, mapper_.Height(),
                                           msg.utime, msg.seq));
  // After Process: an input that crashes the mapper is not replayed into the next crash. After
  // POSE: the journal write stays off the pose's latency.
  Journal(msg.seq, std::move(planes), odometry);
  if (mapper_.TakeMapChanged()) map_pending_ = true;
  last_utime_ = msg.utime;
  last_seq_ = msg.seq;
  if (map_pending_ && MapDue(msg.utime)) PublishMap();
  stats_.SetDetail(fmt::format("planes {} groups {}", mapper_.Stats().map_planes,
                               mapper_.Stats().groups));
}

bool MapperService::MapDue(int64_t utime) const {
  if (last_map_utime_ < 0 || utime < last_map_utime_) return true;  // first, or time restarted
  // Unsigned: hostile time stamps must not overflow the difference.
  return static_cast<uint64_t>(utime) - static_cast<uint64_t>(last_map_utime_) >=
         static_cast<uint64_t>(kMapPeriodUs);
}

void MapperService::PublishMap() {
  if (last_seq_ < 0) return;
  bus::Publish(bus_, "MAP", ToMapMessage(mapper_.Map(), last_utime_, last_seq_));
  last_map_utime_ = last_utime_;
  map_pending_ = false;
}

bool MapperService::Resume(const std::string& path) {
  JournalContents journal;
  std::string error;
  if (!ReadJournal(path, &journal, &error)) {
    spdlog::error("{}", error);
    return false;
  }
  if (!journal.problem.empty()) {
    spdlog::warn("{}: {}; {} bytes after {} intact records discarded", path, journal.problem,
                 journal.discarded_bytes, journal.records.size());
  }
  if (!journal.records.empty()) {
    const int64_t t0 = MonotonicMicros();
    for (const JournalRecord& record : journal.records) {
      mapper_.Process(record.iteration, record.planes, record.odometry);
    }
    const double seconds = static_cast<double>(MonotonicMicros() - t0) / 1e6;
    last_seq_ = journal.records.back().iteration;
    stats_.AcceptSeq(last_seq_);  // later frames continue from here; older ones are refused
    map_pending_ = true;
    spdlog::info(
        "resumed from {}: {} iterations restored (up to seq {}) in {:.3f} s ({:.0f} "
        "iterations/s); {} planes, {} groups",
        path, journal.records.size(), last_seq_, seconds,
        static_cast<double>(journal.records.size()) / std::max(seconds, 1e-9),
        mapper_.Stats().map_planes, mapper_.Stats().groups);
  }
  if (!journal_.Open(path, journal.valid_bytes, &error)) {
    spdlog::error("{}", error);
    return false;
  }
  return true;
}

void MapperService::Journal(int64_t seq, std::vector<PlaneInput> planes,
                            const std::optional<OdometryIncrement>& odometry) {
  if (!journal_.IsOpen()) return;
  std::string error;
  const JournalRecord record{seq, std::move(planes), odometry};
  if (!journal_.Append(record, &error)) {
    stats_.Rejected("checkpoint: " + error);  // counted and said; mapping goes on
  }
}

}  // namespace relplane::mapper
