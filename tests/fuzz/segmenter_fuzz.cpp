// libFuzzer target for the segmenter's input path: SENSOR_POINTS bytes -> bus::Subscribe
// (size limit, defensive Decode) -> SegmenterService (max_points, TakePointCloud, seq check) ->
// Segmenter::Segment -> PLANES. Inputs are small clouds of points on a few planes built from the
// fuzzer's bytes, with hostile numbers mixed in, now and then raw bytes behind the true
// fingerprint; a few frames per input, since the segmenter seeds each frame from the last.
// Every PLANES message published must decode and be finite.

#include <Eigen/Geometry>
#include <relplane/plane_set_t.hpp>
#include <relplane/point_cloud_t.hpp>

#include "fuzz_support.hpp"
#include "service.hpp"

namespace {

using namespace relplane;

point_cloud_t Cloud(FuzzedDataProvider& in, int64_t seq) {
  point_cloud_t cloud{};
  cloud.seq = seq;
  cloud.utime = seq * 33333;
  // A few planes n . p + d = 0, points on them (with a little noise) and hostile points.
  const int num_planes = in.ConsumeIntegralInRange<int>(1, 4);
  std::vector<Eigen::Vector3d> normals;
  std::vector<double> offsets;
  for (int k = 0; k < num_planes; ++k) {
    Eigen::Vector3d n(fuzz::Number(in, 1.0), fuzz::Number(in, 1.0), fuzz::Number(in, 1.0));
    if (!(n.norm() > 1e-3) || !n.allFinite()) n = Eigen::Vector3d::UnitX();
    normals.push_back(n.normalized());
    offsets.push_back(in.ConsumeFloatingPointInRange<double>(-8.0, 8.0));
  }
  const int n = in.ConsumeIntegralInRange<int>(0, 600);
  for (int i = 0; i < n && in.remaining_bytes() > 0; ++i) {
    Eigen::Vector3d p;
    if (in.ConsumeIntegralInRange<int>(0, 31) == 0) {
      p = Eigen::Vector3d(fuzz::Number(in, 10), fuzz::Number(in, 10), fuzz::Number(in, 10));
    } else {
      const int k = in.ConsumeIntegralInRange<int>(0, num_planes - 1);
      const Eigen::Vector3d& nk = normals[k];
      const Eigen::Vector3d u = nk.unitOrthogonal(), v = nk.cross(u);
      const double a = in.ConsumeFloatingPointInRange<double>(-3, 3);
      const double b = in.ConsumeFloatingPointInRange<double>(-3, 3);
      const double noise = in.ConsumeFloatingPointInRange<double>(-0.01, 0.01);
      p = -offsets[k] * nk + a * u + b * v + noise * nk;
    }
    cloud.x.push_back(static_cast<float>(p.x()));
    cloud.y.push_back(static_cast<float>(p.y()));
    cloud.z.push_back(static_cast<float>(p.z()));
  }
  cloud.num_points = static_cast<int32_t>(cloud.x.size());
  return cloud;
}

void CheckOutputs(fuzz::MemoryBus& bus) {
  for (const auto& bytes : bus.published["PLANES"]) {
    const plane_set_t set = fuzz::MustDecode<plane_set_t>(bytes);
    for (const plane_t& p : set.planes) fuzz::MustBeFinite(p);
  }
  bus.published.clear();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  spdlog::set_level(spdlog::level::off);
  FuzzedDataProvider in(data, size);
  fuzz::MemoryBus bus;
  segmenter::ServiceOptions options;
  options.max_points = 500;  // clouds beyond it are refused: that path is fuzzed too
  segmenter::SegmenterService service(bus, options);
  service.Subscribe();
  for (int64_t frame = 0; frame < 4 && in.remaining_bytes() > 0; ++frame) {
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
      std::vector<uint8_t> raw = fuzz::Encode(point_cloud_t{});
      raw.resize(8);  // the fingerprint, then whatever the fuzzer says
      const std::vector<uint8_t> rest = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange(0, 512));
      raw.insert(raw.end(), rest.begin(), rest.end());
      bus.Deliver("SENSOR_POINTS", raw);
      continue;
    }
    bus.Deliver("SENSOR_POINTS", fuzz::Encode(Cloud(in, frame)));
    CheckOutputs(bus);
  }
  return 0;
}
