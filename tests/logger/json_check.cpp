#include "json_check.hpp"

#include <cctype>
#include <cstdlib>
#include <stdexcept>

namespace relplane::testing {
namespace {

const Json kNullJson;

class Parser {
 public:
  explicit Parser(const std::string& text) : s_(text) {}

  Json Document() {
    Json value = Value();
    Space();
    if (i_ != s_.size()) Fail("trailing characters");
    return value;
  }

 private:
  [[noreturn]] void Fail(const std::string& why) {
    throw std::runtime_error("offset " + std::to_string(i_) + ": " + why);
  }
  void Space() {
    while (i_ < s_.size() && (s_[i_] == ' ' || s_[i_] == '\n' || s_[i_] == '\r' || s_[i_] == '\t'))
      ++i_;
  }
  bool Eat(char c) {
    Space();
    if (i_ < s_.size() && s_[i_] == c) {
      ++i_;
      return true;
    }
    return false;
  }
  void Expect(char c) {
    if (!Eat(c)) Fail(std::string("expected '") + c + "'");
  }
  void Literal(const char* word) {
    for (const char* p = word; *p; ++p, ++i_) {
      if (i_ >= s_.size() || s_[i_] != *p) Fail(std::string("expected ") + word);
    }
  }

  Json Value() {
    Space();
    if (i_ >= s_.size()) Fail("unexpected end");
    Json v;
    const char c = s_[i_];
    if (c == '{') {
      v.kind = Json::kObject;
      ++i_;
      if (Eat('}')) return v;
      do {
        Space();
        const std::string key = String();
        Expect(':');
        if (v.fields.count(key)) Fail("duplicate key " + key);
        v.fields[key] = Value();
      } while (Eat(','));
      Expect('}');
    } else if (c == '[') {
      v.kind = Json::kArray;
      ++i_;
      if (Eat(']')) return v;
      do {
        v.items.push_back(Value());
      } while (Eat(','));
      Expect(']');
    } else if (c == '"') {
      v.kind = Json::kString;
      v.text = String();
    } else if (c == 't') {
      Literal("true");
      v.kind = Json::kBool;
      v.boolean = true;
    } else if (c == 'f') {
      Literal("false");
      v.kind = Json::kBool;
    } else if (c == 'n') {
      Literal("null");
    } else {
      v.kind = Json::kNumber;
      v.number = Number();
    }
    return v;
  }

  std::string String() {
    if (i_ >= s_.size() || s_[i_] != '"') Fail("expected a string");
    ++i_;
    std::string out;
    while (true) {
      if (i_ >= s_.size()) Fail("unterminated string");
      const char c = s_[i_++];
      if (c == '"') return out;
      if (static_cast<unsigned char>(c) < 0x20) Fail("control character in string");
      if (c != '\\') {
        out += c;
        continue;
      }
      if (i_ >= s_.size()) Fail("unterminated escape");
      const char e = s_[i_++];
      switch (e) {
        case '"':
        case '\\':
        case '/':
          out += e;
          break;
        case 'b':
          out += '\b';
          break;
        case 'f':
          out += '\f';
          break;
        case 'n':
          out += '\n';
          break;
        case 'r':
          out += '\r';
          break;
        case 't':
          out += '\t';
          break;
        case 'u':
          for (int k = 0; k < 4; ++k, ++i_) {
            if (i_ >= s_.size() || !std::isxdigit(static_cast<unsigned char>(s_[i_])))
              Fail("bad \\u escape");
          }
          out += '?';
          break;
        default:
          Fail("bad escape");
      }
    }
  }

  double Number() {
    // RFC 8259: -?(0|[1-9][0-9]*)(\.[0-9]+)?([eE][+-]?[0-9]+)?
    const size_t start = i_;
    const auto digits = [&] {
      const size_t from = i_;
      while (i_ < s_.size() && std::isdigit(static_cast<unsigned char>(s_[i_]))) ++i_;
      if (i_ == from) Fail("expected a digit");
    };
    if (s_[i_] == '-') ++i_;
    if (i_ < s_.size() && s_[i_] == '0') {
      ++i_;
    } else {
      digits();
    }
    if (i_ < s_.size() && s_[i_] == '.') {
      ++i_;
      digits();
    }
    if (i_ < s_.size() && (s_[i_] == 'e' || s_[i_] == 'E')) {
      ++i_;
      if (i_ < s_.size() && (s_[i_] == '+' || s_[i_] == '-')) ++i_;
      digits();
    }
    return std::strtod(s_.substr(start, i_ - start).c_str(), nullptr);
  }

  const std::string& s_;
  size_t i_ = 0;
};

}  // namespace

const Json& Json::operator[](const std::string& key) const {
  const auto it = fields.find(key);
  return it == fields.end() ? kNullJson : it->second;
}

const Json& Json::operator[](size_t index) const {
  return index < items.size() ? items[index] : kNullJson;
}

bool ParseJson(const std::string& text, Json* out, std::string* error) {
  try {
    *out = Parser(text).Document();
    return true;
  } catch (const std::runtime_error& e) {
    *error = e.what();
    return false;
  }
}

}  // namespace relplane::testing
