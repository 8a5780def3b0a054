#include "scenario.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "relplane/common/options.hpp"

namespace relplane::launch {
namespace {

std::string ReadText(const std::string& file) {
  std::ifstream in(file);
  if (!in) throw config::ConfigError(file + ": cannot open the file");
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

std::string Stem(const std::string& file) {
  std::string base = file.substr(file.find_last_of('/') + 1);
  const size_t dot = base.find_last_of('.');
  return dot == std::string::npos || dot == 0 ? base : base.substr(0, dot);
}

// The project's scenario names, sorted, joined by ", ".
std::string KnownScenarios(const std::string& dir) {
  std::vector<std::string> names;
  std::error_code error;
  for (const auto& entry : std::filesystem::directory_iterator(dir, error)) {
    if (entry.path().extension() == ".yaml") names.push_back(entry.path().stem().string());
  }
  std::sort(names.begin(), names.end());
  std::string known;
  for (const std::string& n : names) known += (known.empty() ? "" : ", ") + n;
  return known;
}

// `launch.restart`; `services` are the run's services, to check the names against.
RestartPolicy ReadRestartPolicy(config::Reader reader, const std::vector<std::string>& services) {
  RestartPolicy policy;
  reader.Read("max_restarts", &policy.max_restarts);
  if (policy.max_restarts < 0) reader.Fail("max_restarts", "must be >= 0");
  if (!reader.Has("services")) {
    for (const std::string& service : services) {
      if (service != "sim" && service != "logger") policy.services.push_back(service);
    }
    return policy;
  }
  reader.Read("services", &policy.services);
  for (const std::string& service : policy.services) {
    if (service == "sim") {
      reader.Fail("services", "'sim' cannot be restarted: its end ends the run");
    }
    if (service == "logger") {
      // A new logger starts with nothing and would replace the run's files with what it sees
      // from then on; bus.lcmlog has everything, for relplane-eval.
      reader.Fail("services",
                  "'logger' cannot be restarted: a new one would overwrite the run's files with "
                  "less; score the run with relplane-eval RUN/bus.lcmlog");
    }
    if (std::find(services.begin(), services.end(), service) == services.end()) {
      const std::string closest = ClosestKey(service, services);
      reader.Fail("services", "'" + service + "' is not in launch.services" +
                                  (closest.empty() ? "" : " (did you mean '" + closest + "'?)"));
    }
  }
  return policy;
}

}  // namespace

bool RestartPolicy::Covers(const std::string& service) const {
  return max_restarts > 0 && std::find(services.begin(), services.end(), service) != services.end();
}

const std::vector<std::string>& TopLevelKeys() {
  static const std::vector<std::string> keys = {"name", "description", "launch", "expect",
                                                "sim",  "segmenter",   "mapper", "logger"};
  return keys;
}

std::string ClosestKey(const std::string& key, const std::vector<std::string>& candidates) {
  std::string best;
  size_t best_distance = 3;  // only close matches are suggestions
  for (const std::string& candidate : candidates) {
    const size_t distance = config::EditDistance(key, candidate);
    if (distance < best_distance) {
      best_distance = distance;
      best = candidate;
    }
  }
  return best;
}

std::string ResolveScenarioFile(const std::string& name, const std::string& scenarios_dir) {
  const bool bare = name.find('/') == std::string::npos && name.find('.') == std::string::npos;
  // A path is the caller's to open (and to report missing); only bare names are looked up.
  if (!bare || std::ifstream(name).good()) return name;
  const std::string own = scenarios_dir + "/" + name + ".yaml";
  if (std::ifstream(own).good()) return own;
  throw config::ConfigError(
      name + ": no such scenario file (the project's: " + KnownScenarios(scenarios_dir) + ")");
}

YAML::Node LoadScenario(const std::string& file) {
  const std::string text = ReadText(file);
  // The options loader parses the text and formats every message as FILE:LINE: key '...'.
  config::Reader top = config::Reader::FromString(text, file);
  const YAML::Node doc = YAML::Load(text);
  if (doc.IsNull()) top.Fail("name", "the scenario is empty");
  const std::vector<std::string>& known = TopLevelKeys();
  for (const auto& entry : doc) {
    const std::string key = entry.first.Scalar();
    if (std::find(known.begin(), known.end(), key) != known.end()) continue;
    const std::string closest = ClosestKey(key, known);
    top.Fail(key, "unknown top-level key" +
                      (closest.empty() ? std::string(" (known: name, description, launch, "
                                                     "expect, sim, segmenter, mapper, logger)")
                                       : " (did you mean '" + closest + "'?)"));
  }
  std::string ignored;
  top.Read("name", &ignored);
  top.Read("description", &ignored);
  for (const char* section : {"launch", "expect", "sim", "segmenter", "mapper", "logger"}) {
    if (doc[section] && !doc[section].IsNull() && !doc[section].IsMap()) {
      top.Fail(section, "expected a mapping of keys");
    }
  }
  return doc;
}

LaunchOptions ReadLaunchOptions(const std::string& yaml_text, const std::string& name) {
  LaunchOptions options;
  config::Reader reader = config::Reader::FromString(yaml_text, name, "launch");
  reader.Read("services", &options.services);
  reader.Read("grace_s", &options.grace_s);
  reader.Read("drain_s", &options.drain_s);
  reader.Read("rate_hz", &options.rate_hz);
  reader.Read("record", &options.record);
  options.restart = ReadRestartPolicy(reader.Child("restart"), options.services);
  reader.Finish();
  for (size_t i = 0; i < options.services.size(); ++i) {
    const std::string& service = options.services[i];
    if (service.empty() || service.find_first_of("/ \t") != std::string::npos) {
      reader.Fail("services", "'" + service + "' is not a service name");
    }
    if (std::find(options.services.begin(), options.services.begin() + i, service) !=
        options.services.begin() + i) {
      reader.Fail("services", "'" + service + "' is listed twice");
    }
  }
  if (options.record != kRecordAll && options.record != kRecordWithoutClouds &&
      options.record != kRecordNothing) {
    reader.Fail("record", "'" + options.record + "' is not one of " + kRecordAll + ", " +
                              kRecordWithoutClouds + ", " + kRecordNothing);
  }
  if (!(options.grace_s > 0.0)) reader.Fail("grace_s", "must be > 0");
  if (!(options.drain_s >= 0.0)) reader.Fail("drain_s", "must be >= 0");
  if (reader.Has("rate_hz") && !(options.rate_hz >= 0.0)) {
    reader.Fail("rate_hz", "must be >= 0 (0: as fast as the bus allows)");
  }
  return options;
}

std::string ScenarioName(const YAML::Node& doc, const std::string& file) {
  std::string name = Stem(file);
  if (doc.IsMap() && doc["name"] && doc["name"].IsScalar() && !doc["name"].Scalar().empty()) {
    name = doc["name"].Scalar();
  }
  for (char& c : name) {
    const bool safe =
        std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == '_' || c == '.';
    if (!safe) c = '_';
  }
  return name.empty() || name[0] == '.' ? "scenario" + name : name;
}

std::string ToYaml(const YAML::Node& doc) {
  YAML::Emitter out;
  out << doc;
  return std::string(out.c_str()) + "\n";
}

}  // namespace relplane::launch
