#pragma once
// The service around the mapper: PLANES in, POSE for every accepted plane set and MAP (at most
// 10 Hz of simulated time) out; bad input is counted and logged through ServiceStats, never a
// crash. With a checkpoint journal it resumes where a killed mapper stopped (journal.hpp).

#include <relplane/odometry_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <string>
#include <vector>

#include "journal.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/mapper/mapper.hpp"
#include "relplane/mapper/odometry.hpp"

namespace relplane::mapper {

class MapperService {
 public:
  MapperService(bus::Bus& bus, MapperOptions options);

  // Subscribes PLANES, and ODOMETRY (optional: without it the mapper runs on planes alone), on
  // the bus given to the constructor.
  void Subscribe();
  void OnPlanes(const plane_set_t& msg);
  void OnOdometry(const odometry_t& msg);
  // Publishes MAP now if anything was processed (at shutdown).
  void PublishMap();
  // Replays the journal at `path` (if any) through the fresh mapper and opens it for appending.
  // False when the journal cannot be read or written.
  bool Resume(const std::string& path);
  ServiceStats& Stats() { return stats_; }

 private:
  void Journal(int64_t seq, std::vector<PlaneInput> planes,
               const std::optional<OdometryIncrement>& odometry);
  // MAP at most every kMapPeriodUs of simulated time, and at once when time went backwards.
  bool MapDue(int64_t utime) const;

  bus::Bus& bus_;
  ServiceStats stats_;
  Mapper mapper_;
  JournalWriter journal_;
  OdometryIntegrator odometry_;
  bool map_pending_ = false;
  int64_t last_map_utime_ = -1;
  int64_t last_utime_ = 0;
  int64_t last_seq_ = -1;
};

}  // namespace relplane::mapper
