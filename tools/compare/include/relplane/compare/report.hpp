#pragma once
// What each method did over one input set, and the table that compares them.

#include <string>
#include <vector>

#include "relplane/plane_truth/accuracy.hpp"

namespace relplane::compare {

struct MethodStats {
  std::string name;
  std::vector<double> seconds;  // per frame
  int planes = 0;               // reported, summed over frames
  plane_truth::AccuracyTally tally;
};

// A Markdown table, one row per method: frames, median time per frame, planes per frame,
// precision, recall, median angle and offset errors, and the median time over the first
// method's (relplane as it runs in the pipeline).
std::string Table(const std::vector<MethodStats>& stats);

}  // namespace relplane::compare
