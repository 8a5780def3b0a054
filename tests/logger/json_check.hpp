#pragma once
// A minimal JSON parser for tests: enough to prove map.json and metrics.json are valid JSON
// (RFC 8259 grammar) and to read values back.

#include <map>
#include <memory>
#include <string>
#include <vector>

namespace relplane::testing {

struct Json {
  enum Kind { kNull, kBool, kNumber, kString, kArray, kObject } kind = kNull;
  bool boolean = false;
  double number = 0.0;
  std::string text;
  std::vector<Json> items;
  std::map<std::string, Json> fields;

  // Member or element access; a missing one reads as null.
  const Json& operator[](const std::string& key) const;
  const Json& operator[](size_t index) const;
  bool IsNull() const { return kind == kNull; }
};

// Parses a whole document; false with "offset N: reason" when it is not valid JSON.
bool ParseJson(const std::string& text, Json* out, std::string* error);

}  // namespace relplane::testing
