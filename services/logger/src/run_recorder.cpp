#include "relplane/eval/run_recorder.hpp"

#include <utility>

#include "relplane/eval/expectations.hpp"
#include "relplane/eval/files.hpp"
#include "relplane/eval/report_json.hpp"
#include "relplane/eval/svg.hpp"
#include "relplane/eval/tum.hpp"

namespace relplane::eval {
namespace {

std::vector<PoseSample> Values(const std::map<int64_t, PoseSample>& by_seq) {
  std::vector<PoseSample> out;
  out.reserve(by_seq.size());
  for (const auto& [seq, pose] : by_seq) out.push_back(pose);
  return out;
}

}  // namespace

RunRecorder::RunRecorder(std::string out_dir, EvalOptions options, std::vector<Expectation> expect,
                         std::string source)
    : out_dir_(std::move(out_dir)),
      options_(options),
      expect_(std::move(expect)),
      source_(std::move(source)) {}

void RunRecorder::OnPose(const PoseSample& pose, int64_t receive_us) {
  estimate_[pose.seq] = pose;
  if (first_pose_us_ < 0) first_pose_us_ = receive_us;
  last_pose_us_ = receive_us;
  timing_.Arrived(TimingRecorder::kPose, pose.seq, receive_us);
  changed_ = true;
}

void RunRecorder::OnTruth(const PoseSample& pose, int64_t receive_us) {
  truth_[pose.seq] = pose;
  timing_.Arrived(TimingRecorder::kCloud, pose.seq, receive_us);
  changed_ = true;
}

void RunRecorder::OnPlanes(int64_t seq, int64_t receive_us) {
  timing_.Arrived(TimingRecorder::kPlanes, seq, receive_us);
}

void RunRecorder::OnMap(MapSnapshot map, int64_t) {
  map_ = std::move(map);
  ++map_updates_;
  changed_ = true;
}

void RunRecorder::OnWorld(MapSnapshot world, int64_t) {
  world_ = std::move(world);
  changed_ = true;
}

void RunRecorder::OnStatus(const StatusSample& status, int64_t) {
  // An idle service repeats its counters every second: that is no reason to rewrite the folder.
  if (timing_.Status(status)) changed_ = true;
}

RunMetrics RunRecorder::Metrics() const {
  RunMetrics m;
  const std::vector<PoseSample> estimate = Values(estimate_);
  const std::vector<PoseSample> truth = Values(truth_);
  RunCounts& r = m.run;
  r.estimate_poses = static_cast<int64_t>(estimate.size());
  r.truth_poses = static_cast<int64_t>(truth.size());
  r.map_updates = map_updates_;
  for (const PoseSample& p : estimate) {
    switch (static_cast<PoseStatus>(p.status)) {
      case PoseStatus::kTracking:
        ++r.tracking;
        break;
      case PoseStatus::kMotionModel:
        ++r.motion_model;
        break;
      case PoseStatus::kInitializing:
        ++r.initializing;
        break;
      case PoseStatus::kLost:
        ++r.lost;
        break;
      default:
        break;
    }
  }
  if (estimate.size() >= 2) {
    r.duration_s = 1e-6 * static_cast<double>(last_pose_us_ - first_pose_us_);
    if (r.duration_s > 0) r.wall_rate_hz = static_cast<double>(estimate.size() - 1) / r.duration_s;
    const double sim_s = 1e-6 * static_cast<double>(estimate.back().utime - estimate.front().utime);
    if (sim_s > 0) r.sim_rate_hz = static_cast<double>(estimate.size() - 1) / sim_s;
  }
  m.trajectory = ComputeTrajectoryMetrics(MatchBySeq(estimate, truth), options_.rpe_segment_m);
  m.map = ComputeMapMetrics(world_, map_, truth, options_);
  m.timing = timing_.Compute();
  m.expectations = CheckExpectations(expect_, m);
  return m;
}

bool RunRecorder::Write(std::string* reason) {
  last_metrics_ = Metrics();
  const std::vector<PoseSample> estimate = Values(estimate_);
  const std::vector<PoseSample> truth = Values(truth_);
  MapPicture picture;
  picture.world = &world_;
  picture.map = &map_;
  picture.truth = &truth;
  picture.estimate = &estimate;
  picture.metrics = &last_metrics_;
  picture.width_px = options_.svg_width_px;
  const std::pair<const char*, std::string> files[] = {
      {"trajectory.tum", FormatTum(estimate)},
      {"truth.tum", FormatTum(truth)},
      {"map.json", MapToJson(map_)},
      {"metrics.json", MetricsToJson(last_metrics_, source_)},
      {"map.svg", RenderMapSvg(picture)},
      {"error.svg", RenderErrorSvg(last_metrics_.trajectory, options_.svg_width_px)},
  };
  for (const auto& [name, content] : files) {
    if (!WriteFileAtomic(out_dir_ + "/" + name, content, reason)) return false;
  }
  changed_ = false;
  return true;
}

}  // namespace relplane::eval
