#include "relplane/common/service_runtime.hpp"

#include <relplane/status_t.hpp>
#include <spdlog/spdlog.h>

#include <atomic>
#include <chrono>
#include <csignal>

namespace relplane {
namespace {
std::atomic<bool> g_stop{false};
void OnSignal(int) { g_stop.store(true); }
// Under the launcher's default grace period (3 s) before SIGTERM.
constexpr int64_t kDrainMaxUs = 1000000;
constexpr int kDrainQuietMs = 50;  // a bus this long silent after the stop has been drained
}  // namespace

void InstallStopHandlers() {
  struct sigaction action {};
  action.sa_handler = OnSignal;
  sigemptyset(&action.sa_mask);
  sigaction(SIGINT, &action, nullptr);
  sigaction(SIGTERM, &action, nullptr);
}

bool StopRequested() { return g_stop.load(); }
void RequestStop() { g_stop.store(true); }

int64_t MonotonicMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::steady_clock::now().time_since_epoch())
      .count();
}

int64_t WallMicros() {
  return std::chrono::duration_cast<std::chrono::microseconds>(
             std::chrono::system_clock::now().time_since_epoch())
      .count();
}

void PublishStatus(bus::Bus& bus, ServiceStats& stats) {
  const StatusSnapshot s = stats.Snapshot();
  status_t msg;
  msg.utime = WallMicros();
  msg.service = stats.Service();
  msg.frames_processed = s.frames_processed;
  msg.frames_dropped = s.frames_dropped;
  msg.inputs_rejected = s.inputs_rejected;
  msg.p50_ms = static_cast<float>(s.p50_ms);
  msg.p99_ms = static_cast<float>(s.p99_ms);
  msg.max_ms = static_cast<float>(s.max_ms);
  msg.last_seq = s.last_seq;
  msg.detail = s.detail;
  bus::Publish(bus, "STATUS", msg);
}

int RunService(bus::Bus& bus, ServiceStats& stats, const std::function<bool()>& done,
               const std::function<void()>& on_idle) {
  return RunService(bus, bus, stats, done, on_idle);
}

int RunService(bus::Bus& listen, bus::Bus& report, ServiceStats& stats,
               const std::function<bool()>& done, const std::function<void()>& on_idle) {
  int64_t next_status = MonotonicMicros() + 1000000;
  int result = 0;
  while (!StopRequested() && !(done && done())) {
    // A stop signal interrupts the wait (EINTR) and fails Handle: that is a stop, not an error.
    if (listen.Handle(100) < 0 && !StopRequested()) {
      spdlog::error("the LCM bus failed; stopping");
      result = 1;
      break;
    }
    if (on_idle) on_idle();
    if (MonotonicMicros() >= next_status) {
      PublishStatus(report, stats);
      next_status += 1000000;
    }
  }
  // What arrived before the stop belongs to the run: the launcher stops the services in
  // pipeline order, so the MAP the mapper sent as it stopped may still wait in the logger's
  // socket when the logger is told to stop (a replay's map.json then lagged a frame). Drain,
  // bounded in time so a flooded bus cannot hold the stop past the launcher's grace period.
  if (result == 0) {
    const int64_t give_up = MonotonicMicros() + kDrainMaxUs;
    // LCM's reader thread moves datagrams from the socket to its queue: wait briefly for each.
    while (MonotonicMicros() < give_up && listen.Handle(kDrainQuietMs) > 0) {
    }
  }
  PublishStatus(report, stats);
  spdlog::info("stopping: {} processed, {} dropped, {} rejected", stats.Processed(),
               stats.Dropped(), stats.Rejected());
  return result;
}

}  // namespace relplane
