#include "relplane/common/options.hpp"

#include <gtest/gtest.h>

namespace relplane::config {
namespace {

struct SensorOptions {
  int width = 160;
  double max_range = 8.0;
};

// Reads a section the way services do: known keys, then Finish().
SensorOptions ReadSensor(const std::string& yaml) {
  Reader root = Reader::FromString(yaml, "scene.yaml", "sim");
  SensorOptions o;
  Reader sensor = root.Child("sensor");
  sensor.Read("width", &o.width);
  sensor.Read("max_range", &o.max_range);
  root.Finish();
  return o;
}

std::string ErrorOf(const std::string& yaml) {
  try {
    ReadSensor(yaml);
  } catch (const ConfigError& e) {
    return e.what();
  }
  return "";
}

TEST(Options, DefaultsWhenAbsent) {
  const SensorOptions o = ReadSensor("name: x\n");
  EXPECT_EQ(o.width, 160);
  EXPECT_EQ(o.max_range, 8.0);
}

TEST(Options, ReadsValues) {
  const SensorOptions o = ReadSensor("sim:\n  sensor:\n    width: 640\n    max_range: 4.5\n");
  EXPECT_EQ(o.width, 640);
  EXPECT_EQ(o.max_range, 4.5);
}

TEST(Options, UnknownKeyNamesFileLineAndSuggestion) {
  EXPECT_EQ(ErrorOf("sim:\n  sensor:\n    width: 640\n    max_rnge: 4.5\n"),
            "scene.yaml:4: unknown key 'sim.sensor.max_rnge' (did you mean 'max_range'?)");
}

TEST(Options, UnknownKeyWithoutNearMatch) {
  EXPECT_EQ(ErrorOf("sim:\n  colour: red\n"), "scene.yaml:2: unknown key 'sim.colour'");
}

TEST(Options, OtherSectionsAreNotThisReadersBusiness) {
  EXPECT_EQ(ErrorOf("mapper:\n  anything: 1\nsim:\n  sensor: {width: 10}\n"), "");
}

TEST(Options, WrongTypeNamesKey) {
  EXPECT_EQ(ErrorOf("sim:\n  sensor:\n    width: wide\n"),
            "scene.yaml:3: key 'sim.sensor.width': expected an integer");
}

TEST(Options, SectionMustBeMapping) {
  EXPECT_EQ(ErrorOf("sim: 3\n"), "scene.yaml:1: key 'sim': expected a mapping of keys");
}

TEST(Options, InvalidYamlIsOneLine) {
  const std::string error = ErrorOf("sim:\n  sensor: [1, 2\n");
  EXPECT_EQ(error.rfind("scene.yaml:", 0), 0u) << error;
  EXPECT_EQ(error.find('\n'), std::string::npos);
}

TEST(Options, MissingFile) {
  try {
    Reader::Load("/nonexistent/scene.yaml", "sim");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "/nonexistent/scene.yaml: cannot open the file");
  }
}

TEST(Options, ListsOfMappingsAreCheckedPerElement) {
  Reader root = Reader::FromString("walls:\n  - {x: 1}\n  - {x: 2, y: 3}\n", "w.yaml");
  std::vector<double> xs;
  for (Reader& wall : root.Children("walls")) {
    double x = 0;
    wall.ReadRequired("x", &x);
    xs.push_back(x);
  }
  EXPECT_EQ(xs, (std::vector<double>{1, 2}));
  try {
    root.Finish();
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "w.yaml:3: unknown key 'walls[1].y'");
  }
}

TEST(Options, FailNamesKeyLine) {
  Reader root = Reader::FromString("a: 1\nrate: -3\n", "r.yaml");
  double rate = 0;
  root.Read("rate", &rate);
  try {
    root.Fail("rate", "must be >= 0");
    FAIL() << "expected ConfigError";
  } catch (const ConfigError& e) {
    EXPECT_STREQ(e.what(), "r.yaml:2: key 'rate': must be >= 0");
  }
}

TEST(Options, RequiredKeyMissing) {
  Reader root = Reader::FromString("a: 1\n", "r.yaml");
  double b = 0;
  EXPECT_THROW(root.ReadRequired("b", &b), ConfigError);
}

}  // namespace
}  // namespace relplane::config
