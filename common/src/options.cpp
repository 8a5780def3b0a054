#include "relplane/common/options.hpp"

#include <algorithm>
#include <fstream>
#include <sstream>

namespace relplane::config {

namespace detail {
std::string TypeName(const std::string*) { return "a string"; }
std::string TypeName(const bool*) { return "true or false"; }
std::string TypeName(const double*) { return "a number"; }
std::string TypeName(const float*) { return "a number"; }
std::string TypeName(const int*) { return "an integer"; }
std::string TypeName(const long*) { return "an integer"; }
std::string TypeName(const long long*) { return "an integer"; }
std::string TypeName(const unsigned*) { return "a non-negative integer"; }
std::string TypeName(const std::vector<double>*) { return "a list of numbers"; }
std::string TypeName(const std::vector<std::string>*) { return "a list of strings"; }
}  // namespace detail

size_t EditDistance(const std::string& a, const std::string& b) {
  std::vector<size_t> row(b.size() + 1);
  for (size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (size_t i = 1; i <= a.size(); ++i) {
    size_t diagonal = row[0];
    row[0] = i;
    for (size_t j = 1; j <= b.size(); ++j) {
      const size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1] ? 1u : 0u)});
      diagonal = above;
    }
  }
  return row[b.size()];
}

namespace {

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

}  // namespace

Reader::Reader(std::shared_ptr<State> state, YAML::Node node, std::string path)
    : state_(std::move(state)), node_(std::move(node)), path_(std::move(path)) {}

Reader Reader::FromString(const std::string& yaml, const std::string& name,
                          const std::string& section) {
  auto state = std::make_shared<State>();
  state->file = name;
  YAML::Node doc;
  try {
    doc = YAML::Load(yaml);
  } catch (const YAML::ParserException& e) {
    throw ConfigError(name + ":" + std::to_string(e.mark.line + 1) + ": invalid YAML: " + e.msg);
  }
  // yaml-cpp's Node::operator= writes through to the node it refers to; reset() rebinds.
  if (doc.IsNull()) doc.reset(YAML::Node(YAML::NodeType::Map));
  if (!doc.IsMap()) throw ConfigError(name + ":1: expected a mapping of keys at the top level");
  state->root.reset(doc);
  if (section.empty()) return Reader(state, doc, "");
  Reader top(state, doc, "");
  Reader sub = top.Child(section);
  state->root.reset(sub.node_);
  state->root_path = section;
  return sub;
}

Reader Reader::Load(const std::string& file, const std::string& section) {
  std::ifstream in(file);
  if (!in) throw ConfigError(file + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return FromString(text.str(), file, section);
}

bool Reader::Has(const std::string& key) const {
  return node_.IsMap() && node_[key] && !node_[key].IsNull();
}

std::string Reader::KeyPath(const std::string& key) const { return Join(path_, key); }

int Reader::LineOf(const std::string& key) const {
  if (node_.IsMap()) {
    for (const auto& kv : node_) {
      if (kv.first.Scalar() == key) return kv.first.Mark().line + 1;
    }
  }
  return node_.Mark().line >= 0 ? node_.Mark().line + 1 : 1;
}

YAML::Node Reader::Lookup(const std::string& key) {
  state_->asked[path_].insert(key);
  // An invalid node, not YAML::Node(): a default-constructed node counts as defined.
  if (!Has(key)) return YAML::Node(YAML::NodeType::Undefined);
  state_->read.insert(KeyPath(key));
  return node_[key];
}

void Reader::Fail(const std::string& key, const std::string& reason) const {
  throw ConfigError(state_->file + ":" + std::to_string(LineOf(key)) + ": key '" + KeyPath(key) +
                    "': " + reason);
}

Reader Reader::Child(const std::string& key) {
  YAML::Node child = Lookup(key);
  if (!child) return Reader(state_, YAML::Node(YAML::NodeType::Map), KeyPath(key));
  if (!child.IsMap()) Fail(key, "expected a mapping of keys");
  return Reader(state_, child, KeyPath(key));
}

std::vector<Reader> Reader::Children(const std::string& key) {
  std::vector<Reader> out;
  YAML::Node child = Lookup(key);
  if (!child) return out;
  if (!child.IsSequence()) Fail(key, "expected a list");
  for (size_t i = 0; i < child.size(); ++i) {
    const std::string path = KeyPath(key) + "[" + std::to_string(i) + "]";
    if (!child[i].IsMap()) {
      throw ConfigError(state_->file + ":" + std::to_string(child[i].Mark().line + 1) + ": key '" +
                        path + "': expected a mapping of keys");
    }
    out.emplace_back(Reader(state_, child[i], path));
  }
  return out;
}

void Reader::CheckUnread(const YAML::Node& node, const std::string& path) const {
  if (node.IsSequence()) {
    for (size_t i = 0; i < node.size(); ++i) {
      if (node[i].IsMap()) CheckUnread(node[i], path + "[" + std::to_string(i) + "]");
    }
    return;
  }
  if (!node.IsMap()) return;
  for (const auto& kv : node) {
    const std::string key = kv.first.Scalar();
    const std::string full = Join(path, key);
    if (state_->read.count(full) == 0) {
      std::string message = state_->file + ":" + std::to_string(kv.first.Mark().line + 1) +
                            ": unknown key '" + full + "'";
      const auto asked = state_->asked.find(path);
      if (asked != state_->asked.end()) {
        std::string best;
        size_t best_distance = 3;  // suggest only close matches, and not for one-letter keys
        for (const auto& candidate : asked->second) {
          const size_t distance = EditDistance(key, candidate);
          if (distance < best_distance && 2 * distance < std::max(key.size(), candidate.size())) {
            best_distance = distance;
            best = candidate;
          }
        }
        if (!best.empty()) message += " (did you mean '" + best + "'?)";
      }
      throw ConfigError(message);
    }
    // Only mappings that were read as mappings are walked; lists of scalars are values.
    if (kv.second.IsMap() || kv.second.IsSequence()) CheckUnread(kv.second, full);
  }
}

void Reader::Finish() const { CheckUnread(state_->root, state_->root_path); }

}  // namespace relplane::config
