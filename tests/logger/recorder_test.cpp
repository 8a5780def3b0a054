// The RunRecorder fed encoded bus messages (the logger's and relplane-eval's one code path)
// writes a complete, parseable run folder.
#include <gtest/gtest.h>

#include <filesystem>

#include "convert.hpp"
#include "fixtures.hpp"
#include "json_check.hpp"
#include "messages.hpp"
#include "relplane/eval/files.hpp"
#include "relplane/eval/tum.hpp"
#include "xml_check.hpp"

namespace relplane::eval {
namespace {

namespace fs = std::filesystem;

class RecorderTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::path(::testing::TempDir()) /
           (std::string("recorder-") +
            ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  template <class M>
  FeedResult Feed(RunRecorder& r, const std::string& channel, const M& msg, int64_t t_us) {
    const std::vector<uint8_t> bytes = testing::Encode(msg);
    std::string reason;
    return FeedEncoded(r, channel, bytes.data(), bytes.size(), t_us, &reason);
  }

  std::string Read(const std::string& name) {
    std::string text;
    EXPECT_TRUE(ReadFile((dir_ / name).string(), &text)) << name;
    return text;
  }

  fs::path dir_;
};

TEST_F(RecorderTest, EncodedMessagesBecomeACompleteRunFolder) {
  RunRecorder recorder(dir_.string(), EvalOptions{}, {{"ate_rmse_max_m", 0.05}, {"dropped_max", 1}},
                       "test");
  const std::vector<PoseSample> truth = testing::LoopInRoom();
  EXPECT_EQ(Feed(recorder, "SIM_WORLD", testing::MapMessage(testing::Room()), 0),
            FeedResult::kUsed);
  for (const PoseSample& t : truth) {
    const int64_t at = 1000 + t.seq * 33000;
    PoseSample e = t;
    e.position.x() += 0.02;  // a constant 2 cm error
    Feed(recorder, "SIM_TRUTH", testing::PoseMessage(t), at);
    Feed(recorder, "PLANES", testing::PlanesMessage(t.seq), at + 4000);
    Feed(recorder, "POSE", testing::PoseMessage(e), at + 10000);
  }
  MapSnapshot map;
  map.planes = testing::Room().planes;
  map.groups = {{0, 0, {0, 1, 2}}};
  Feed(recorder, "MAP", testing::MapMessage(map), 5000000);
  Feed(recorder, "STATUS", testing::StatusMessage("relplane-mapper", 10, 3.0f), 5000000);
  EXPECT_EQ(Feed(recorder, "SENSOR_POINTS", testing::PlanesMessage(0), 0), FeedResult::kIgnored);
  EXPECT_TRUE(recorder.Changed());

  std::string reason;
  ASSERT_TRUE(recorder.Write(&reason)) << reason;
  EXPECT_FALSE(recorder.Changed());
  const RunMetrics& m = recorder.LastMetrics();
  EXPECT_EQ(m.run.estimate_poses, static_cast<int64_t>(truth.size()));
  EXPECT_NEAR(m.trajectory.ate_rmse_m, 0.02, 1e-6);
  EXPECT_NEAR(m.timing.end_to_end.p50_ms, 10.0, 1e-9);
  EXPECT_NEAR(m.timing.segmenter.max_ms, 4.0, 1e-9);
  EXPECT_NEAR(m.timing.mapper.p99_ms, 6.0, 1e-9);
  EXPECT_NEAR(m.run.wall_rate_hz, 1e6 / 33000, 1e-6);
  EXPECT_NEAR(m.run.sim_rate_hz, 10.0, 1e-9);
  EXPECT_EQ(m.map.walls_mapped, 4);
  EXPECT_EQ(m.timing.frames_dropped_total, 2);
  ASSERT_EQ(m.expectations.size(), 2u);
  EXPECT_TRUE(m.expectations[0].pass);
  EXPECT_FALSE(m.expectations[1].pass);  // 2 dropped > 1

  std::vector<PoseSample> back;
  ASSERT_TRUE(ParseTum(Read("trajectory.tum"), &back, &reason)) << reason;
  EXPECT_EQ(back.size(), truth.size());
  ASSERT_TRUE(ParseTum(Read("truth.tum"), &back, &reason)) << reason;
  EXPECT_EQ(back.size(), truth.size());
  testing::Json json;
  ASSERT_TRUE(testing::ParseJson(Read("metrics.json"), &json, &reason)) << reason;
  EXPECT_FALSE(json["expect_pass"].boolean);
  ASSERT_TRUE(testing::ParseJson(Read("map.json"), &json, &reason)) << reason;
  EXPECT_EQ(json["groups"][0]["members"].items.size(), 3u);
  EXPECT_TRUE(testing::CheckXml(Read("map.svg"), &reason)) << reason;
  EXPECT_TRUE(testing::CheckXml(Read("error.svg"), &reason)) << reason;
  for (const auto& entry : fs::directory_iterator(dir_)) {
    EXPECT_NE(entry.path().extension(), ".tmp") << "temporary file left behind";
  }
}

TEST_F(RecorderTest, BadMessagesAreRejectedWithAReason) {
  RunRecorder recorder(dir_.string(), EvalOptions{}, {}, "test");
  std::string reason;
  const uint8_t garbage[] = {1, 2, 3, 4, 5};
  EXPECT_EQ(FeedEncoded(recorder, "POSE", garbage, sizeof(garbage), 0, &reason),
            FeedResult::kRejected);
  EXPECT_EQ(reason.rfind("POSE: undecodable", 0), 0u) << reason;
  PoseSample bad = testing::Pose(1, 0, 0, 0);
  relplane::pose_t msg = testing::PoseMessage(bad);
  msg.position[0] = std::nan("");
  EXPECT_EQ(Feed(recorder, "POSE", msg, 0), FeedResult::kRejected);
  msg = testing::PoseMessage(bad);
  for (double& q : msg.orientation) q = 0.0;
  EXPECT_EQ(Feed(recorder, "SIM_TRUTH", msg, 0), FeedResult::kRejected);
  // Every other field valid, so only the name can be the reason.
  relplane::status_t status = testing::StatusMessage("relplane-mapper", 1, 1.0f);
  status.service = "relplane-\x1b[2Jmapper";  // a terminal escape in the name
  EXPECT_EQ(Feed(recorder, "STATUS", status, 0), FeedResult::kRejected);
  status.service = std::string(65, 'a');
  EXPECT_EQ(Feed(recorder, "STATUS", status, 0), FeedResult::kRejected);
  status.service = "relplane-mapper";
  EXPECT_EQ(Feed(recorder, "STATUS", status, 0), FeedResult::kUsed);
  ASSERT_TRUE(recorder.Write(&reason));
  EXPECT_EQ(recorder.LastMetrics().run.estimate_poses, 0);
}

TEST_F(RecorderTest, WriteFailsWithAReasonWhenTheFolderIsGone) {
  RunRecorder recorder((dir_ / "missing" / "deeper").string(), EvalOptions{}, {}, "test");
  std::string reason;
  EXPECT_FALSE(recorder.Write(&reason));
  EXPECT_NE(reason.find("cannot write"), std::string::npos) << reason;
}

}  // namespace
}  // namespace relplane::eval
