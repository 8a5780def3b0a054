// libFuzzer target for the logger's inputs: bytes on POSE, SIM_TRUTH, MAP, SIM_WORLD, STATUS
// and PLANES -> eval::FeedEncoded (defensive Decode, FromMessage validation) -> RunRecorder ->
// metrics, metrics.json, map.json, the summary and both pictures, as relplane-logger and
// relplane-eval compute them. Messages are built from the fuzzer's bytes (hostile numbers
// included), now and then raw bytes behind a true fingerprint.

#include <relplane/map_t.hpp>
#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>
#include <relplane/status_t.hpp>

#include "convert.hpp"
#include "fuzz_support.hpp"
#include "relplane/eval/report_json.hpp"
#include "relplane/eval/summary.hpp"
#include "relplane/eval/svg.hpp"

namespace {

using namespace relplane;

pose_t Pose(FuzzedDataProvider& in) {
  pose_t p{};
  p.seq = in.ConsumeIntegralInRange<int64_t>(-2, 40);
  p.utime = p.seq * 33333 + in.ConsumeIntegralInRange<int64_t>(-5, 5);
  for (double& v : p.position) v = fuzz::Number(in, 20.0);
  p.orientation[0] = 1.0;
  for (double& v : p.orientation) v += fuzz::Number(in, 1.0);
  p.status = in.ConsumeIntegral<int8_t>();
  // Mostly a diagonal covariance (valid), sometimes any numbers (rejected unless PSD).
  if (in.ConsumeBool()) {
    for (double& v : p.covariance) v = fuzz::Number(in, 1.0);
  } else {
    for (int k = 0; k < 3; ++k) p.covariance[4 * k] = std::abs(fuzz::Number(in, 1.0));
  }
  return p;
}

map_t Map(FuzzedDataProvider& in) {
  map_t m{};
  m.seq = in.ConsumeIntegralInRange<int64_t>(-2, 40);
  m.utime = m.seq * 33333;
  m.num_planes = in.ConsumeIntegralInRange<int32_t>(0, 6);
  for (int i = 0; i < m.num_planes; ++i) {
    plane_t p{};
    p.id = in.ConsumeIntegralInRange<int64_t>(-1, 8);
    const double yaw = in.ConsumeFloatingPointInRange<double>(-M_PI, M_PI);
    p.normal[0] = static_cast<float>(in.ConsumeBool() ? std::cos(yaw) : fuzz::Number(in, 1));
    p.normal[1] = static_cast<float>(in.ConsumeBool() ? std::sin(yaw) : fuzz::Number(in, 1));
    p.normal[2] = static_cast<float>(in.ConsumeBool() ? 0.0 : fuzz::Number(in, 1));
    p.d = static_cast<float>(fuzz::Number(in, 10));
    for (float& c : p.centroid) c = static_cast<float>(fuzz::Number(in, 10));
    p.num_vertices = in.ConsumeIntegralInRange<int32_t>(0, 5);
    p.vertices.resize(p.num_vertices);
    for (auto& v : p.vertices) {
      v.resize(3);  // lcm-gen makes float[n][3] a vector of vectors
      for (float& c : v) c = static_cast<float>(fuzz::Number(in, 10));
    }
    p.num_points = in.ConsumeIntegral<int32_t>();
    p.rms = static_cast<float>(fuzz::Number(in, 0.1));
    m.planes.push_back(p);
  }
  m.num_groups = in.ConsumeIntegralInRange<int32_t>(0, 3);
  for (int g = 0; g < m.num_groups; ++g) {
    group_t group{};
    group.id = g;
    group.basis_id = in.ConsumeIntegralInRange<int64_t>(-1, 8);
    group.num_members = in.ConsumeIntegralInRange<int32_t>(0, 4);
    for (int k = 0; k < group.num_members; ++k) {
      group.members.push_back(in.ConsumeIntegralInRange<int64_t>(-1, 8));
    }
    m.groups.push_back(group);
  }
  return m;
}

status_t Status(FuzzedDataProvider& in) {
  status_t s{};
  s.utime = in.ConsumeIntegral<int64_t>();
  s.service = in.ConsumeRandomLengthString(24);
  s.frames_processed = in.ConsumeIntegral<int64_t>();
  s.frames_dropped = in.ConsumeIntegral<int64_t>();
  s.inputs_rejected = in.ConsumeIntegral<int64_t>();
  s.p50_ms = fuzz::Number(in, 100);
  s.p99_ms = fuzz::Number(in, 100);
  s.max_ms = fuzz::Number(in, 100);
  return s;
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  FuzzedDataProvider in(data, size);
  eval::RunRecorder recorder("/nonexistent", eval::EvalOptions{}, {}, "fuzz");
  // What the pictures are drawn from, kept as the recorder keeps it.
  eval::MapSnapshot map, world;
  std::vector<eval::PoseSample> truth, estimate;
  int64_t now_us = 0;
  static const char* const kChannels[] = {"POSE",      "SIM_TRUTH", "MAP",
                                          "SIM_WORLD", "STATUS",    "PLANES"};
  for (int i = 0; i < 96 && in.remaining_bytes() > 0; ++i) {
    const std::string channel = kChannels[in.ConsumeIntegralInRange<int>(0, 5)];
    now_us += in.ConsumeIntegralInRange<int64_t>(0, 100000);
    std::vector<uint8_t> bytes;
    if (in.ConsumeIntegralInRange<int>(0, 15) == 0) {
      bytes = in.ConsumeBytes<uint8_t>(in.ConsumeIntegralInRange(0, 256));
    } else if (channel == "POSE" || channel == "SIM_TRUTH") {
      const pose_t pose = Pose(in);
      bytes = fuzz::Encode(pose);
      eval::PoseSample sample;
      std::string why;
      if (eval::FromMessage(pose, &sample, &why)) {
        (channel == "POSE" ? estimate : truth).push_back(sample);
      }
    } else if (channel == "MAP" || channel == "SIM_WORLD") {
      const map_t m = Map(in);
      bytes = fuzz::Encode(m);
      eval::MapSnapshot snapshot;
      std::string why;
      if (eval::FromMessage(m, &snapshot, &why)) (channel == "MAP" ? map : world) = snapshot;
    } else if (channel == "STATUS") {
      bytes = fuzz::Encode(Status(in));
    } else {
      plane_set_t set{};
      set.seq = in.ConsumeIntegralInRange<int64_t>(-2, 40);
      bytes = fuzz::Encode(set);
    }
    std::string reason;
    eval::FeedEncoded(recorder, channel, bytes.data(), bytes.size(), now_us, &reason);
  }
  const eval::RunMetrics metrics = recorder.Metrics();
  eval::MetricsToJson(metrics, "fuzz");
  eval::MapToJson(map);
  eval::FormatSummary(metrics);
  eval::RenderErrorSvg(metrics.trajectory);
  eval::MapPicture picture;
  picture.world = &world;
  picture.map = &map;
  picture.truth = &truth;
  picture.estimate = &estimate;
  picture.metrics = &metrics;
  eval::RenderMapSvg(picture);
  return 0;
}
