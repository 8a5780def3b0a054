#include "relplane/eval/json_writer.hpp"

#include <cmath>
#include <cstdio>

namespace relplane::eval {

std::string JsonEscape(const std::string& text) {
  std::string out;
  out.reserve(text.size());
  for (const char c : text) {
    switch (c) {
      case '"':
        out += "\\\"";
        break;
      case '\\':
        out += "\\\\";
        break;
      case '\n':
        out += "\\n";
        break;
      case '\r':
        out += "\\r";
        break;
      case '\t':
        out += "\\t";
        break;
      default:
        if (static_cast<unsigned char>(c) < 0x20) {
          char buf[8];
          std::snprintf(buf, sizeof(buf), "\\u%04x", c);
          out += buf;
        } else {
          out += c;
        }
    }
  }
  return out;
}

void JsonWriter::NewLine() {
  out_ += '\n';
  out_.append(2 * stack_.size(), ' ');
}

void JsonWriter::BeforeValue() {
  if (after_key_) {
    after_key_ = false;
    return;
  }
  if (stack_.empty()) return;
  Level& level = stack_.back();
  if (!level.first) out_ += level.compact ? ", " : ",";
  if (!level.compact) NewLine();
  level.first = false;
}

void JsonWriter::Open(char bracket, bool compact) {
  BeforeValue();
  out_ += bracket;
  const bool inherit = !stack_.empty() && stack_.back().compact;
  stack_.push_back({compact || inherit, true});
}

void JsonWriter::Close(char bracket) {
  const Level level = stack_.back();
  stack_.pop_back();
  if (!level.compact && !level.first) NewLine();
  out_ += bracket;
  if (stack_.empty()) out_ += '\n';
}

JsonWriter& JsonWriter::BeginObject(bool compact) {
  Open('{', compact);
  return *this;
}
JsonWriter& JsonWriter::EndObject() {
  Close('}');
  return *this;
}
JsonWriter& JsonWriter::BeginArray(bool compact) {
  Open('[', compact);
  return *this;
}
JsonWriter& JsonWriter::EndArray() {
  Close(']');
  return *this;
}

JsonWriter& JsonWriter::Key(const std::string& key) {
  BeforeValue();
  out_ += '"' + JsonEscape(key) + "\": ";
  after_key_ = true;
  return *this;
}

JsonWriter& JsonWriter::Value(double value) {
  if (!std::isfinite(value)) return Null();
  BeforeValue();
  char buf[32];
  std::snprintf(buf, sizeof(buf), "%.9g", value);
  out_ += buf;
  return *this;
}

JsonWriter& JsonWriter::Value(int64_t value) {
  BeforeValue();
  out_ += std::to_string(value);
  return *this;
}

JsonWriter& JsonWriter::Value(bool value) {
  BeforeValue();
  out_ += value ? "true" : "false";
  return *this;
}

JsonWriter& JsonWriter::Value(const std::string& value) {
  BeforeValue();
  out_ += '"' + JsonEscape(value) + '"';
  return *this;
}

JsonWriter& JsonWriter::Null() {
  BeforeValue();
  out_ += "null";
  return *this;
}

JsonWriter& JsonWriter::Vector(const double* values, int n) {
  BeginArray(true);
  for (int i = 0; i < n; ++i) Value(values[i]);
  return EndArray();
}

}  // namespace relplane::eval
