#pragma once
// The scenario's `expect:` section: limits on metrics, reported as PASS/FAIL (never enforced by
// the logger). Keys ending in _max / _max_<unit> are upper limits, _min ones lower limits.

#include <string>
#include <vector>

#include "relplane/eval/options.hpp"
#include "relplane/eval/run_metrics.hpp"

namespace relplane::eval {

struct ExpectationKey {
  const char* key;
  const char* meaning;
  bool is_max;
};

// Every key `expect:` accepts, in report order.
const std::vector<ExpectationKey>& ExpectationKeys();

// The value of the metric behind `key` (NaN when unknown or without data).
double ExpectationValue(const std::string& key, const RunMetrics& metrics);

std::vector<ExpectationResult> CheckExpectations(const std::vector<Expectation>& expect,
                                                 const RunMetrics& metrics);

}  // namespace relplane::eval
