#pragma once
// The service around the segmenter: one PLANES message per accepted SENSOR_POINTS cloud; bad
// input is counted and logged through ServiceStats, never a crash.

#include <cstdint>
#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>

#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/segmenter/segmenter.hpp"

namespace relplane::segmenter {

class SegmenterService {
 public:
  // Clouds and planes on one bus.
  SegmenterService(bus::Bus& bus, ServiceOptions options);
  // SENSOR_POINTS read on `clouds`, PLANES published on `out`.
  SegmenterService(bus::Bus& clouds, bus::Bus& out, ServiceOptions options);

  // Subscribes SENSOR_POINTS on the cloud bus given to the constructor.
  void Subscribe();
  // Takes the message's arrays (they come back with the previous frame's capacity).
  void OnCloud(point_cloud_t& msg);
  ServiceStats& Stats() { return stats_; }

 private:
  bus::Bus& clouds_;
  bus::Bus& out_;
  ServiceStats stats_;
  int64_t max_points_;
  Segmenter segmenter_;
  int64_t nonfinite_total_ = 0;
  int64_t layers_total_ = 0;   // planes dropped as one quantized depth value
  int64_t grazing_total_ = 0;  // planes dropped as beyond the camera's incidence limit
  // Kept from frame to frame so that steady state allocates no cloud or message arrays.
  Cloud cloud_;
  plane_set_t planes_msg_;
};

}  // namespace relplane::segmenter
