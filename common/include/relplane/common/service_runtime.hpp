#pragma once
// The loop every service runs: deliver bus messages, publish STATUS once a second, stop
// cleanly on SIGINT/SIGTERM.

#include <functional>
#include <string>

#include "relplane/common/bus.hpp"
#include "relplane/common/service_stats.hpp"

namespace relplane {

// Installs SIGINT/SIGTERM handlers that only set a flag; StopRequested() reads it.
void InstallStopHandlers();
bool StopRequested();
void RequestStop();

// Monotonic host clock in microseconds: for timing and rate control in services, never in
// algorithm code.
int64_t MonotonicMicros();
// Wall clock in microseconds since the epoch, for STATUS.
int64_t WallMicros();

// Publishes one STATUS message from `stats`.
void PublishStatus(bus::Bus& bus, ServiceStats& stats);

// Handles the bus until a stop is requested or `done()` says so; publishes STATUS once a
// second and a last time on the way out. `on_idle` runs after each wait (e.g. to flush work).
// Returns 0, or 1 after a transport error.
int RunService(bus::Bus& bus, ServiceStats& stats, const std::function<bool()>& done = {},
               const std::function<void()>& on_idle = {});
// The same for a service that listens on one bus and reports STATUS on another (the segmenter
// reads clouds on the cloud bus and only publishes on the main one, so it never reads the main
// bus's traffic).
int RunService(bus::Bus& listen, bus::Bus& report, ServiceStats& stats,
               const std::function<bool()>& done = {}, const std::function<void()>& on_idle = {});

}  // namespace relplane
