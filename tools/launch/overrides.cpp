#include "overrides.hpp"

#include <algorithm>
#include <cctype>

#include "relplane/common/options.hpp"
#include "scenario.hpp"

namespace relplane::launch {
namespace {

[[noreturn]] void Fail(const std::string& argument, const std::string& reason) {
  throw config::ConfigError("--set '" + argument + "': " + reason);
}

bool IsKeyChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-';
}

std::string Describe(const Override& o, size_t steps) {
  std::string out;
  for (size_t i = 0; i < steps; ++i) {
    if (const auto* key = std::get_if<std::string>(&o.path[i])) {
      out += (out.empty() ? "" : ".") + *key;
    } else {
      out += "[" + std::to_string(std::get<size_t>(o.path[i])) + "]";
    }
  }
  return out;
}

}  // namespace

Override ParseOverride(const std::string& argument) {
  Override result;
  result.text = argument;
  const size_t equals = argument.find('=');
  if (equals == std::string::npos) Fail(argument, "expected key.path=value");
  const std::string path = argument.substr(0, equals);
  const std::string value = argument.substr(equals + 1);

  size_t i = 0;
  while (i < path.size()) {
    if (path[i] == '[') {
      const size_t close = path.find(']', i);
      const std::string digits = path.substr(i + 1, close == std::string::npos ? 0 : close - i - 1);
      if (close == std::string::npos || digits.empty() || result.path.empty() ||
          !std::all_of(digits.begin(), digits.end(), ::isdigit)) {
        Fail(argument, "a list index is written key[N]");
      }
      result.path.emplace_back(static_cast<size_t>(std::stoul(digits)));
      i = close + 1;
      if (i < path.size() && path[i] != '.' && path[i] != '[') Fail(argument, "bad key path");
      if (i < path.size() && path[i] == '.') ++i;
      if (i == path.size() && path.back() == '.') Fail(argument, "empty key in the path");
      continue;
    }
    size_t end = i;
    while (end < path.size() && IsKeyChar(path[end])) ++end;
    if (end == i) Fail(argument, "empty or malformed key in the path");
    result.path.emplace_back(path.substr(i, end - i));
    i = end;
    if (i < path.size() && path[i] == '.') {
      ++i;
      if (i == path.size()) Fail(argument, "empty key in the path");
    } else if (i < path.size() && path[i] != '[') {
      Fail(argument, "unexpected '" + std::string(1, path[i]) + "' in the key path");
    }
  }
  if (result.path.empty()) Fail(argument, "expected key.path=value");

  const std::string& section = std::get<std::string>(result.path.front());
  const std::vector<std::string>& known = TopLevelKeys();
  if (std::find(known.begin(), known.end(), section) == known.end()) {
    const std::string closest = ClosestKey(section, known);
    Fail(argument, "unknown top-level key '" + section + "'" +
                       (closest.empty() ? "" : " (did you mean '" + closest + "'?)"));
  }
  if (value.empty()) Fail(argument, "empty value");
  try {
    result.value = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    Fail(argument, "value is not YAML: " + e.msg);
  }
  return result;
}

void ApplyOverride(YAML::Node doc, const Override& o) {
  YAML::Node current = doc;
  for (size_t i = 0; i < o.path.size(); ++i) {
    const bool last = i + 1 == o.path.size();
    if (const auto* key = std::get_if<std::string>(&o.path[i])) {
      if (!current.IsMap() && !current.IsNull()) {
        Fail(o.text, "'" + Describe(o, i) + "' is not a mapping");
      }
      if (last) {
        current[*key] = o.value;
        return;
      }
      if (!current[*key].IsDefined() || current[*key].IsNull()) {
        current[*key] = YAML::Node(YAML::NodeType::Map);
      }
      YAML::Node next = current[*key];
      current.reset(next);
    } else {
      const size_t index = std::get<size_t>(o.path[i]);
      if (!current.IsSequence()) Fail(o.text, "'" + Describe(o, i) + "' is not a list");
      if (index >= current.size()) {
        Fail(o.text, "'" + Describe(o, i) + "' has " + std::to_string(current.size()) + " items");
      }
      if (last) {
        current[index] = o.value;
        return;
      }
      YAML::Node next = current[index];
      current.reset(next);
    }
  }
}

}  // namespace relplane::launch
