#include "xml_check.hpp"

#include <cctype>
#include <stdexcept>
#include <vector>

namespace relplane::testing {
namespace {

bool NameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.' ||
         c == ':';
}

class Checker {
 public:
  Checker(const std::string& text, std::map<std::string, int>* counts)
      : s_(text), counts_(counts) {}

  void Run() {
    if (s_.compare(0, 5, "<?xml") == 0) {
      const size_t end = s_.find("?>");
      if (end == std::string::npos) Fail("unterminated XML declaration");
      i_ = end + 2;
    }
    int roots = 0;
    while (i_ < s_.size()) {
      if (s_[i_] == '<') {
        if (s_.compare(i_, 4, "<!--") == 0) {
          Comment();
          continue;
        }
        if (stack_.empty() && s_[i_ + 1] != '/') ++roots;
        if (roots > 1) Fail("more than one root element");
        Tag();
      } else {
        if (stack_.empty() && !std::isspace(static_cast<unsigned char>(s_[i_]))) {
          Fail("text outside the root element");
        }
        Text();
      }
    }
    if (!stack_.empty()) Fail("unclosed element <" + stack_.back() + ">");
    if (roots != 1) Fail("no root element");
  }

 private:
  [[noreturn]] void Fail(const std::string& why) {
    throw std::runtime_error("offset " + std::to_string(i_) + ": " + why);
  }
  void Comment() {
    const size_t end = s_.find("-->", i_ + 4);
    if (end == std::string::npos) Fail("unterminated comment");
    i_ = end + 3;
  }
  std::string Name() {
    const size_t start = i_;
    while (i_ < s_.size() && NameChar(s_[i_])) ++i_;
    if (i_ == start) Fail("expected a name");
    return s_.substr(start, i_ - start);
  }
  void Space() {
    while (i_ < s_.size() && std::isspace(static_cast<unsigned char>(s_[i_]))) ++i_;
  }
  void Entity() {
    const size_t end = s_.find(';', i_);
    if (end == std::string::npos) Fail("unterminated entity");
    const std::string name = s_.substr(i_ + 1, end - i_ - 1);
    if (name != "lt" && name != "gt" && name != "amp" && name != "quot" && name != "apos" &&
        (name.empty() || name[0] != '#')) {
      Fail("unknown entity &" + name + ";");
    }
    i_ = end + 1;
  }
  void Text() {
    while (i_ < s_.size() && s_[i_] != '<') {
      if (s_[i_] == '&') {
        Entity();
      } else {
        ++i_;
      }
    }
  }
  void Tag() {
    ++i_;  // '<'
    if (i_ < s_.size() && s_[i_] == '/') {
      ++i_;
      const std::string name = Name();
      Space();
      if (i_ >= s_.size() || s_[i_] != '>') Fail("expected '>'");
      ++i_;
      if (stack_.empty() || stack_.back() != name) Fail("mismatched </" + name + ">");
      stack_.pop_back();
      return;
    }
    const std::string name = Name();
    if (counts_ != nullptr) ++(*counts_)[name];
    std::map<std::string, bool> seen;
    while (true) {
      Space();
      if (i_ >= s_.size()) Fail("unterminated tag");
      if (s_[i_] == '>') {
        ++i_;
        stack_.push_back(name);
        return;
      }
      if (s_.compare(i_, 2, "/>") == 0) {
        i_ += 2;
        return;
      }
      const std::string attribute = Name();
      if (seen[attribute]) Fail("repeated attribute " + attribute);
      seen[attribute] = true;
      Space();
      if (i_ >= s_.size() || s_[i_] != '=') Fail("expected '=' after " + attribute);
      ++i_;
      Space();
      if (i_ >= s_.size() || (s_[i_] != '"' && s_[i_] != '\'')) Fail("unquoted attribute");
      const char quote = s_[i_++];
      while (i_ < s_.size() && s_[i_] != quote) {
        if (s_[i_] == '<') Fail("'<' in attribute value");
        if (s_[i_] == '&') {
          Entity();
        } else {
          ++i_;
        }
      }
      if (i_ >= s_.size()) Fail("unterminated attribute value");
      ++i_;
    }
  }

  const std::string& s_;
  std::map<std::string, int>* counts_;
  size_t i_ = 0;
  std::vector<std::string> stack_;
};

}  // namespace

bool CheckXml(const std::string& text, std::string* error,
              std::map<std::string, int>* element_counts) {
  try {
    Checker(text, element_counts).Run();
    return true;
  } catch (const std::runtime_error& e) {
    *error = e.what();
    return false;
  }
}

}  // namespace relplane::testing
