#pragma once
// Pure decisions of a run: which command lines to start, in which order to stop them, where
// the run folder goes, and how a child's end reads in a report.

#include <ctime>
#include <string>
#include <vector>

#include "scenario.hpp"

namespace relplane::launch {

// The service whose normal end (exit 0) ends a live run.
inline const std::string kSourceService = "sim";
// The source of a replay: lcm-logplayer feeding a recorded log.
inline const std::string kReplaySource = "logplayer";
// The services a replay feeds (the simulator's part comes from the log).
inline const std::vector<std::string> kReplayServices = {"segmenter", "mapper", "logger"};
// The channels a replay feeds: the simulator's (wheel odometry too, when it was on). The
// services' own outputs are made afresh.
inline const std::string kReplayChannels = "^(SENSOR_POINTS|SIM_TRUTH|SIM_WORLD|ODOMETRY)$";

// The simulator's channels but the clouds: what a replay plays on the main bus when clouds have
// a bus of their own.
inline const std::string kReplaySimChannels = "^(SIM_TRUTH|SIM_WORLD)$";
// The second player of such a replay; its end (exit 0) is normal and ends nothing.
inline const std::string kReplaySimSource = "logplayer-sim";
// The cloud bus's recorder and its log in the run folder, merged into bus.lcmlog at the end.
inline const std::string kCloudRecorder = "lcm-logger-clouds";
inline const std::string kCloudLog = "clouds.lcmlog";

// The mapper's checkpoint in the run folder: it resumes from it when restarted.
inline const std::string kMapperJournal = "mapper.journal";

// One process of the run: a name for its output prefix and its command line.
struct ChildSpec {
  std::string name;
  std::vector<std::string> argv;  // argv[0] is the executable's path
};

// The command line of service `name`: relplane-NAME --config SCENARIO --lcm-url URL, plus
// --out RUN for the logger, --checkpoint RUN/mapper.journal for the mapper and --rate for the
// simulator when the scenario sets launch.rate_hz. `iterations` >= 0 is passed to the simulator as
// --iterations.
ChildSpec ServiceCommand(const std::string& name, const std::string& bin_dir,
                         const std::string& scenario_file, const std::string& url,
                         const std::string& run_dir, const LaunchOptions& options,
                         long iterations = -1);

// Whether service `name` publishes or reads SENSOR_POINTS, and so joins the cloud bus.
bool UsesClouds(const std::string& name);

// `spec` of service `name` with --cloud-url CLOUD_URL added when the service uses clouds and
// clouds have a bus of their own (`cloud_url` differs from `url`).
ChildSpec WithCloudUrl(ChildSpec spec, const std::string& url, const std::string& cloud_url);

// The recorders `record` (LaunchOptions::record) asks for: none for kRecordNothing, else
// RecorderCommand on `url` and, when every channel is recorded and clouds have a bus of their
// own, a second lcm-logger (kCloudRecorder) writing `cloud_url` to RUN/clouds.lcmlog.
std::vector<ChildSpec> RecorderCommands(const std::string& lcm_logger, const std::string& url,
                                        const std::string& cloud_url, const std::string& run_dir,
                                        const std::string& record);

// The recorder: lcm-logger writing the channels of `url` that `record` (LaunchOptions::record,
// not kRecordNothing) asks for to RUN/bus.lcmlog.
ChildSpec RecorderCommand(const std::string& lcm_logger, const std::string& url,
                          const std::string& run_dir, const std::string& record = kRecordAll);

// A POSIX extended regular expression matching every channel name but `channel` (lcm-logger's
// --channel has no negation; LCM anchors it as ^...$).
std::string EveryChannelBut(const std::string& channel);

// lcm-logplayer playing `log` onto `url` at `speed` (1: as recorded), the simulator's channels.
ChildSpec ReplayCommand(const std::string& lcm_logplayer, const std::string& url,
                        const std::string& log, double speed);

// The players of a replay, the source (kReplaySource) last: ReplayCommand when `cloud_url` is
// `url`; else SENSOR_POINTS played onto `cloud_url` (kReplaySource) and the simulator's other
// channels onto `url` (kReplaySimSource), both from the same log.
std::vector<ChildSpec> ReplayCommands(const std::string& lcm_logplayer, const std::string& url,
                                      const std::string& cloud_url, const std::string& log,
                                      double speed);

// Services in the order they are stopped: the source first (so no new data enters), then the
// pipeline from its head (segmenter, mapper, logger) so each stage sees its input's end, then
// anything else in the order listed. The recorder is stopped after all of these.
std::vector<std::string> StopOrder(const std::vector<std::string>& services,
                                   const std::string& source = kSourceService);

// Services in the order they are started: every other service first, so their subscriptions
// exist before the source publishes, the source last.
std::vector<std::string> StartOrder(const std::vector<std::string>& services,
                                    const std::string& source = kSourceService);

// ROOT/NAME-YYYYmmddTHHMMSSZ (UTC).
std::string DefaultRunDir(const std::string& root, const std::string& name, std::time_t now);

// "exited with code 3", "was killed by signal 9 (Killed)", from a waitpid status.
std::string DescribeExit(int wait_status);

}  // namespace relplane::launch
