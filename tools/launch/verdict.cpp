#include "verdict.hpp"

#include <cstdio>
#include <regex>
#include <vector>

namespace relplane::launch {
namespace {

// One entry of metrics.json's "expect" array: {"key": K, "limit": L, "value": V, "pass": B}.
struct Check {
  std::string key, limit, value;
  bool pass = false;
};

// The text of the value after `"name":` in `object`, up to the next comma or closing brace.
std::string FieldText(const std::string& object, const std::string& name) {
  const std::regex field("\"" + name + "\"\\s*:\\s*(\"[^\"]*\"|[^,}\\s]+)");
  std::smatch match;
  if (!std::regex_search(object, match, field)) return "";
  std::string text = match[1].str();
  if (text.size() >= 2 && text.front() == '"') text = text.substr(1, text.size() - 2);
  return text;
}

// The objects of the "expect" array, in order; false when there is no such array.
bool ReadChecks(const std::string& json, std::vector<Check>* checks) {
  const std::regex start("\"expect\"\\s*:\\s*\\[");
  std::smatch match;
  if (!std::regex_search(json, match, start)) return false;
  size_t pos = match.position(0) + match.length(0);
  for (;;) {
    const size_t open = json.find_first_of("{]", pos);
    if (open == std::string::npos) return false;
    if (json[open] == ']') return true;
    const size_t close = json.find('}', open);
    if (close == std::string::npos) return false;
    const std::string object = json.substr(open, close - open + 1);
    Check c;
    c.key = FieldText(object, "key");
    c.limit = FieldText(object, "limit");
    c.value = FieldText(object, "value");
    c.pass = FieldText(object, "pass") == "true";
    checks->push_back(c);
    pos = close + 1;
  }
}

// "ate_rmse_max_m 6.882 > 0.5": what failed and by how much.
std::string DescribeFailure(const Check& c) {
  if (c.value == "null") return c.key + " no data";
  const bool is_max = c.key.find("_max") != std::string::npos;
  return c.key + " " + c.value + (is_max ? " > " : " < ") + c.limit;
}

}  // namespace

Verdict VerdictOfMetrics(const std::string& metrics_json) {
  Verdict v;
  if (metrics_json.find("\"relplane-metrics/") == std::string::npos) {
    v.line = "no verdict: no metrics.json from relplane-logger";
    return v;
  }
  std::vector<Check> checks;
  if (!ReadChecks(metrics_json, &checks)) {
    v.line = "no verdict: metrics.json has no expect list";
    return v;
  }
  if (checks.empty()) {
    v.kind = Verdict::Kind::kNoExpectations;
    v.line = "no verdict: the scenario has no expect: section";
    return v;
  }
  std::string failed;
  int failures = 0;
  for (const Check& c : checks) {
    if (c.pass) continue;
    ++failures;
    failed += (failed.empty() ? "" : ", ") + DescribeFailure(c);
  }
  const std::string of = " of " + std::to_string(checks.size()) + " expectations ";
  if (failures == 0) {
    v.kind = Verdict::Kind::kPass;
    v.line = "PASS: " + std::to_string(checks.size()) + of + "held";
  } else {
    v.kind = Verdict::Kind::kFail;
    v.line = "FAIL: " + std::to_string(failures) + of + "failed: " + failed;
  }
  return v;
}

}  // namespace relplane::launch
