// libFuzzer target for the mapper's input path: PLANES bytes -> bus::Subscribe (defensive
// Decode) -> MapperService (seq check, FromPlaneSet validation) -> Mapper::Process -> POSE and
// MAP. The input is a stream of plane sets built from the fuzzer's bytes (hostile numbers
// included), now and then raw bytes behind the true fingerprint. What the service publishes must
// decode and be finite.

#include <relplane/map_t.hpp>
#include <relplane/odometry_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>

#include "fuzz_support.hpp"
#include "relplane/common/covariance.hpp"
#include "service.hpp"

namespace {

using namespace relplane;

plane_t Plane(FuzzedDataProvider& in, int64_t id) {
  plane_t p{};
  p.id = id;
  const bool wall = in.ConsumeBool();  // most of a mapper's planes are walls
  const double yaw = in.ConsumeFloatingPointInRange<double>(-M_PI, M_PI);
  const double n[3] = {wall ? std::cos(yaw) : fuzz::Number(in, 1.0),
                       wall ? std::sin(yaw) : fuzz::Number(in, 1.0),
                       wall ? 0.0 : fuzz::Number(in, 1.0)};
  for (int i = 0; i < 3; ++i) p.normal[i] = static_cast<float>(n[i]);
  p.d = static_cast<float>(fuzz::Number(in, 10.0));
  for (float& c : p.centroid) c = static_cast<float>(fuzz::Number(in, 10.0));
  p.num_vertices = in.ConsumeIntegralInRange<int32_t>(0, 6);
  p.vertices.resize(p.num_vertices);
  for (auto& v : p.vertices) {
    v.resize(3);  // lcm-gen makes float[n][3] a vector of vectors
    for (float& c : v) c = static_cast<float>(fuzz::Number(in, 10.0));
  }
  p.num_points = in.ConsumeIntegral<int32_t>();
  p.rms = static_cast<float>(fuzz::Number(in, 0.1));
  return p;
}

void CheckOutputs(fuzz::MemoryBus& bus) {
  for (const auto& bytes : bus.published["POSE"]) {
    const pose_t pose = fuzz::MustDecode<pose_t>(bytes);
    for (double v : pose.position) fuzz::MustBeFinite(v);
    for (double v : pose.orientation) fuzz::MustBeFinite(v);
    std::string reason;
    if (!geometry::ValidCovariance(pose.covariance, &reason)) std::abort();
  }
  for (const auto& bytes : bus.published["MAP"]) {
    const map_t map = fuzz::MustDecode<map_t>(bytes);
    for (const plane_t& p : map.planes) fuzz::MustBeFinite(p);
  }
  bus.published.clear();
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  spdlog::set_level(spdlog::level::off);
  FuzzedDataProvider in(data, size);
  fuzz::MemoryBus bus;
  mapper::MapperService service(bus, mapper::MapperOptions{});
  service.Subscribe();
  int64_t seq = 0;
  for (int frame = 0; frame < 64 && in.remaining_bytes() > 0; ++frame) {
    if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
      std::vector<uint8_t> raw = fuzz::Encode(plane_set_t{});
      raw.resize(8);  // the fingerprint, then whatever the fuzzer says
      const std::vector<uint8_t> rest = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange(0, 512));
      raw.insert(raw.end(), rest.begin(), rest.end());
      bus.Deliver("PLANES", raw);
      continue;
    }
    if (in.ConsumeIntegralInRange<int>(0, 7) == 0) {
      // Wheel odometry: mostly sane readings, sometimes hostile numbers or time stamps.
      odometry_t odo{};
      odo.seq = in.ConsumeIntegralInRange<int64_t>(-1, 200);
      odo.utime = in.ConsumeBool() ? in.ConsumeIntegral<int64_t>() : odo.seq * 33333;
      for (double& v : odo.position) v = fuzz::Number(in, 20.0);
      odo.orientation[0] = 1.0;
      for (double& v : odo.orientation) v += fuzz::Number(in, 1.0);
      for (double& v : odo.covariance) v = in.ConsumeBool() ? 0.0 : fuzz::Number(in, 1.0);
      bus.Deliver("ODOMETRY", fuzz::Encode(odo));
      continue;
    }
    plane_set_t set{};
    seq += in.ConsumeIntegralInRange<int64_t>(-1, 3);  // repeats, gaps, going back
    set.seq = in.ConsumeIntegralInRange<int>(0, 63) == 0 ? in.ConsumeIntegral<int64_t>() : seq;
    set.utime = in.ConsumeIntegralInRange<int>(0, 15) == 0
                    ? in.ConsumeIntegral<int64_t>()  // hostile time stamps
                    : static_cast<int64_t>(static_cast<uint64_t>(set.seq) * 33333u);
    set.num_planes = in.ConsumeIntegralInRange<int32_t>(0, 8);
    for (int i = 0; i < set.num_planes; ++i) set.planes.push_back(Plane(in, i));
    bus.Deliver("PLANES", fuzz::Encode(set));
    CheckOutputs(bus);
  }
  service.PublishMap();
  CheckOutputs(bus);
  return 0;
}
