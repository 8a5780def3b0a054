#pragma once
// Reading a recorded bus.lcmlog in integration tests.

#include <map>
#include <string>

namespace relplane::testing {

// Messages per channel in the LCM log at `path`; a log that cannot be opened is a test failure
// (and no counts).
std::map<std::string, int> ChannelCounts(const std::string& path);

// Messages on `channel` in `counts` (0 where there were none).
inline int CountOf(const std::map<std::string, int>& counts, const std::string& channel) {
  const auto it = counts.find(channel);
  return it == counts.end() ? 0 : it->second;
}

}  // namespace relplane::testing
