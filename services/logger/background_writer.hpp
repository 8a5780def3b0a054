#pragma once
// Rewrites the run folder from a copy of the recorder on a thread of its own, so the bus loop
// keeps stamping receive times while metrics and pictures are computed: a write stalling the
// loop would show up as latency in the very numbers the logger reports.

#include <future>
#include <string>

#include "relplane/eval/run_recorder.hpp"

namespace relplane::logger {

class BackgroundWriter {
 public:
  ~BackgroundWriter();

  // Starts writing a snapshot of `recorder` and clears its changed flag. Returns false (and
  // copies nothing) while the previous write has not been collected.
  bool Start(eval::RunRecorder& recorder);
  // Collects a finished write, if any: false with the reason when it failed.
  bool Collect(std::string* reason);
  // Waits for the running write, if any, and collects it.
  bool Finish(std::string* reason);
  // How long the last collected write took, milliseconds.
  double LastWriteMs() const { return last_write_ms_; }

 private:
  struct Result {
    bool ok = true;
    std::string reason;
    double elapsed_ms = 0.0;
  };
  std::future<Result> running_;
  double last_write_ms_ = 0.0;
};

}  // namespace relplane::logger
