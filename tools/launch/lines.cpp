#include "lines.hpp"

namespace relplane::launch {
namespace {
std::string Trimmed(std::string line) {
  if (!line.empty() && line.back() == '\r') line.pop_back();
  return line;
}
}  // namespace

std::vector<std::string> LineSplitter::Feed(const char* data, size_t size) {
  std::vector<std::string> lines;
  for (size_t i = 0; i < size; ++i) {
    if (data[i] == '\n') {
      lines.push_back(Trimmed(std::move(pending_)));
      pending_.clear();
    } else {
      pending_.push_back(data[i]);
      if (pending_.size() >= kMaxLine) {
        lines.push_back(std::move(pending_));
        pending_.clear();
      }
    }
  }
  return lines;
}

std::vector<std::string> LineSplitter::Flush() {
  std::vector<std::string> lines;
  if (!pending_.empty()) lines.push_back(Trimmed(std::move(pending_)));
  pending_.clear();
  return lines;
}

}  // namespace relplane::launch
