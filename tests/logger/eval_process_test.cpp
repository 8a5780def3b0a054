// relplane-eval as a real process on a bus.lcmlog written here with LCM's eventlog API.
#include <gtest/gtest.h>
#include <lcm/eventlog.h>
#include <unistd.h>

#include <filesystem>

#include "fixtures.hpp"
#include "messages.hpp"
#include "process.hpp"
#include "run_folder_check.hpp"

namespace relplane::testing {
namespace {

namespace fs = std::filesystem;

class EventLogWriter {
 public:
  explicit EventLogWriter(const std::string& path) : log_(lcm_eventlog_create(path.c_str(), "w")) {}
  ~EventLogWriter() { lcm_eventlog_destroy(log_); }
  bool Ok() const { return log_ != nullptr; }

  template <class M>
  void Write(const std::string& channel, const M& msg, int64_t timestamp_us) {
    std::vector<uint8_t> data = Encode(msg);
    lcm_eventlog_event_t event{};
    event.eventnum = count_++;
    event.timestamp = timestamp_us;
    event.channellen = static_cast<int32_t>(channel.size());
    event.datalen = static_cast<int32_t>(data.size());
    event.channel = const_cast<char*>(channel.c_str());
    event.data = data.data();
    lcm_eventlog_write_event(log_, &event);
  }

 private:
  lcm_eventlog_t* log_;
  int64_t count_ = 0;
};

TEST(EvalProcess, ScoresARecordedLogLikeTheLogger) {
  const ScratchDir scratch("relplane-eval-log");
  const std::string& dir = scratch.Path();
  {
    EventLogWriter log(dir + "/bus.lcmlog");
    ASSERT_TRUE(log.Ok());
    log.Write("SIM_WORLD", MapMessage(Room()), 0);
    const std::vector<eval::PoseSample> truth = LoopInRoom();
    for (const eval::PoseSample& t : truth) {
      const int64_t at = 1000000 + t.seq * 33333;
      eval::PoseSample e = t;
      e.position.y() -= 0.03;
      log.Write("SIM_TRUTH", PoseMessage(t), at);
      log.Write("SENSOR_POINTS", PlanesMessage(t.seq), at);  // not read: ignored
      log.Write("PLANES", PlanesMessage(t.seq), at + 5000);
      log.Write("POSE", PoseMessage(e), at + 12000);
    }
    eval::MapSnapshot map;
    map.planes = {Wall(1, {-1, -2}, {5, -2}), Wall(2, {-1, -1.95}, {2, -1.95})};
    log.Write("MAP", MapMessage(map), 9000000);
  }
  // The scenario beside the log supplies expect: unless --config says otherwise.
  WriteFileForTest(dir + "/scenario.yaml", "name: t\nexpect: {duplicates_max: 0}\n");
  std::string out, err;
  ASSERT_EQ(RunProcess({RELPLANE_EVAL_PATH, dir + "/bus.lcmlog", "--out", dir + "/scored"}, 30.0,
                       &out, &err),
            0)
      << err;
  const RunFolder folder = CheckRunFolder(dir + "/scored");
  EXPECT_EQ(folder.trajectory.size(), LoopInRoom().size());
  EXPECT_EQ(folder.metrics["source"].text, "relplane-eval");
  EXPECT_NEAR(folder.metrics["trajectory"]["ate_rmse_m"].number, 0.03, 1e-6);
  EXPECT_NEAR(folder.metrics["timing"]["end_to_end"]["p50_ms"].number, 12.0, 1e-9);
  EXPECT_NEAR(folder.metrics["timing"]["stages"]["mapper"]["max_ms"].number, 7.0, 1e-9);
  EXPECT_EQ(folder.metrics["map"]["duplicates"].number, 1);
  EXPECT_EQ(folder.metrics["map"]["missed"].number, 3);
  EXPECT_FALSE(folder.metrics["expect"][0]["pass"].boolean);
  EXPECT_NE(out.find("duplicates_max"), std::string::npos) << out;
  EXPECT_NE(out.find("FAIL"), std::string::npos) << out;
}

TEST(EvalProcess, MissingOrUnreadableLogIsOneLineAndExitTwo) {
  const ScratchDir scratch("relplane-eval-bad");
  const std::string& dir = scratch.Path();
  std::string out, err;
  EXPECT_EQ(RunProcess({RELPLANE_EVAL_PATH, dir + "/nothing.lcmlog", "--out", dir + "/o"}, 10.0,
                       &out, &err),
            2);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
  EXPECT_NE(err.find("nothing.lcmlog"), std::string::npos) << err;

  WriteFileForTest(dir + "/garbage.lcmlog", "this is not an LCM log at all\n");
  EXPECT_EQ(RunProcess({RELPLANE_EVAL_PATH, dir + "/garbage.lcmlog", "--out", dir + "/o"}, 10.0,
                       &out, &err),
            2);
  EXPECT_EQ(std::count(err.begin(), err.end(), '\n'), 1) << err;
}

}  // namespace
}  // namespace relplane::testing
