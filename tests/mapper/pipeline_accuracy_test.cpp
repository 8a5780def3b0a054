// Issue 4 targets through the real EM segmenter, in one process: the simulator's
// frames are segmented and mapped as the services do (through their message conversions), and
// the map is scored by the evaluation's own metrics. The ideal-segmenter tests check the mapper
// alone; here a wall's last sample lands up to a ray spacing short of its end, as it does live.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>

// The shells' headers share their names, so each is named by its path.
#include "../../services/mapper/convert.hpp"
#include "../../services/mapper/options_yaml.hpp"
#include "../../services/segmenter/convert.hpp"
#include "../../services/segmenter/options_yaml.hpp"
#include "../../services/sim/convert.hpp"
#include "../../services/sim/options_yaml.hpp"
#include "relplane/eval/map_metrics.hpp"
#include "relplane/eval/trajectory_metrics.hpp"
#include "relplane/mapper/mapper.hpp"
#include "relplane/segmenter/segmenter.hpp"
#include "relplane/sim/simulation.hpp"

namespace relplane {
namespace {

struct PipelineResult {
  eval::TrajectoryMetrics trajectory;
  eval::MapMetrics map;
  std::vector<double> reached_ends;  // end errors of the true ends the best match reaches
};

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

eval::PoseSample Sample(int64_t seq, const Eigen::Vector3d& position, double yaw) {
  eval::PoseSample s;
  s.seq = s.utime = seq;
  s.position = position;
  s.orientation = Eigen::Quaterniond(Eigen::AngleAxisd(yaw, Eigen::Vector3d::UnitZ()));
  return s;
}

// The scenario as its YAML has it; a sigma >= 0 and a seed > 0 replace the sensor's.
PipelineResult RunScenario(const std::string& name, double sigma = -1.0, uint64_t seed = 0) {
  const std::string file = std::string(RELPLANE_SOURCE_DIR) + "/scenarios/" + name + ".yaml";
  sim::ServiceOptions sim_options = sim::LoadServiceOptions(file);
  if (sigma >= 0.0) sim_options.sim.sensor.noise_sigma = sigma;
  if (seed > 0) sim_options.sim.sensor.seed = seed;
  sim::Simulation simulation(sim_options.sim);
  segmenter::Segmenter segmenter(segmenter::LoadServiceOptions(file).segmenter);
  mapper::Mapper mapper(mapper::LoadMapperOptions(file));
  std::vector<eval::PoseSample> estimate, truth;
  for (int64_t k = 0; k < simulation.NumIterations(); ++k) {
    const point_cloud_t cloud_msg = sim::ToPointCloud(simulation.Frame(k), k, k);
    segmenter::Cloud cloud;
    std::string reason;
    EXPECT_TRUE(segmenter::FromPointCloud(cloud_msg, &cloud, &reason)) << reason;
    const plane_set_t set = segmenter::ToPlaneSet(segmenter.Segment(cloud), k, k);
    std::vector<mapper::PlaneInput> planes;
    EXPECT_TRUE(mapper::FromPlaneSet(set, &planes, &reason)) << reason;
    const mapper::PoseEstimate pose = mapper.Process(k, planes);
    estimate.push_back(Sample(k, {pose.pose.x, pose.pose.y, mapper.Height()}, pose.pose.yaw));
    const Eigen::Isometry3d t = simulation.SensorPose(k);
    truth.push_back(Sample(k, t.translation(), 0.0));
    truth.back().orientation = Eigen::Quaterniond(t.rotation());
  }
  eval::MapSnapshot world, map;
  for (const sim::TruePlane& p : simulation.TruePlanes()) {
    world.planes.push_back(
        Record(p.id, p.normal, p.d, p.centroid, {p.corners.begin(), p.corners.end()}));
  }
  for (const mapper::MappedPlane& p : mapper.Map().planes) {
    map.planes.push_back(Record(p.id, p.normal, p.d, p.centroid, p.vertices));
  }
  eval::EvalOptions options;
  options.visibility.range_m = sim_options.sim.sensor.max_range;
  options.visibility.hfov_deg = sim_options.sim.sensor.hfov_deg;
  PipelineResult r;
  r.trajectory = eval::ComputeTrajectoryMetrics(eval::MatchBySeq(estimate, truth), 1.0);
  r.map = eval::ComputeMapMetrics(world, map, truth, options);
  // A true wall seen only in pieces is matched by one piece, whose far end lies metres from the
  // wall's end: score the ends the match reaches (within a quarter metre).
  for (const eval::WallMatch& wall : r.map.walls) {
    for (double error : wall.endpoint_error_m) {
      if (error < 0.25) r.reached_ends.push_back(error);
    }
  }
  return r;
}

void ExpectExact(const PipelineResult& r, size_t min_ends) {
  EXPECT_LT(r.trajectory.ate_rmse_m, 0.01);
  EXPECT_EQ(r.map.duplicates, 0);
  EXPECT_LT(r.map.offset_error_m.max, 0.01);
  EXPECT_LT(r.map.normal_error_deg.max, 0.1);
  EXPECT_GE(r.reached_ends.size(), min_ends);  // not met by mapping nothing
  for (double error : r.reached_ends) EXPECT_LT(error, 0.01);
}

TEST(PipelineEnds, StraightHallwayNoiseFreeWallsEndAtTheirCorners) {
  // The side walls' far ends meet the end wall 6-8 m away, where rays are 6-8 cm apart.
  ExpectExact(RunScenario("straight_hallway"), 4);
}

TEST(PipelineEnds, OfficeNoiseFreeWallsEndAtTheirCorners) {
  ExpectExact(RunScenario("office"), 12);
}

// σ = 1 cm on the other sensor with a noise seed the scenario does not use: a partition's edge
// seen once 0.45 m into the door beside it (its pieces joined over the lintel) placed a door
// frame's group, and every room after it, 0.44 m along the partition (ATE 0.34 m).
TEST(PipelineAccuracy, OfficeOtherSensorNoisySeed4) {
  const PipelineResult r = RunScenario("office_other_sensor", 0.01, 4);
  EXPECT_LE(r.trajectory.ate_rmse_m, 0.05);
  EXPECT_EQ(r.map.duplicates, 0);
  EXPECT_LT(r.map.offset_error_m.max, 0.05);
  EXPECT_LT(r.map.normal_error_deg.max, 1.0);
}

}  // namespace
}  // namespace relplane
