// The service shell on the in-process bus: options from YAML, PLANES per cloud, bad input
// counted and survived.

#include "service.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <relplane/plane_set_t.hpp>
#include <relplane/pose_t.hpp>

#include "convert.hpp"
#include "options_yaml.hpp"
#include "synthetic_scene.hpp"

namespace relplane::segmenter {
namespace {

ServiceOptions FromYaml(const std::string& yaml) {
  config::Reader r = config::Reader::FromString(yaml, "test.yaml", "segmenter");
  ServiceOptions o = ReadServiceOptions(r);
  r.Finish();
  return o;
}

TEST(ServiceOptions, ReadsItsSectionAndRefusesUnknownOrBadKeys) {
  const ServiceOptions o = FromYaml(
      "sim: {rate_hz: 10}\nsegmenter:\n  noise: {sigma_max: 0.007, range_noise: 0.003}\n"
      "  em: {iterations: 5, min_support: 20}\n  proposals: {max_per_round: 3}\n"
      "  merge: {overlap_angle_deg: 0}\n  assignment: {inlier_sigmas: 2.5}\n"
      "  extents: {min_points: 200}\n  description: {points_max: 0}\n"
      "  max_points: 5000\n  seed: 7\n");
  EXPECT_FLOAT_EQ(o.segmenter.noise.sigma_max, 0.007f);
  EXPECT_FLOAT_EQ(o.segmenter.noise.range_noise, 0.003f);
  EXPECT_EQ(o.segmenter.em.iterations, 5);
  EXPECT_EQ(o.segmenter.em.min_support, 20);
  EXPECT_EQ(o.segmenter.proposals.max_per_round, 3);
  EXPECT_FLOAT_EQ(o.segmenter.merge.overlap_angle_deg, 0.0f);
  EXPECT_FLOAT_EQ(o.segmenter.assignment.inlier_sigmas, 2.5f);
  EXPECT_EQ(o.segmenter.extents.min_points, 200);
  EXPECT_EQ(o.segmenter.description.points_max, 0);
  EXPECT_EQ(o.segmenter.seed, 7u);
  EXPECT_EQ(o.max_points, 5000);
  EXPECT_EQ(FromYaml("segmenter: {}\n").segmenter.extents.min_points, Options{}.extents.min_points);
  EXPECT_THROW(FromYaml("segmenter:\n  noise: {sigma_mx: 0.01}\n"), config::ConfigError);
  EXPECT_THROW(FromYaml("segmenter:\n  nois: {sigma_max: 0.01}\n"), config::ConfigError);
  EXPECT_THROW(FromYaml("segmenter:\n  extents: {cell_size: -1}\n"), config::ConfigError);
  EXPECT_THROW(FromYaml("segmenter:\n  noise: {sigma_min: 0.05, sigma_max: 0.01}\n"),
               config::ConfigError);
  EXPECT_THROW(FromYaml("segmenter:\n  extents: {min_points: many}\n"), config::ConfigError);
  EXPECT_THROW(FromYaml("segmenter:\n  noise: 0.01\n"), config::ConfigError);
}

TEST(ServiceOptions, TheEstimatorsChoicesAreSettable) {
  const ServiceOptions o = FromYaml(
      "segmenter:\n  proposals: {min_neighbours: 10, max_flatness: 0.2, inlier_sigmas: 2.0}\n"
      "  seeds: {kept_support: 0.4, max_turn_deg: 8, max_shift: 0.3}\n"
      "  assignment: {crossing_angle_deg: 25}\n"
      "  extents: {trim_sigmas: 3, max_refits: 4, max_end_spacing: 0.2, range_cut_share: 0.95}\n"
      "  description: {leaning_rms: 4, min_line_share: 0.6, min_noise_points: 80}\n");
  const Options& s = o.segmenter;
  EXPECT_EQ(s.proposals.min_neighbours, 10);
  EXPECT_DOUBLE_EQ(s.proposals.max_flatness, 0.2);
  EXPECT_FLOAT_EQ(s.proposals.inlier_sigmas, 2.0f);
  EXPECT_FLOAT_EQ(s.seeds.kept_support, 0.4f);
  EXPECT_FLOAT_EQ(s.seeds.max_turn_deg, 8.0f);
  EXPECT_FLOAT_EQ(s.seeds.max_shift, 0.3f);
  EXPECT_FLOAT_EQ(s.assignment.crossing_angle_deg, 25.0f);
  EXPECT_FLOAT_EQ(s.extents.trim_sigmas, 3.0f);
  EXPECT_EQ(s.extents.max_refits, 4);
  EXPECT_FLOAT_EQ(s.extents.max_end_spacing, 0.2f);
  EXPECT_FLOAT_EQ(s.extents.range_cut_share, 0.95f);
  EXPECT_DOUBLE_EQ(s.description.leaning_rms, 4.0);
  EXPECT_DOUBLE_EQ(s.description.min_line_share, 0.6);
  EXPECT_EQ(s.description.min_noise_points, 80);
  for (const char* bad : {"proposals: {min_neighbours: 40}", "proposals: {max_flatness: 2}",
                          "seeds: {max_shift: 0}", "extents: {range_cut_share: 1.5}",
                          "description: {min_line_share: 0}", "seeds: {max_turn: 5}"}) {
    EXPECT_THROW(FromYaml(std::string("segmenter:\n  ") + bad + "\n"), config::ConfigError) << bad;
  }
}

TEST(ServiceOptions, TheKinectPresetLoads) {
  const ServiceOptions o =
      LoadServiceOptions(std::string(RELPLANE_SOURCE_DIR) + "/services/segmenter/kinect.yaml");
  EXPECT_FLOAT_EQ(o.segmenter.noise.sigma_max, 0.007f);
  EXPECT_FLOAT_EQ(o.segmenter.noise.range_noise, 0.003f);
}

std::string ErrorOf(const std::string& yaml) {
  try {
    FromYaml(yaml);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(ServiceOptions, AKeyOfTheFlatLayoutNamesWhereItMoved) {
  EXPECT_NE(ErrorOf("segmenter:\n  sigma_max: 0.007\n").find("moved to 'noise.sigma_max'"),
            std::string::npos);
  EXPECT_NE(ErrorOf("segmenter:\n  min_em_points: 9\n").find("moved to 'em.min_support'"),
            std::string::npos);
  EXPECT_NE(
      ErrorOf("segmenter:\n  describe_points_max: 0\n").find("moved to 'description.points_max'"),
      std::string::npos);
  // The switches of settled choices are gone: the segmenter always does what they turned on.
  for (const char* key :
       {"wall_end_estimate", "ray_noise_fit", "dominant_line_fit", "drop_pieceless_planes"}) {
    EXPECT_NE(ErrorOf(std::string("segmenter:\n  ") + key + ": false\n").find("always on"),
              std::string::npos)
        << key;
  }
}

TEST(ServiceOptions, SensorPresetByName) {
  EXPECT_FALSE(FromYaml("segmenter: {}\n").segmenter.sensor.Known());
  for (const char* name : {"kinect_v1", "realsense_d435", "tof"}) {
    const ServiceOptions o = FromYaml(std::string("segmenter:\n  sensor: ") + name + "\n");
    EXPECT_TRUE(o.segmenter.sensor.Known());
    EXPECT_EQ(o.segmenter.sensor.model.name, name);
  }
  const ServiceOptions share =
      FromYaml("segmenter:\n  sensor: tof\n  layer_rms_share: 0.3\n  grazing_margin_deg: 4\n");
  EXPECT_FLOAT_EQ(share.segmenter.sensor.layer_rms_share, 0.3f);
  EXPECT_FLOAT_EQ(share.segmenter.sensor.grazing_margin_deg, 4.0f);
  try {
    FromYaml("segmenter:\n  sensor: kinect\n");
    ADD_FAILURE() << "an unknown sensor loaded";
  } catch (const config::ConfigError& e) {
    EXPECT_NE(std::string(e.what()).find("segmenter.sensor"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("kinect_v1"), std::string::npos) << e.what();
  }
}

point_cloud_t Message(const Cloud& c, int64_t seq) {
  point_cloud_t msg;
  msg.utime = 100000 * seq;
  msg.seq = seq;
  msg.num_points = static_cast<int32_t>(c.size());
  msg.x = c.x;
  msg.y = c.y;
  msg.z = c.z;
  return msg;
}

class ServiceOnMemq : public ::testing::Test {
 protected:
  void SetUp() override {
    bus_ = bus::OpenLcmBus("memq://");
    bus::Subscribe<plane_set_t>(
        *bus_, "PLANES", [this](const plane_set_t& m) { planes_.push_back(m); },
        [](const std::string&) {});
  }
  void Drain() {
    while (bus_->Handle(20) > 0) {
    }
  }
  std::unique_ptr<bus::Bus> bus_;
  std::vector<plane_set_t> planes_;
};

TEST_F(ServiceOnMemq, PublishesOnePlaneSetPerCloudWithItsUtimeAndSeq) {
  ServiceOptions options;
  SegmenterService service(*bus_, options);
  service.Subscribe();
  testing::Sensor sensor;
  const Cloud cloud = testing::Render(testing::Office(), sensor).cloud;
  for (int64_t seq = 0; seq < 3; ++seq) bus::Publish(*bus_, "SENSOR_POINTS", Message(cloud, seq));
  Drain();
  ASSERT_EQ(planes_.size(), 3u);
  for (int64_t seq = 0; seq < 3; ++seq) {
    const plane_set_t& set = planes_[seq];
    EXPECT_EQ(set.seq, seq);
    EXPECT_EQ(set.utime, 100000 * seq);
    ASSERT_GE(set.num_planes, 5);
    EXPECT_EQ(set.num_planes, static_cast<int32_t>(set.planes.size()));
    for (int k = 0; k < set.num_planes; ++k) {
      const plane_t& p = set.planes[k];
      EXPECT_EQ(p.id, k);
      EXPECT_EQ(p.num_vertices, static_cast<int32_t>(p.vertices.size()));
      EXPECT_GE(p.num_vertices, 3);
      EXPECT_GT(p.d, 0.0f);  // normal towards the sensor at the origin
      EXPECT_GT(p.num_points, 0);
    }
  }
  EXPECT_EQ(service.Stats().Processed(), 3);
  EXPECT_EQ(service.Stats().Rejected(), 0);
}

TEST_F(ServiceOnMemq, EmptyCloudGivesAnEmptySetAndNonFinitePointsAreCounted) {
  SegmenterService service(*bus_, ServiceOptions{});
  service.Subscribe();
  bus::Publish(*bus_, "SENSOR_POINTS", Message(Cloud{}, 0));
  Cloud nan_cloud;
  for (int i = 0; i < 50; ++i) nan_cloud.Add(std::numeric_limits<float>::quiet_NaN(), 0, 0);
  bus::Publish(*bus_, "SENSOR_POINTS", Message(nan_cloud, 1));
  Drain();
  ASSERT_EQ(planes_.size(), 2u);
  EXPECT_EQ(planes_[0].num_planes, 0);
  EXPECT_EQ(planes_[1].num_planes, 0);
  const StatusSnapshot s = service.Stats().Snapshot();
  EXPECT_NE(s.detail.find("non-finite points dropped 50 (total 50)"), std::string::npos)
      << s.detail;
}

TEST_F(ServiceOnMemq, OversizeTruncatedAndForeignMessagesAreRejectedAndTheServiceGoesOn) {
  ServiceOptions options;
  options.max_points = 1000;
  SegmenterService service(*bus_, options);
  service.Subscribe();
  Cloud big;
  for (int i = 0; i < 1001; ++i) big.Add(2.0f, 0.001f * i, 0.0f);
  bus::Publish(*bus_, "SENSOR_POINTS", Message(big, 0));  // over max_points
  pose_t pose{};
  bus::Publish(*bus_, "SENSOR_POINTS", pose);  // foreign type
  point_cloud_t small = Message(Cloud{}, 1);
  small.num_points = 2;
  small.x = {1, 2};
  small.y = {1, 2};
  small.z = {1, 2};
  std::vector<uint8_t> bytes(small.getEncodedSize());
  small.encode(bytes.data(), 0, static_cast<int>(bytes.size()));
  bus_->PublishRaw("SENSOR_POINTS", bytes.data(), bytes.size() - 3);  // truncated
  bus::Publish(*bus_, "SENSOR_POINTS", Message(Cloud{}, 2));          // and a good one after
  Drain();
  EXPECT_EQ(service.Stats().Rejected(), 3);
  ASSERT_EQ(planes_.size(), 1u);
  EXPECT_EQ(planes_[0].seq, 2);
}

// The subscription decodes every cloud into one message and the service swaps its arrays into
// one cloud: a large frame after a small one (and the reverse) must not see the other's points.
TEST_F(ServiceOnMemq, CloudsOfChangingSizeGiveTheSamePlanesAsEachAlone) {
  SegmenterService service(*bus_, ServiceOptions{});
  service.Subscribe();
  testing::Sensor sensor;
  const Cloud office = testing::Render(testing::Office(), sensor).cloud;
  Cloud half = office;
  half.x.resize(office.size() / 2);
  half.y.resize(office.size() / 2);
  half.z.resize(office.size() / 2);
  const Cloud order[] = {office, half, Cloud{}, office, half};
  for (int64_t seq = 0; seq < 5; ++seq)
    bus::Publish(*bus_, "SENSOR_POINTS", Message(order[seq], seq));
  Drain();
  ASSERT_EQ(planes_.size(), 5u);
  auto same = [](const plane_set_t& a, const plane_set_t& b) {
    if (a.num_planes != b.num_planes) return false;
    for (int k = 0; k < a.num_planes; ++k) {
      if (a.planes[k].num_points != b.planes[k].num_points || a.planes[k].d != b.planes[k].d ||
          a.planes[k].vertices != b.planes[k].vertices) {
        return false;
      }
    }
    return true;
  };
  EXPECT_TRUE(same(planes_[0], planes_[3]));
  EXPECT_TRUE(same(planes_[1], planes_[4]));
  EXPECT_EQ(planes_[2].num_planes, 0);
  EXPECT_GE(planes_[0].num_planes, 5);
}

// Clouds read on one bus, planes published on another (the launcher's cloud bus): the cloud
// bus carries no PLANES and the main bus no clouds.
TEST(ServiceOnTwoBuses, ReadsCloudsOnTheCloudBusAndPublishesPlanesOnTheMainBus) {
  auto clouds = bus::OpenLcmBus("memq://");
  auto main_bus = bus::OpenLcmBus("memq://");
  int planes_on_main = 0, planes_on_clouds = 0;
  bus::Subscribe<plane_set_t>(
      *main_bus, "PLANES", [&](const plane_set_t&) { ++planes_on_main; },
      [](const std::string&) {});
  bus::Subscribe<plane_set_t>(
      *clouds, "PLANES", [&](const plane_set_t&) { ++planes_on_clouds; },
      [](const std::string&) {});
  SegmenterService service(*clouds, *main_bus, ServiceOptions{});
  service.Subscribe();
  testing::Sensor sensor;
  const Cloud cloud = testing::Render(testing::Office(), sensor).cloud;
  bus::Publish(*main_bus, "SENSOR_POINTS", Message(cloud, 0));  // not the cloud bus: ignored
  bus::Publish(*clouds, "SENSOR_POINTS", Message(cloud, 1));
  while (clouds->Handle(20) > 0 || main_bus->Handle(20) > 0) {
  }
  EXPECT_EQ(service.Stats().Processed(), 1);
  EXPECT_EQ(planes_on_main, 1);
  EXPECT_EQ(planes_on_clouds, 0);
}

TEST(Convert, MismatchedArraysAreRefused) {
  point_cloud_t msg{};
  msg.num_points = 3;
  msg.x = {1, 2, 3};
  msg.y = {1, 2};
  msg.z = {1, 2, 3};
  Cloud c;
  std::string reason;
  EXPECT_FALSE(FromPointCloud(msg, &c, &reason));
  EXPECT_NE(reason.find("num_points 3"), std::string::npos);
  EXPECT_FALSE(TakePointCloud(&msg, &c, &reason));
  EXPECT_EQ(msg.x.size(), 3u);  // refused: nothing taken
}

}  // namespace
}  // namespace relplane::segmenter
