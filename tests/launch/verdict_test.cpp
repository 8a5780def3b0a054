#include "verdict.hpp"

#include <gtest/gtest.h>

namespace relplane::launch {
namespace {

// The metrics.json relplane-logger writes, cut to what the verdict reads.
std::string Metrics(const std::string& expect_entries) {
  return "{\n  \"schema\": \"relplane-metrics/1\",\n  \"map\": {\"walls\": [{\"key\": \"x\"}]},\n"
         "  \"expect\": [" +
         expect_entries + "],\n  \"expect_pass\": null\n}\n";
}

TEST(VerdictTest, PassWhenEveryExpectationHeld) {
  const Verdict v = VerdictOfMetrics(Metrics(
      "\n    {\"key\": \"ate_rmse_max_m\", \"limit\": 0.05, \"value\": 0.01, \"pass\": true},"
      "\n    {\"key\": \"lost_max\", \"limit\": 0, \"value\": 0, \"pass\": true}\n  "));
  EXPECT_EQ(v.kind, Verdict::Kind::kPass);
  EXPECT_EQ(v.line, "PASS: 2 of 2 expectations held");
}

TEST(VerdictTest, FailNamesEachFailedExpectationWithItsValueAndLimit) {
  const Verdict v = VerdictOfMetrics(Metrics(
      "\n    {\"key\": \"ate_rmse_max_m\", \"limit\": 0.5, \"value\": 6.882, \"pass\": false},"
      "\n    {\"key\": \"walls_mapped_min\", \"limit\": 6, \"value\": 3, \"pass\": false},"
      "\n    {\"key\": \"normal_error_max_deg\", \"limit\": 1, \"value\": null, \"pass\": false},"
      "\n    {\"key\": \"lost_max\", \"limit\": 0, \"value\": 0, \"pass\": true}\n  "));
  EXPECT_EQ(v.kind, Verdict::Kind::kFail);
  EXPECT_EQ(v.line,
            "FAIL: 3 of 4 expectations failed: ate_rmse_max_m 6.882 > 0.5, walls_mapped_min 3 < "
            "6, normal_error_max_deg no data");
}

TEST(VerdictTest, AScenarioWithoutExpectationsHasNoVerdict) {
  EXPECT_EQ(VerdictOfMetrics(Metrics("")).kind, Verdict::Kind::kNoExpectations);
}

TEST(VerdictTest, MissingOrForeignMetricsAreUnreadable) {
  EXPECT_EQ(VerdictOfMetrics("").kind, Verdict::Kind::kUnreadable);
  EXPECT_EQ(VerdictOfMetrics("{\"expect\": []}").kind, Verdict::Kind::kUnreadable);
  EXPECT_EQ(VerdictOfMetrics("{\"schema\": \"relplane-metrics/1\"}").kind,
            Verdict::Kind::kUnreadable);
  EXPECT_EQ(VerdictOfMetrics("{\"schema\": \"relplane-metrics/1\", \"expect\": [{\"key\": ").kind,
            Verdict::Kind::kUnreadable);
}

}  // namespace
}  // namespace relplane::launch
