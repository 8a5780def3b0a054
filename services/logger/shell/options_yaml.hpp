#pragma once
// Scenario YAML -> evaluation options: section `logger` and the top-level `expect:`.

#include <string>
#include <vector>

#include "relplane/eval/options.hpp"

namespace relplane::eval {

struct EvalConfig {
  EvalOptions options;
  std::vector<Expectation> expect;
};

// Reads `logger` and `expect` of `file` (both optional) and checks that every key in them is
// known. Throws config::ConfigError with a one-line "FILE:LINE: key ...: reason".
EvalConfig LoadEvalConfig(const std::string& file);

// The same from YAML text (`name` stands in for the file name), for tests.
EvalConfig ParseEvalConfig(const std::string& yaml, const std::string& name);

}  // namespace relplane::eval
