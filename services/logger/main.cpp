// relplane-logger: subscribes POSE, MAP, SIM_TRUTH, SIM_WORLD, STATUS (and PLANES for stage
// latency) and keeps the run folder current: every file is rewritten atomically at most every
// flush_period_s when something changed, and once more with a summary table at shutdown.
#include <spdlog/spdlog.h>

#include <ctime>
#include <filesystem>
#include <iostream>

#include "background_writer.hpp"
#include "convert.hpp"
#include "options_yaml.hpp"
#include "relplane/common/bus.hpp"
#include "relplane/common/cli.hpp"
#include "relplane/common/options.hpp"
#include "relplane/common/service_runtime.hpp"
#include "relplane/common/service_stats.hpp"
#include "relplane/eval/summary.hpp"

namespace {

// ./run-YYYYmmdd-HHMMSS (UTC) when no --out is given.
std::string DefaultOutDir() {
  const std::time_t now = std::time(nullptr);
  std::tm utc{};
  gmtime_r(&now, &utc);
  char name[64];
  std::strftime(name, sizeof(name), "run-%Y%m%d-%H%M%S", &utc);
  return name;
}

}  // namespace

int main(int argc, char** argv) {
  using namespace relplane;
  cli::Parser parser{"relplane-logger: record a run's trajectories, map, metrics and pictures"};
  cli::CommonFlags flags;
  cli::AddCommonFlags(parser, &flags);
  std::string out_dir;
  bool check_config = false;
  parser.Add("--out", &out_dir, "Run folder to write (created; default ./run-<UTC time>)");
  parser.AddFlag("--check-config", &check_config,
                 "Validate the logger and expect: sections of --config and exit");
  if (const auto code = parser.Parse(argc, argv)) return *code;

  eval::EvalConfig cfg;
  try {
    if (!flags.config.empty()) cfg = eval::LoadEvalConfig(flags.config);
  } catch (const config::ConfigError& e) {
    std::cerr << e.what() << "\n";
    return cli::kExitConfig;
  }
  if (check_config) return 0;
  try {
    cli::SetupLogging("relplane-logger", flags.log_level);
  } catch (const std::exception& e) {
    std::cerr << "relplane-logger: " << e.what() << "\n";
    return cli::kExitConfig;
  }

  if (out_dir.empty()) out_dir = DefaultOutDir();
  std::error_code ec;
  std::filesystem::create_directories(out_dir, ec);
  if (ec) {
    std::cerr << "relplane-logger: cannot create " << out_dir << ": " << ec.message() << "\n";
    return cli::kExitConfig;
  }

  std::unique_ptr<bus::Bus> bus;
  try {
    bus = bus::OpenLcmBus(bus::ResolveUrl(flags.lcm_url));
  } catch (const std::exception& e) {
    std::cerr << "relplane-logger: " << e.what() << "\n";
    return 1;
  }

  InstallStopHandlers();
  ServiceStats stats("relplane-logger", 33.3);
  eval::RunRecorder recorder(out_dir, cfg.options, cfg.expect, "relplane-logger");
  for (const std::string& channel : eval::RecordedChannels()) {
    bus->SubscribeRaw(
        channel,
        [&](const std::string& ch, const uint8_t* data, size_t size) {
          const int64_t start = MonotonicMicros();
          std::string reason;
          const auto result = eval::FeedEncoded(recorder, ch, data, size, start, &reason);
          if (result == eval::FeedResult::kRejected) {
            stats.Rejected(reason);
          } else if (ch != "STATUS") {
            // Frames are the run's data; counting STATUS (our own too) would make the logger's
            // report change every second and the folder be rewritten on an idle bus.
            stats.Processed(1e-3 * static_cast<double>(MonotonicMicros() - start));
          }
        },
        bus::kDefaultQueueCapacity);
  }

  // Periodic rewrites run on a copy in the background; the first and the last are synchronous
  // so the folder is complete from the start and final at the end.
  const auto write_now = [&] {
    std::string reason;
    if (!recorder.Write(&reason)) stats.Rejected("write failed: " + reason);
  };
  write_now();
  logger::BackgroundWriter writer;
  const int64_t period_us = static_cast<int64_t>(cfg.options.flush_period_s * 1e6);
  int64_t next_write = MonotonicMicros() + period_us;
  spdlog::info("recording {} into {}", bus->Url().empty() ? "LCM's default bus" : bus->Url(),
               out_dir);
  const int result = RunService(*bus, stats, {}, [&] {
    std::string reason;
    if (!writer.Collect(&reason)) stats.Rejected("write failed: " + reason);
    if (MonotonicMicros() < next_write || !recorder.Changed()) return;
    // Busy with the previous write: try again on the next round.
    if (!writer.Start(recorder)) return;
    stats.SetDetail("last write " + std::to_string(static_cast<int>(writer.LastWriteMs())) + " ms");
    next_write = MonotonicMicros() + period_us;
  });
  std::string reason;
  if (!writer.Finish(&reason)) stats.Rejected("write failed: " + reason);
  write_now();
  std::cout << eval::FormatSummary(recorder.LastMetrics()) << "  run folder: " << out_dir
            << std::endl;
  return result;
}
