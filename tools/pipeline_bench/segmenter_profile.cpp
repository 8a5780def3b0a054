#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>
#include <stdexcept>

#include "convert.hpp"  // the segmenter service's
#include "options_yaml.hpp"
#include "process_cpu.hpp"
#include "relplane/segmenter/segmenter.hpp"
#include "stage_profile.hpp"

namespace relplane::bench {

std::vector<double> ProfileSegmenter(const std::string& scenario,
                                     const std::vector<std::vector<uint8_t>>& clouds,
                                     std::vector<std::vector<uint8_t>>* plane_sets) {
  segmenter::Segmenter seg(segmenter::LoadServiceOptions(scenario).segmenter);
  std::vector<double> ms;
  plane_sets->clear();
  for (size_t k = 0; k < clouds.size(); ++k) {
    point_cloud_t msg;
    segmenter::Cloud cloud;
    std::string reason = "does not decode";
    if (msg.decode(clouds[k].data(), 0, static_cast<int>(clouds[k].size())) < 0 ||
        !segmenter::FromPointCloud(msg, &cloud, &reason)) {
      throw std::runtime_error("cloud " + std::to_string(k) + ": " + reason);
    }
    const double t0 = ThreadCpuMs();
    const segmenter::Result result = seg.Segment(cloud);
    ms.push_back(ThreadCpuMs() - t0);
    const plane_set_t out = segmenter::ToPlaneSet(result, msg.utime, msg.seq);
    std::vector<uint8_t> bytes(static_cast<size_t>(out.getEncodedSize()));
    out.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
    plane_sets->push_back(std::move(bytes));
  }
  return ms;
}

}  // namespace relplane::bench
