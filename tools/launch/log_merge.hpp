#pragma once
// One bus.lcmlog from the two recorders of a run whose clouds travel on a bus of their own:
// the events of both logs in the order of their receive times, numbered afresh, so replay and
// offline tools read one log holding every channel (LCM's event log format, read and written
// with LCM's own eventlog API).

#include <string>

namespace relplane::launch {

// Writes the events of `first` and `second` to `out` ordered by timestamp (on a tie, `first`'s
// event first), event numbers 0, 1, 2, ... A missing or empty input counts as an empty log.
// False with a one-line reason when `out` cannot be written or an input is not an event log.
bool MergeLogs(const std::string& first, const std::string& second, const std::string& out,
               std::string* reason);

}  // namespace relplane::launch
