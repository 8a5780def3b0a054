#pragma once
// TUM trajectory text: one line per pose, `t tx ty tz qx qy qz qw` with t in seconds, as the
// usual trajectory tools (evo, the TUM RGB-D scripts) read it.

#include <string>
#include <vector>

#include "relplane/eval/types.hpp"

namespace relplane::eval {

// Formats the poses in the given order.
std::string FormatTum(const std::vector<PoseSample>& poses);

// Parses TUM text; '#' lines and blank lines are skipped. utime comes from t, seq is the row
// index. Returns false with a one-line reason ("line N: ...") on a malformed line.
bool ParseTum(const std::string& text, std::vector<PoseSample>* poses, std::string* reason);

}  // namespace relplane::eval
