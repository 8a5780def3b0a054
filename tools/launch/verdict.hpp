#pragma once
// The run's verdict: whether every expectation of the scenario's `expect:` held, read from the
// metrics.json relplane-logger wrote into the run folder.

#include <string>

namespace relplane::launch {

struct Verdict {
  enum class Kind {
    kPass,            // every expectation held
    kFail,            // at least one did not, or it could not be computed
    kNoExpectations,  // the scenario expects nothing
    kUnreadable,      // no metrics.json, or not one the logger wrote
  };
  Kind kind = Kind::kUnreadable;
  std::string line;  // one line for the user: "PASS: ...", "FAIL: ...", ...
};

// The verdict in the text of a metrics.json (schema relplane-metrics/1).
Verdict VerdictOfMetrics(const std::string& metrics_json);

}  // namespace relplane::launch
