// relplane-eval LOG --out DIR: scores a recorded bus.lcmlog offline and writes the same run
// folder the logger writes live, through the same RunRecorder.
#include <lcm/eventlog.h>

#include <filesystem>
#include <iostream>

#include "convert.hpp"
#include "options_yaml.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/options.hpp"
#include "relplane/eval/summary.hpp"

namespace {

constexpr int kExitBadLog = 2;

}  // namespace

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"Score a recorded relplane bus.lcmlog and write its run folder"};
  std::string log_path;
  std::string out_dir;
  std::string config;
  std::string log_level = "warn";
  bool quiet = false;
  parser.Add("LOG", &log_path, "Recorded LCM log (bus.lcmlog)").Required();
  parser.Add("--out", &out_dir, "Run folder to write (default: the log's folder)");
  parser.Add("--config", &config,
             "Scenario YAML for the logger section and expect: (default: scenario.yaml "
             "beside the log, when present)");
  parser.AddFlag("--quiet", &quiet, "Do not print the summary table");
  parser.Add("--log-level", &log_level, "trace, debug, info, warn, error, critical or off");
  if (const auto code = parser.Parse(argc, argv)) return *code;
  try {
    cli::SetupLogging("relplane-eval", log_level);
  } catch (const std::exception& e) {
    std::cerr << "relplane-eval: " << e.what() << "\n";
    return cli::kExitConfig;
  }

  namespace fs = std::filesystem;
  std::error_code ec;
  if (!fs::is_regular_file(log_path, ec)) {
    std::cerr << "relplane-eval: " << log_path << ": no such log file\n";
    return kExitBadLog;
  }
  const fs::path log_dir = fs::path(log_path).parent_path();
  if (out_dir.empty()) out_dir = log_dir.empty() ? "." : log_dir.string();
  if (config.empty() && fs::is_regular_file(log_dir / "scenario.yaml", ec)) {
    config = (log_dir / "scenario.yaml").string();
  }
  eval::EvalConfig cfg;
  try {
    if (!config.empty()) cfg = eval::LoadEvalConfig(config);
  } catch (const config::ConfigError& e) {
    std::cerr << "relplane-eval: " << e.what() << "\n";
    return cli::kExitConfig;
  }
  fs::create_directories(out_dir, ec);
  if (ec) {
    std::cerr << "relplane-eval: cannot create " << out_dir << ": " << ec.message() << "\n";
    return kExitBadLog;
  }

  lcm_eventlog_t* log = lcm_eventlog_create(log_path.c_str(), "r");
  if (log == nullptr) {
    std::cerr << "relplane-eval: " << log_path << ": cannot open as an LCM log\n";
    return kExitBadLog;
  }
  eval::RunRecorder recorder(out_dir, cfg.options, cfg.expect, "relplane-eval");
  int64_t events = 0;
  int64_t used = 0;
  int64_t rejected = 0;
  std::string reason;
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log)) {
    ++events;
    const std::string channel(event->channel, event->channellen);
    const auto result =
        eval::FeedEncoded(recorder, channel, static_cast<const uint8_t*>(event->data),
                          static_cast<size_t>(event->datalen), event->timestamp, &reason);
    if (result == eval::FeedResult::kUsed) ++used;
    if (result == eval::FeedResult::kRejected) {
      if (rejected++ == 0) std::cerr << "relplane-eval: rejected " << reason << "\n";
    }
    lcm_eventlog_free_event(event);
  }
  lcm_eventlog_destroy(log);
  if (events == 0) {
    std::cerr << "relplane-eval: " << log_path << ": no events (not an LCM log?)\n";
    return kExitBadLog;
  }
  if (!recorder.Write(&reason)) {
    std::cerr << "relplane-eval: " << reason << "\n";
    return 1;
  }
  if (!quiet) {
    std::cout << eval::FormatSummary(recorder.LastMetrics());
    std::cout << "  events " << events << ", used " << used << ", rejected " << rejected
              << "; wrote " << out_dir << "\n";
  }
  return 0;
}
