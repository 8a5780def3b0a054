#include "relplane/accuracy/scenario_run.hpp"

#include <yaml-cpp/yaml.h>

#include <cmath>
#include <fstream>
#include <map>
#include <sstream>

// The shells' headers share their names, so each is named by its path.
#include "../../../services/mapper/convert.hpp"
#include "../../../services/mapper/options_yaml.hpp"
#include "../../../services/segmenter/convert.hpp"
#include "../../../services/segmenter/options_yaml.hpp"
#include "../../../services/sim/convert.hpp"
#include "../../../services/sim/options_yaml.hpp"
#include "overrides.hpp"
#include "relplane/common/options.hpp"
#include "relplane/mapper/mapper.hpp"
#include "relplane/mapper/odometry.hpp"
#include "relplane/mapper/pose_covariance.hpp"
#include "relplane/segmenter/segmenter.hpp"
#include "relplane/sim/odometry_stream.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane::accuracy {
namespace {

// The scenario's text with the overrides applied; the file's own text when there are none, so
// that messages name the file's lines.
std::string ScenarioText(const RunSpec& spec) {
  std::ifstream in(spec.file);
  if (!in) throw config::ConfigError(spec.file + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  if (spec.overrides.empty()) return text.str();
  YAML::Node doc;
  try {
    doc = YAML::Load(text.str());
  } catch (const YAML::ParserException& e) {
    throw config::ConfigError(spec.file + ":" + std::to_string(e.mark.line + 1) +
                              ": invalid YAML: " + e.msg);
  }
  for (const std::string& o : spec.overrides) launch::ApplyOverride(doc, launch::ParseOverride(o));
  return YAML::Dump(doc);
}

eval::PlaneRecord Record(int64_t id, const Eigen::Vector3d& normal, double d,
                         const Eigen::Vector3d& centroid, std::vector<Eigen::Vector3d> vertices) {
  eval::PlaneRecord r;
  r.id = id;
  r.normal = normal;
  r.d = d;
  r.centroid = centroid;
  r.vertices = std::move(vertices);
  return r;
}

eval::PoseSample Sample(int64_t seq, const Eigen::Vector3d& position,
                        const Eigen::Quaterniond& orientation) {
  eval::PoseSample s;
  s.seq = s.utime = seq;
  s.position = position;
  s.orientation = orientation;
  return s;
}

// The three services' sections, each read and checked as the service reads its own.
struct Sections {
  sim::ServiceOptions sim;
  segmenter::ServiceOptions segmenter;
  mapper::MapperOptions mapper;
};

Sections ReadSections(const RunSpec& spec) {
  const std::string text = ScenarioText(spec);
  const std::string name = spec.overrides.empty() ? spec.file : spec.file + " (with --set)";
  Sections s;
  s.sim = sim::ReadServiceOptions(config::Reader::FromString(text, name, "sim"));
  config::Reader segmenter_reader = config::Reader::FromString(text, name, "segmenter");
  s.segmenter = segmenter::ReadServiceOptions(segmenter_reader);
  segmenter_reader.Finish();
  config::Reader mapper_reader = config::Reader::FromString(text, name, "mapper");
  s.mapper = mapper::ReadMapperOptions(mapper_reader);
  mapper_reader.Finish();
  return s;
}

}  // namespace

void CheckScenario(const RunSpec& spec) { ReadSections(spec); }

WorldKind ClassifyScenario(const RunSpec& spec) {
  return ClassifyWorld(sim::Simulation(ReadSections(spec).sim.sim));
}

RunResult RunScenario(const RunSpec& spec) {
  const Sections sections = ReadSections(spec);
  const sim::ServiceOptions& sim_options = sections.sim;
  sim::Simulation simulation(sim_options.sim);
  segmenter::Segmenter segmenter(sections.segmenter.segmenter);
  mapper::Mapper mapper(sections.mapper);
  // Wheel odometry when the scenario has it, through the messages as ODOMETRY carries it.
  sim::OdometryStream odometry_stream(sim_options.odometry, simulation);
  mapper::OdometryIntegrator odometry;
  RunResult r;
  r.kind = ClassifyWorld(simulation);
  std::vector<eval::PoseSample> estimate, truth;
  const std::vector<sim::TruePlane> true_planes = simulation.TruePlanes();
  for (int64_t k = 0; k < simulation.NumIterations(); ++k) {
    ++r.frames;
    const Eigen::Isometry3d t = simulation.SensorPose(k);
    truth.push_back(Sample(k, t.translation(), Eigen::Quaterniond(t.rotation())));
    FramePose& frame = r.poses.emplace_back();
    frame.seq = k;
    frame.true_x = t.translation().x();
    frame.true_y = t.translation().y();
    const Eigen::Vector3d forward = t.rotation() * Eigen::Vector3d::UnitX();
    frame.true_yaw = std::atan2(forward.y(), forward.x());
    for (const sim::TimedOdometry& due : odometry_stream.UpTo(k)) {
      mapper::OdometryReading reading;
      std::string why;
      if (!mapper::FromOdometry(sim::ToOdometry(due.reading, due.utime), &reading, &why) ||
          !odometry.Add(reading)) {
        ++r.rejected_odometry;
      }
    }
    // Through the messages, as the services pass them: a refused message is counted and the
    // frame gets no pose, as live.
    const point_cloud_t cloud_msg = sim::ToPointCloud(simulation.Frame(k), k, k);
    segmenter::Cloud cloud;
    std::string reason;
    if (!segmenter::FromPointCloud(cloud_msg, &cloud, &reason)) {
      ++r.rejected_frames;
      continue;
    }
    const segmenter::Result segmented = segmenter.Segment(cloud);
    if (spec.plane_errors) {
      for (const PlaneError& e : PlaneErrors(k, t, segmented.planes, true_planes)) {
        r.plane_errors.push_back(e);
      }
    }
    const plane_set_t set = segmenter::ToPlaneSet(segmented, k, k);
    std::vector<mapper::PlaneInput> planes;
    if (!mapper::FromPlaneSet(set, &planes, &reason)) {
      ++r.rejected_frames;
      continue;
    }
    const mapper::PoseEstimate pose =
        mapper.Process(k, planes, odometry.TakeUntil(simulation.Utime(k)));
    frame.status = static_cast<int>(pose.status);
    frame.x = pose.pose.x;
    frame.y = pose.pose.y;
    frame.yaw = pose.pose.yaw;
    frame.planes = pose.planes;
    if (pose.status == mapper::PoseStatus::kLost) ++r.lost_frames;
    if (pose.status == mapper::PoseStatus::kMotionModel) ++r.motion_model_frames;
    estimate.push_back(
        Sample(k, {pose.pose.x, pose.pose.y, mapper.Height()},
               Eigen::Quaterniond(Eigen::AngleAxisd(pose.pose.yaw, Eigen::Vector3d::UnitZ()))));
    estimate.back().status = static_cast<int>(pose.status) + 1;  // pose_t's status numbering
    estimate.back().covariance = mapper::ObservabilityOf(pose).covariance;
  }

  eval::MapSnapshot world, map;
  for (const sim::TruePlane& p : true_planes) {
    world.planes.push_back(
        Record(p.id, p.normal, p.d, p.centroid, {p.corners.begin(), p.corners.end()}));
  }
  for (const mapper::MappedPlane& p : mapper.Map().planes) {
    map.planes.push_back(Record(p.id, p.normal, p.d, p.centroid, p.vertices));
  }
  eval::EvalOptions options;
  options.visibility.range_m = sim_options.sim.sensor.max_range;
  options.visibility.hfov_deg = sim_options.sim.sensor.hfov_deg;
  options.visibility.min_wall_length_m = spec.min_wall_length_m;
  r.trajectory = eval::ComputeTrajectoryMetrics(eval::MatchBySeq(estimate, truth), 1.0);
  r.map = eval::ComputeMapMetrics(world, map, truth, options);
  std::map<int64_t, geometry::Segment2> segments;
  for (const eval::WallLine& line : eval::WallsOf(world.planes)) segments[line.id] = line.segment;
  for (const eval::WallMatch& wall : r.map.walls) {
    for (double error : wall.endpoint_error_m) {
      if (error < 0.25) r.reached_ends.push_back(error);
    }
    const auto it = segments.find(wall.true_id);
    r.wall_segments.push_back(it != segments.end() ? it->second : geometry::Segment2{});
  }
  return r;
}

}  // namespace relplane::accuracy
