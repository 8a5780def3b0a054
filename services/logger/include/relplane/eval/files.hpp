#pragma once
// Whole-file replacement that a reader (or a crash) never sees half written.

#include <string>

namespace relplane::eval {

// Writes `content` to `path` through a temporary file in the same folder and rename(2), so the
// path holds either the old or the new complete file. Returns false with a one-line reason.
bool WriteFileAtomic(const std::string& path, const std::string& content, std::string* reason);

// Reads a whole file; false when it cannot be opened.
bool ReadFile(const std::string& path, std::string* content);

}  // namespace relplane::eval
