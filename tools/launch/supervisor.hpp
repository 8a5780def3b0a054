#pragma once
// Starts the processes of one run, passes their output on line by line with their names, and
// stops them in order when the source finishes, a child dies, or the launcher is interrupted.

#include <optional>
#include <string>
#include <vector>

#include "plan.hpp"

namespace relplane::launch {

struct SupervisorOptions {
  double grace_s = 3.0;           // SIGINT -> SIGTERM -> SIGKILL spacing
  double drain_s = 1.0;           // after the source's end, before stopping the services
  double recorder_drain_s = 0.5;  // before stopping the recorder (it drops its queue on SIGINT)
  double ready_timeout_s = 3.0;   // longest wait for the subscribers before the source starts
  // udpm ports of the run (main bus, cloud bus), to see subscribers bind; empty: unknown.
  std::vector<int> bus_ports;
  std::string source = kSourceService;  // the child whose exit 0 ends the run (started last)
  // Other sources (a replay's second player): started with the source once the subscribers
  // listen, stopped first; their exit 0 is normal and ends nothing.
  std::vector<std::string> side_sources;
  RestartPolicy restart;                // crashed services started again, up to a limit
};

// Exit codes of a run.
constexpr int kExitOk = 0;
constexpr int kExitFailed = 1;         // a child failed, died unexpectedly or would not start
constexpr int kExitExpectationFailed = 3;  // completed, but an `expect:` limit was not met
constexpr int kExitInterrupted = 130;  // SIGINT/SIGTERM/SIGHUP to the launcher

// Runs `recorders` then `services` (already in start order; options.source last)
// and supervises them to the end; the recorders are stopped last. Returns one of the exit
// codes above. No child outlives it.
int Supervise(const std::vector<ChildSpec>& recorders, const std::vector<ChildSpec>& services,
              const SupervisorOptions& options);

// The launcher's own report lines ("[launch] ...", on stderr).
void Say(const std::string& message);

}  // namespace relplane::launch
