#include "scenario.hpp"

#include <gtest/gtest.h>
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "relplane/common/options.hpp"

namespace relplane::launch {
namespace {

// Writes `text` to a temporary scenario file and returns its path.
std::string WriteScenario(const std::string& text) {
  char path[] = "/tmp/relplane-launch-test-XXXXXX";
  const int fd = mkstemp(path);
  EXPECT_GE(fd, 0);
  std::ofstream(path) << text;
  close(fd);
  return path;
}

std::string LoadError(const std::string& text, std::string* file) {
  *file = WriteScenario(text);
  try {
    LoadScenario(*file);
  } catch (const config::ConfigError& e) {
    std::remove(file->c_str());
    return e.what();
  }
  std::remove(file->c_str());
  return "";
}

TEST(LoadScenarioTest, AcceptsEveryKnownTopLevelKey) {
  const std::string file = WriteScenario(
      "name: hall\ndescription: a hall\nlaunch: {services: [sim]}\nexpect: {}\n"
      "sim: {rate_hz: 30}\nsegmenter:\nmapper: {}\nlogger: {}\n");
  const YAML::Node doc = LoadScenario(file);
  EXPECT_EQ(doc["sim"]["rate_hz"].as<int>(), 30);
  std::remove(file.c_str());
}

TEST(LoadScenarioTest, UnknownTopLevelKeyNamesFileLineAndKey) {
  std::string file;
  const std::string error = LoadError("name: x\nsim: {}\n\nsimm: {rate_hz: 3}\n", &file);
  EXPECT_EQ(error, file + ":4: key 'simm': unknown top-level key (did you mean 'sim'?)");
}

TEST(LoadScenarioTest, UnknownKeyFarFromAnyListsTheKnownKeys) {
  std::string file;
  const std::string error = LoadError("wibble: 1\n", &file);
  EXPECT_NE(error.find(":1: key 'wibble': unknown top-level key (known: name"), std::string::npos)
      << error;
}

TEST(LoadScenarioTest, SectionMustBeAMapping) {
  std::string file;
  const std::string error = LoadError("name: x\nmapper: 3\n", &file);
  EXPECT_EQ(error, file + ":2: key 'mapper': expected a mapping of keys");
}

TEST(LoadScenarioTest, NameMustBeAString) {
  std::string file;
  const std::string error = LoadError("name: [a, b]\n", &file);
  EXPECT_EQ(error, file + ":1: key 'name': expected a string");
}

TEST(LoadScenarioTest, MissingFileIsOneLine) {
  try {
    LoadScenario("/nonexistent/scenario.yaml");
    FAIL() << "no error";
  } catch (const config::ConfigError& e) {
    EXPECT_EQ(std::string(e.what()), "/nonexistent/scenario.yaml: cannot open the file");
  }
}

TEST(LoadScenarioTest, InvalidYamlNamesTheLine) {
  std::string file;
  const std::string error = LoadError("name: x\nsim: {a: [1, 2}\n", &file);
  EXPECT_EQ(error.rfind(file + ":2: invalid YAML", 0), 0u) << error;
}

TEST(ReadLaunchOptionsTest, DefaultsWithoutSection) {
  const LaunchOptions options = ReadLaunchOptions("name: x\n", "s.yaml");
  EXPECT_EQ(options.services, std::vector<std::string>{"sim"});
  EXPECT_LT(options.rate_hz, 0.0);
}

TEST(ReadLaunchOptionsTest, ReadsEveryKey) {
  const LaunchOptions options = ReadLaunchOptions(
      "launch:\n  services: [sim, segmenter]\n  grace_s: 1.5\n  drain_s: 0\n  rate_hz: 0\n",
      "s.yaml");
  EXPECT_EQ(options.services, (std::vector<std::string>{"sim", "segmenter"}));
  EXPECT_DOUBLE_EQ(options.grace_s, 1.5);
  EXPECT_DOUBLE_EQ(options.drain_s, 0.0);
  EXPECT_DOUBLE_EQ(options.rate_hz, 0.0);
}

TEST(ReadLaunchOptionsTest, RejectsTyposAndBadValues) {
  const auto error = [](const std::string& text) -> std::string {
    try {
      ReadLaunchOptions(text, "s.yaml");
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error("launch:\n  servises: [sim]\n"),
            "s.yaml:2: unknown key 'launch.servises' (did you mean 'services'?)");
  EXPECT_EQ(error("launch:\n  grace_s: 0\n"), "s.yaml:2: key 'launch.grace_s': must be > 0");
  EXPECT_EQ(error("launch:\n  rate_hz: -1\n"),
            "s.yaml:2: key 'launch.rate_hz': must be >= 0 (0: as fast as the bus allows)");
  EXPECT_EQ(error("launch:\n  services: [sim, sim]\n"),
            "s.yaml:2: key 'launch.services': 'sim' is listed twice");
  EXPECT_EQ(error("launch:\n  services: [../x]\n"),
            "s.yaml:2: key 'launch.services': '../x' is not a service name");
  EXPECT_EQ(error("launch:\n  services: sim\n"),
            "s.yaml:2: key 'launch.services': expected a list of strings");
}

TEST(ReadLaunchOptionsTest, RestartPolicy) {
  const LaunchOptions none = ReadLaunchOptions("launch:\n  services: [sim, mapper]\n", "s.yaml");
  EXPECT_EQ(none.restart.max_restarts, 0);
  EXPECT_FALSE(none.restart.Covers("mapper"));

  const LaunchOptions listed = ReadLaunchOptions(
      "launch:\n  services: [sim, segmenter, mapper]\n"
      "  restart: {max_restarts: 3, services: [mapper]}\n",
      "s.yaml");
  EXPECT_EQ(listed.restart.max_restarts, 3);
  EXPECT_TRUE(listed.restart.Covers("mapper"));
  EXPECT_FALSE(listed.restart.Covers("segmenter"));

  // Without a list: every service but the simulator and the logger.
  const LaunchOptions all = ReadLaunchOptions(
      "launch:\n  services: [sim, segmenter, mapper, logger]\n  restart:\n    max_restarts: 1\n",
      "s.yaml");
  EXPECT_EQ(all.restart.services, (std::vector<std::string>{"segmenter", "mapper"}));
  EXPECT_FALSE(all.restart.Covers("sim"));
  EXPECT_FALSE(all.restart.Covers("logger"));
}

TEST(ReadLaunchOptionsTest, RestartPolicyTyposAreOneLine) {
  const auto error = [](const std::string& text) -> std::string {
    try {
      ReadLaunchOptions("launch:\n  services: [sim, mapper]\n" + text, "s.yaml");
    } catch (const config::ConfigError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(error("  restart: {max_restart: 3}\n"),
            "s.yaml:3: unknown key 'launch.restart.max_restart' (did you mean 'max_restarts'?)");
  EXPECT_EQ(error("  restart: {max_restarts: -1}\n"),
            "s.yaml:3: key 'launch.restart.max_restarts': must be >= 0");
  EXPECT_EQ(error("  restart: {max_restarts: many}\n"),
            "s.yaml:3: key 'launch.restart.max_restarts': expected an integer");
  EXPECT_EQ(error("  restart: {max_restarts: 2, services: [maper]}\n"),
            "s.yaml:3: key 'launch.restart.services': 'maper' is not in launch.services (did "
            "you mean 'mapper'?)");
  EXPECT_EQ(error("  restart: {max_restarts: 2, services: [sim]}\n"),
            "s.yaml:3: key 'launch.restart.services': 'sim' cannot be restarted: its end ends "
            "the run");
  EXPECT_EQ(error("  restart: {max_restarts: 2, services: [logger]}\n").substr(0, 63),
            "s.yaml:3: key 'launch.restart.services': 'logger' cannot be res");
  EXPECT_EQ(error("  restrat: {max_restarts: 2}\n"),
            "s.yaml:3: unknown key 'launch.restrat' (did you mean 'restart'?)");
  EXPECT_NE(error("  restart: 3\n"), "");
  EXPECT_EQ(error("  record: clouds\n"),
            "s.yaml:3: key 'launch.record': 'clouds' is not one of all, without_clouds, nothing");
}

TEST(ScenarioNameTest, NameKeyElseStemMadeSafe) {
  EXPECT_EQ(ScenarioName(YAML::Load("name: hallway loop/2"), "a/b.yaml"), "hallway_loop_2");
  EXPECT_EQ(ScenarioName(YAML::Load("sim: {}"), "scenarios/office.yaml"), "office");
  EXPECT_EQ(ScenarioName(YAML::Load("name: ..."), "x.yaml"), "scenario...");
}

TEST(ResolveScenarioFileTest, AFileAsGivenABareNameFromTheProjectsScenarios) {
  const std::string dir = std::string(RELPLANE_SOURCE_DIR) + "/scenarios";
  EXPECT_EQ(ResolveScenarioFile("office", dir), dir + "/office.yaml");
  const std::string file = WriteScenario("name: x\n");
  EXPECT_EQ(ResolveScenarioFile(file, dir), file);
  std::remove(file.c_str());
  try {
    ResolveScenarioFile("ofice", dir);
    FAIL() << "a name that is no scenario";
  } catch (const config::ConfigError& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind("ofice: no such scenario file (the project's: ", 0), 0u) << message;
    EXPECT_NE(message.find("office, "), std::string::npos) << message;
    EXPECT_NE(message.find("straight_hallway"), std::string::npos) << message;
  }
  // A path or a file name is never looked up among the project's scenarios.
  EXPECT_EQ(ResolveScenarioFile("./office", dir), "./office");
  EXPECT_EQ(ResolveScenarioFile("office.yaml", dir), "office.yaml");
}

TEST(ClosestKeyTest, OnlyCloseMatches) {
  EXPECT_EQ(ClosestKey("mappr", TopLevelKeys()), "mapper");
  EXPECT_EQ(ClosestKey("zzzzzz", TopLevelKeys()), "");
}

}  // namespace
}  // namespace relplane::launch
