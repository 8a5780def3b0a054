#include "overrides.hpp"

#include <gtest/gtest.h>

#include "relplane/common/options.hpp"
#include "scenario.hpp"

namespace relplane::launch {
namespace {

std::string ParseError(const std::string& argument) {
  try {
    ParseOverride(argument);
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

std::string ApplyError(YAML::Node doc, const std::string& argument) {
  try {
    ApplyOverride(doc, ParseOverride(argument));
  } catch (const config::ConfigError& e) {
    return e.what();
  }
  return "";
}

YAML::Node Applied(const std::string& yaml, const std::vector<std::string>& arguments) {
  YAML::Node doc = YAML::Load(yaml);
  for (const std::string& argument : arguments) ApplyOverride(doc, ParseOverride(argument));
  return doc;
}

TEST(ParseOverrideTest, SplitsPathAndParsesValueAsYaml) {
  const Override o = ParseOverride("sim.world.walls[2].height=2.5");
  ASSERT_EQ(o.path.size(), 5u);
  EXPECT_EQ(std::get<std::string>(o.path[0]), "sim");
  EXPECT_EQ(std::get<std::string>(o.path[2]), "walls");
  EXPECT_EQ(std::get<size_t>(o.path[3]), 2u);
  EXPECT_EQ(std::get<std::string>(o.path[4]), "height");
  EXPECT_DOUBLE_EQ(o.value.as<double>(), 2.5);

  const Override list = ParseOverride("launch.services=[sim, logger]");
  ASSERT_TRUE(list.value.IsSequence());
  EXPECT_EQ(list.value[1].as<std::string>(), "logger");
  // Only the first '=' splits: the value may hold more.
  EXPECT_EQ(ParseOverride("name=a=b").value.as<std::string>(), "a=b");
}

TEST(ParseOverrideTest, RejectsMalformedArguments) {
  EXPECT_EQ(ParseError("sim.rate_hz"), "--set 'sim.rate_hz': expected key.path=value");
  EXPECT_EQ(ParseError("sim..rate=1"), "--set 'sim..rate=1': empty or malformed key in the path");
  EXPECT_EQ(ParseError("sim.=1"), "--set 'sim.=1': empty key in the path");
  EXPECT_EQ(ParseError("sim.a[x]=1"), "--set 'sim.a[x]=1': a list index is written key[N]");
  EXPECT_EQ(ParseError("[0]=1"), "--set '[0]=1': a list index is written key[N]");
  EXPECT_EQ(ParseError("sim.rate="), "--set 'sim.rate=': empty value");
  EXPECT_EQ(ParseError("sim.a b=1"), "--set 'sim.a b=1': unexpected ' ' in the key path");
  EXPECT_EQ(ParseError("sim.a=[1, 2"),
            "--set 'sim.a=[1, 2': value is not YAML: end of sequence "
            "flow not found");
}

TEST(ParseOverrideTest, FirstKeyMustBeATopLevelKey) {
  EXPECT_EQ(ParseError("simm.rate_hz=3"),
            "--set 'simm.rate_hz=3': unknown top-level key 'simm' (did you mean 'sim'?)");
  EXPECT_EQ(ParseError("foo=3"), "--set 'foo=3': unknown top-level key 'foo'");
}

TEST(ApplyOverrideTest, ReplacesExistingValues) {
  const YAML::Node doc = Applied("sim: {rate_hz: 30, noise: 0}\n", {"sim.rate_hz=100"});
  EXPECT_EQ(doc["sim"]["rate_hz"].as<int>(), 100);
  EXPECT_EQ(doc["sim"]["noise"].as<int>(), 0);
}

TEST(ApplyOverrideTest, CreatesMissingMappingsAndKeys) {
  const YAML::Node doc =
      Applied("name: x\nsegmenter:\n", {"sim.sensor.noise_sigma=0.01", "segmenter.iterations=5"});
  EXPECT_DOUBLE_EQ(doc["sim"]["sensor"]["noise_sigma"].as<double>(), 0.01);
  EXPECT_EQ(doc["segmenter"]["iterations"].as<int>(), 5);
  EXPECT_EQ(doc["name"].as<std::string>(), "x");
}

TEST(ApplyOverrideTest, IndexesIntoLists) {
  const YAML::Node doc = Applied("sim:\n  walls:\n    - {h: 1}\n    - {h: 2}\n",
                                 {"sim.walls[1].h=3", "sim.walls[0]={h: 9}"});
  EXPECT_EQ(doc["sim"]["walls"][0]["h"].as<int>(), 9);
  EXPECT_EQ(doc["sim"]["walls"][1]["h"].as<int>(), 3);
}

TEST(ApplyOverrideTest, LaterOverridesWin) {
  const YAML::Node doc = Applied("sim: {a: 1}\n", {"sim.a=2", "sim.a=3"});
  EXPECT_EQ(doc["sim"]["a"].as<int>(), 3);
}

TEST(ApplyOverrideTest, TheOriginalTreeIsUntouchedThroughAClone) {
  const YAML::Node original = YAML::Load("sim: {a: 1}\n");
  YAML::Node copy = YAML::Clone(original);
  ApplyOverride(copy, ParseOverride("sim.a=2"));
  EXPECT_EQ(original["sim"]["a"].as<int>(), 1);
  EXPECT_EQ(copy["sim"]["a"].as<int>(), 2);
}

TEST(ApplyOverrideTest, RejectsStepsThroughNonMappings) {
  EXPECT_EQ(ApplyError(YAML::Load("sim: {rate_hz: 30}\n"), "sim.rate_hz.x=1"),
            "--set 'sim.rate_hz.x=1': 'sim.rate_hz' is not a mapping");
  EXPECT_EQ(ApplyError(YAML::Load("sim: {walls: [1]}\n"), "sim.walls[3]=1"),
            "--set 'sim.walls[3]=1': 'sim.walls' has 1 items");
  EXPECT_EQ(ApplyError(YAML::Load("sim: {walls: 1}\n"), "sim.walls[0]=1"),
            "--set 'sim.walls[0]=1': 'sim.walls' is not a list");
}

TEST(ApplyOverrideTest, ResolvedTextRoundTrips) {
  const YAML::Node doc = Applied("name: x\nsim: {rate_hz: 30}\n", {"sim.rate_hz=0"});
  const YAML::Node again = YAML::Load(ToYaml(doc));
  EXPECT_EQ(again["sim"]["rate_hz"].as<int>(), 0);
  EXPECT_EQ(again["name"].as<std::string>(), "x");
}

}  // namespace
}  // namespace relplane::launch
