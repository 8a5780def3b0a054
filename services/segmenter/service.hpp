#pragma once
// The service around the segmenter: one PLANES message per accepted SENSOR_POINTS cloud; bad
// input is counted and logged through ServiceStats, never a crash.

#include <cstdint>
#include <relplane/point_cloud_t.hpp>

#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segmenter {

class SegmenterService {
 public:
  SegmenterService(bus::Bus& bus, ServiceOptions options);

  // Subscribes SENSOR_POINTS on the bus given to the constructor.
  void Subscribe();
  void OnCloud(const point_cloud_t& msg);
  ServiceStats& Stats() { return stats_; }

 private:
  bus::Bus& bus_;
  ServiceStats stats_;
  int64_t max_points_;
  Segmenter segmenter_;
  int64_t nonfinite_total_ = 0;
};

}  // namespace relplane::segmenter
