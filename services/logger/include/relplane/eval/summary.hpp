#pragma once
// The short table printed when a run ends (iterations, rate, ATE, map figures, latency p99,
// expectations).

#include <string>

#include "relplane/eval/run_metrics.hpp"

namespace relplane::eval {

std::string FormatSummary(const RunMetrics& metrics);

}  // namespace relplane::eval
