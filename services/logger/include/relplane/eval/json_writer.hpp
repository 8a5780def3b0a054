#pragma once
// A small streaming JSON writer: enough for map.json and metrics.json without a dependency.
// Non-finite numbers are written as null, strings are escaped, output is indented.

#include <cstdint>
#include <string>
#include <vector>

namespace relplane::eval {

class JsonWriter {
 public:
  // `compact` keeps an object or array on one line (e.g. a 3-vector).
  JsonWriter& BeginObject(bool compact = false);
  JsonWriter& EndObject();
  JsonWriter& BeginArray(bool compact = false);
  JsonWriter& EndArray();
  JsonWriter& Key(const std::string& key);
  JsonWriter& Value(double value);
  JsonWriter& Value(int64_t value);
  JsonWriter& Value(int value) { return Value(static_cast<int64_t>(value)); }
  JsonWriter& Value(bool value);
  JsonWriter& Value(const std::string& value);
  JsonWriter& Value(const char* value) { return Value(std::string(value)); }
  JsonWriter& Null();
  // Key(key).Value(value) in one call.
  template <class T>
  JsonWriter& Field(const std::string& key, const T& value) {
    Key(key);
    return Value(value);
  }
  JsonWriter& Vector(const double* values, int n);

  // The document; valid once every object and array is closed.
  const std::string& Str() const { return out_; }

 private:
  struct Level {
    bool compact = false;
    bool first = true;
  };
  void BeforeValue();
  void Open(char bracket, bool compact);
  void Close(char bracket);
  void NewLine();

  std::string out_;
  std::vector<Level> stack_;
  bool after_key_ = false;
};

// Escapes a string for JSON (without the quotes).
std::string JsonEscape(const std::string& text);

}  // namespace relplane::eval
