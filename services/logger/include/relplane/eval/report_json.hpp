#pragma once
// map.json and metrics.json (schemas in the README's logger section).

#include <cstdint>
#include <map>
#include <string>

#include "relplane/eval/run_metrics.hpp"
#include "relplane/eval/types.hpp"

namespace relplane::eval {

// Picture labels of the groups, "X1", "X2", ... in increasing group id (the paper's Fig. 2).
std::map<int64_t, std::string> GroupLabels(const MapSnapshot& map);

// The mapper's last map: planes (id, normal, d, centroid, vertices, observations, rms, groups
// they belong to) and groups (id, label, basis, members).
std::string MapToJson(const MapSnapshot& map);

// `source` names the writer ("relplane-logger" or "relplane-eval").
std::string MetricsToJson(const RunMetrics& metrics, const std::string& source);

}  // namespace relplane::eval
