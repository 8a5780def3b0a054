#pragma once
// Splits a child's output stream into whole lines so each can carry the child's name.

#include <string>
#include <vector>

namespace relplane::launch {

class LineSplitter {
 public:
  // Appends bytes; returns the lines they completed, without their '\n' (and a trailing '\r').
  std::vector<std::string> Feed(const char* data, size_t size);
  // The unterminated rest, at end of stream (nothing when empty).
  std::vector<std::string> Flush();

  // A line longer than this is cut and passed on, so a child never grows the buffer unbounded.
  static constexpr size_t kMaxLine = 64 * 1024;

 private:
  std::string pending_;
};

}  // namespace relplane::launch
