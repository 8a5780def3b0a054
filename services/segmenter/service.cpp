#include "service.hpp"

#include <spdlog/spdlog.h>

#include <algorithm>

#include "convert.hpp"
#include "relplane/common/service_runtime.hpp"

namespace relplane::segmenter {
namespace {

constexpr double kBudgetMs = 10.0;  // the segmenter's share of the 33.3 ms iteration

}  // namespace

SegmenterService::SegmenterService(bus::Bus& bus, ServiceOptions options)
    : SegmenterService(bus, bus, std::move(options)) {}

SegmenterService::SegmenterService(bus::Bus& clouds, bus::Bus& out, ServiceOptions options)
    : clouds_(clouds),
      out_(out),
      stats_("relplane-segmenter", kBudgetMs),
      max_points_(options.max_points),
      segmenter_(options.segmenter) {}

void SegmenterService::Subscribe() {
  // A cloud of max_points points is 12 bytes each plus the header: bigger messages are refused
  // before they are decoded.
  const size_t max_bytes = std::max(static_cast<size_t>(max_points_) * 12 + 1024, size_t{1} << 20);
  bus::Subscribe<point_cloud_t>(
      clouds_, "SENSOR_POINTS", [this](point_cloud_t& msg) { OnCloud(msg); },
      [this](const std::string& reason) { stats_.Rejected("SENSOR_POINTS: " + reason); },
      bus::kDefaultQueueCapacity, max_bytes);
}

void SegmenterService::OnCloud(point_cloud_t& msg) {
  if (msg.num_points > max_points_) {
    stats_.Rejected("SENSOR_POINTS seq " + std::to_string(msg.seq) + ": " +
                    std::to_string(msg.num_points) + " points exceed max_points " +
                    std::to_string(max_points_));
    return;
  }
  std::string reason;
  if (!TakePointCloud(&msg, &cloud_, &reason)) {
    stats_.Rejected("SENSOR_POINTS seq " + std::to_string(msg.seq) + ": " + reason);
    return;
  }
  if (!stats_.AcceptSeq(msg.seq)) return;  // repeated or out of order: counted, ignored
  const int64_t t0 = MonotonicMicros();
  const Result result = segmenter_.Segment(cloud_);
  stats_.Processed(static_cast<double>(MonotonicMicros() - t0) / 1000.0);
  ToPlaneSet(result, msg.utime, msg.seq, &planes_msg_);
  bus::Publish(out_, "PLANES", planes_msg_);
  nonfinite_total_ += result.dropped_nonfinite;
  layers_total_ += result.layer_planes;
  grazing_total_ += result.grazing_planes;
  stats_.SetDetail(fmt::format(
      "planes {}, non-finite points dropped {} (total {}), planes the camera cannot see dropped: "
      "depth layers {} (total {}), beyond its incidence {} (total {})",
      result.planes.size(), result.dropped_nonfinite, nonfinite_total_, result.layer_planes,
      layers_total_, result.grazing_planes, grazing_total_));
}

}  // namespace relplane::segmenter
