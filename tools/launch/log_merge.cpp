#include "log_merge.hpp"

#include <lcm/eventlog.h>
#include <sys/stat.h>

#include <cstdio>
#include <memory>

namespace relplane::launch {
namespace {

struct LogCloser {
  void operator()(lcm_eventlog_t* log) const { lcm_eventlog_destroy(log); }
};
using Log = std::unique_ptr<lcm_eventlog_t, LogCloser>;

struct EventFree {
  void operator()(lcm_eventlog_event_t* event) const { lcm_eventlog_free_event(event); }
};
using Event = std::unique_ptr<lcm_eventlog_event_t, EventFree>;

bool NonEmpty(const std::string& path) {
  struct stat info {};
  return stat(path.c_str(), &info) == 0 && info.st_size > 0;
}

// A log to read, or null for a missing or empty file.
Log OpenForReading(const std::string& path, std::string* reason) {
  if (!NonEmpty(path)) return nullptr;
  Log log(lcm_eventlog_create(path.c_str(), "r"));
  if (!log) *reason = path + ": cannot open the log";
  return log;
}

Event Next(const Log& log) {
  return Event(log ? lcm_eventlog_read_next_event(log.get()) : nullptr);
}

}  // namespace

bool MergeLogs(const std::string& first, const std::string& second, const std::string& out,
               std::string* reason) {
  reason->clear();
  const Log a = OpenForReading(first, reason);
  if (!reason->empty()) return false;
  const Log b = OpenForReading(second, reason);
  if (!reason->empty()) return false;
  const Log merged(lcm_eventlog_create(out.c_str(), "w"));
  if (!merged) {
    *reason = out + ": cannot write the log";
    return false;
  }
  Event next_a = Next(a), next_b = Next(b);
  while (next_a || next_b) {
    const bool take_a = next_a && (!next_b || next_a->timestamp <= next_b->timestamp);
    Event& event = take_a ? next_a : next_b;
    if (lcm_eventlog_write_event(merged.get(), event.get()) != 0) {  // numbers it afresh
      *reason = out + ": write failed (disk full?)";
      return false;
    }
    event = Next(take_a ? a : b);
  }
  return true;
}

}  // namespace relplane::launch
