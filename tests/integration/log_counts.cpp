#include "log_counts.hpp"

#include <gtest/gtest.h>
#include <lcm/eventlog.h>

namespace relplane::testing {

std::map<std::string, int> ChannelCounts(const std::string& path) {
  std::map<std::string, int> counts;
  lcm_eventlog_t* log = lcm_eventlog_create(path.c_str(), "r");
  if (!log) {
    ADD_FAILURE() << "cannot open " << path;
    return counts;
  }
  while (lcm_eventlog_event_t* event = lcm_eventlog_read_next_event(log)) {
    ++counts[event->channel];
    lcm_eventlog_free_event(event);
  }
  lcm_eventlog_destroy(log);
  return counts;
}

}  // namespace relplane::testing
