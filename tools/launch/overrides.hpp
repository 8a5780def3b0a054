#pragma once
// `--set key.path=value` overrides: a dotted path into the scenario (list items as `[N]`,
// e.g. `sim.world.walls[0].height`) and a value parsed as YAML (scalar, `[a, b]` or `{k: v}`).

#include <yaml-cpp/yaml.h>

#include <string>
#include <variant>
#include <vector>

namespace relplane::launch {

struct Override {
  // Each step is a mapping key (string) or a list index (size_t).
  std::vector<std::variant<std::string, size_t>> path;
  YAML::Node value;
  std::string text;  // the argument as given, for messages
};

// Parses one `key.path=value` argument. Throws config::ConfigError with a one-line reason
// ("--set 'x': ...") on a malformed path or value, or a first key that is not a top-level key.
Override ParseOverride(const std::string& argument);

// Assigns the override's value in `doc`, creating missing mappings on the way. A path step
// through a scalar, a key on a list or an index past a list's end is a config::ConfigError.
// Whether the key means anything is for the service reading it to say (--check-config).
void ApplyOverride(YAML::Node doc, const Override& override_value);

}  // namespace relplane::launch
