#include "background_writer.hpp"

#include <chrono>
#include <memory>

namespace relplane::logger {

BackgroundWriter::~BackgroundWriter() {
  std::string ignored;
  Finish(&ignored);
}

bool BackgroundWriter::Start(eval::RunRecorder& recorder) {
  if (running_.valid()) return false;
  auto snapshot = std::make_shared<eval::RunRecorder>(recorder);
  recorder.ClearChanged();
  running_ = std::async(std::launch::async, [snapshot] {
    const auto start = std::chrono::steady_clock::now();
    Result r;
    r.ok = snapshot->Write(&r.reason);
    r.elapsed_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    return r;
  });
  return true;
}

bool BackgroundWriter::Collect(std::string* reason) {
  if (!running_.valid() ||
      running_.wait_for(std::chrono::seconds(0)) != std::future_status::ready) {
    return true;
  }
  return Finish(reason);
}

bool BackgroundWriter::Finish(std::string* reason) {
  if (!running_.valid()) return true;
  const Result r = running_.get();
  last_write_ms_ = r.elapsed_ms;
  if (!r.ok) *reason = r.reason;
  return r.ok;
}

}  // namespace relplane::logger
