#include "verdict.hpp"

#include <cstdio>
#include <string>
#include <vector>

namespace relplane::launch {
namespace {

// One entry of metrics.json's "expect" array: {"key": K, "limit": L, "value": V, "pass": B}.
struct Check {
  std::string key, limit, value;
  bool pass = false;
};

// White space between a name, its colon and its value.
constexpr const char* kSpace = " \t\n\v\f\r";

// The position just past `"name"`, white space, a colon and white space, for the first `"name"`
// in `text` at or after `from` that such a colon follows; npos when there is none.
// Hand-written rather than std::regex, which costs about 5 s of -O3 to compile.
size_t ValueAfter(const std::string& text, const std::string& name, size_t from = 0) {
  const std::string quoted = "\"" + name + "\"";
  for (size_t at = text.find(quoted, from); at != std::string::npos;
       at = text.find(quoted, at + 1)) {
    const size_t colon = text.find_first_not_of(kSpace, at + quoted.size());
    if (colon == std::string::npos || text[colon] != ':') continue;
    const size_t value = text.find_first_not_of(kSpace, colon + 1);
    return value == std::string::npos ? text.size() : value;
  }
  return std::string::npos;
}

// The text of the value after `"name":` in `object`: a string without its quotes, or the bare
// word up to the next comma, closing brace or white space.
std::string FieldText(const std::string& object, const std::string& name) {
  for (size_t pos = ValueAfter(object, name); pos != std::string::npos;
       pos = ValueAfter(object, name, pos)) {
    if (pos < object.size() && object[pos] == '"') {
      const size_t close = object.find('"', pos + 1);
      if (close != std::string::npos) return object.substr(pos + 1, close - pos - 1);
    }
    const size_t end = object.find_first_of(std::string(",}") + kSpace, pos);
    std::string text = object.substr(pos, end == std::string::npos ? end : end - pos);
    if (text.empty()) continue;  // no value here: look for a later "name"
    if (text.size() >= 2 && text.front() == '"') text = text.substr(1, text.size() - 2);
    return text;
  }
  return "";
}

// The objects of the "expect" array, in order; false when there is no such array.
bool ReadChecks(const std::string& json, std::vector<Check>* checks) {
  size_t pos = ValueAfter(json, "expect");
  while (pos != std::string::npos && (pos >= json.size() || json[pos] != '[')) {
    pos = ValueAfter(json, "expect", pos);
  }
  if (pos == std::string::npos) return false;
  ++pos;
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
