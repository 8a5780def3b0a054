#pragma once
// The launcher's view of a scenario file: the top-level keys, the `launch` section, and
// `--set key.path=value` overrides applied to the YAML tree before the services see it.

#include <yaml-cpp/yaml.h>

#include <string>
#include <vector>

namespace relplane::launch {

// `launch.restart`: which services are started again when they crash (a non-zero exit or a
// signal the launcher did not send), and how often at most per service.
struct RestartPolicy {
  int max_restarts = 0;               // per service; 0: a crash fails the run (the default)
  std::vector<std::string> services;  // default: every service of the run but sim and logger
  bool Covers(const std::string& service) const;
};

// The `launch` section (README "Scenario format").
struct LaunchOptions {
  // Services to start, in this order, as relplane-<name> found beside relplane-launch.
  std::vector<std::string> services = {"sim"};
  // Seconds between SIGINT, SIGTERM and SIGKILL when a child does not stop.
  double grace_s = 3.0;
  // Seconds the pipeline may drain after the simulator finished, before it is stopped.
  double drain_s = 1.0;
  // When > 0 or == 0: passed to the simulator as --rate (0: as fast as the bus allows).
  // Negative: the simulator's own rate.
  double rate_hz = -1.0;
  RestartPolicy restart;
  // What lcm-logger records into RUN/bus.lcmlog: kRecordAll, kRecordWithoutClouds (every
  // channel but SENSOR_POINTS, the bulk of the bytes) or kRecordNothing (no lcm-logger).
  std::string record = "all";
};

inline const std::string kRecordAll = "all";
inline const std::string kRecordWithoutClouds = "without_clouds";
inline const std::string kRecordNothing = "nothing";

// The top-level keys a scenario may hold.
const std::vector<std::string>& TopLevelKeys();

// The candidate closest to `key` when it is a likely typo of it (edit distance <= 2), else "".
std::string ClosestKey(const std::string& key, const std::vector<std::string>& candidates);

// A bare name (no '/', no '.') that is no file is one of the project's scenarios,
// `scenarios_dir`/NAME.yaml, or a config::ConfigError listing them; anything else is returned
// as given.
std::string ResolveScenarioFile(const std::string& name, const std::string& scenarios_dir);

// Loads a scenario file and checks its top level: a mapping whose keys are TopLevelKeys() and
// whose `name`/`description` are strings. Throws config::ConfigError (one line naming file,
// line and key) otherwise, or when the file is missing or not YAML.
YAML::Node LoadScenario(const std::string& file);

// Reads and checks the `launch` section of scenario text (`name` stands for the file in
// messages). Throws config::ConfigError on an unknown key, a wrong type or a bad value.
LaunchOptions ReadLaunchOptions(const std::string& yaml_text, const std::string& name);

// The scenario's `name`, else the file's stem; reduced to characters safe in a folder name.
std::string ScenarioName(const YAML::Node& doc, const std::string& file);

// YAML text of a scenario tree, as written to RUN/scenario.yaml.
std::string ToYaml(const YAML::Node& doc);

}  // namespace relplane::launch
