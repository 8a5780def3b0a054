#pragma once
// The one options loader: fills options structs from a scenario YAML file, key by key.
// A key nobody reads is an error naming file, line and key, so a typo in a scenario never
// silently falls back to a default (STYLE.md "Configuration").

#include <yaml-cpp/yaml.h>

#include <map>
#include <memory>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

namespace relplane::config {

// Levenshtein distance, to suggest the key a typo was meant to be.
size_t EditDistance(const std::string& a, const std::string& b);

// Every loader failure. what() is one line: "FILE:LINE: key 'a.b': reason".
class ConfigError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

namespace detail {
std::string TypeName(const std::string*);
std::string TypeName(const bool*);
std::string TypeName(const double*);
std::string TypeName(const float*);
std::string TypeName(const int*);
std::string TypeName(const long*);
std::string TypeName(const long long*);
std::string TypeName(const unsigned*);
std::string TypeName(const std::vector<double>*);
std::string TypeName(const std::vector<std::string>*);
}  // namespace detail

// A view of one YAML mapping. Readers made from one file share the record of which keys were
// read, so Finish() on the root can name every key that nobody asked for.
class Reader {
 public:
  // Loads FILE and returns the reader of its top-level `section` (the whole document when
  // `section` is empty). A missing section reads as an empty mapping: all defaults.
  static Reader Load(const std::string& file, const std::string& section = "");
  // The same from YAML text; `name` stands in for the file name in messages.
  static Reader FromString(const std::string& yaml, const std::string& name,
                           const std::string& section = "");

  bool Has(const std::string& key) const;
  // Reads `key` into *value when present; leaves the default otherwise.
  template <class T>
  void Read(const std::string& key, T* value);
  // As Read, but a missing key is an error.
  template <class T>
  void ReadRequired(const std::string& key, T* value);
  // The mapping under `key` (an empty mapping when absent).
  Reader Child(const std::string& key);
  // The mappings of the sequence under `key` (none when absent).
  std::vector<Reader> Children(const std::string& key);

  // Throws ConfigError naming this file, the key's line and its full path.
  [[noreturn]] void Fail(const std::string& key, const std::string& reason) const;
  // Throws ConfigError for the first key of the whole document that nobody read.
  void Finish() const;

  const std::string& File() const { return state_->file; }
  // The dotted path of this mapping inside the document ("" at the top).
  const std::string& Path() const { return path_; }

 private:
  struct State {
    std::string file;
    std::set<std::string> read;                         // full paths of keys read
    std::map<std::string, std::set<std::string>> asked;  // mapping path -> keys asked for
    YAML::Node root;
    std::string root_path;
  };

  Reader(std::shared_ptr<State> state, YAML::Node node, std::string path);
  std::string KeyPath(const std::string& key) const;
  int LineOf(const std::string& key) const;
  YAML::Node Lookup(const std::string& key);
  void CheckUnread(const YAML::Node& node, const std::string& path) const;

  std::shared_ptr<State> state_;
  YAML::Node node_;
  std::string path_;
};

template <class T>
void Reader::Read(const std::string& key, T* value) {
  YAML::Node child = Lookup(key);
  if (!child) return;
  try {
    *value = child.as<T>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected " + detail::TypeName(static_cast<const T*>(nullptr)));
  }
}

template <class T>
void Reader::ReadRequired(const std::string& key, T* value) {
  if (!Has(key)) Fail(key, "missing required key");
  Read(key, value);
}

}  // namespace relplane::config
