#pragma once
// Checks that a run folder holds the six files and that each one parses; returns what the
// process tests look at.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "json_check.hpp"
#include "relplane/eval/files.hpp"
#include "relplane/eval/tum.hpp"
#include "xml_check.hpp"

namespace relplane::testing {

struct RunFolder {
  std::vector<eval::PoseSample> trajectory;
  std::vector<eval::PoseSample> truth;
  Json map;
  Json metrics;
};

inline RunFolder CheckRunFolder(const std::string& dir) {
  RunFolder folder;
  std::string text, error;
  for (const char* name : {"trajectory.tum", "truth.tum"}) {
    EXPECT_TRUE(eval::ReadFile(dir + "/" + name, &text)) << name << " missing";
    auto* poses = std::string(name) == "truth.tum" ? &folder.truth : &folder.trajectory;
    EXPECT_TRUE(eval::ParseTum(text, poses, &error)) << name << ": " << error;
  }
  EXPECT_TRUE(eval::ReadFile(dir + "/map.json", &text)) << "map.json missing";
  EXPECT_TRUE(ParseJson(text, &folder.map, &error)) << "map.json: " << error;
  EXPECT_TRUE(eval::ReadFile(dir + "/metrics.json", &text)) << "metrics.json missing";
  EXPECT_TRUE(ParseJson(text, &folder.metrics, &error)) << "metrics.json: " << error;
  for (const char* name : {"map.svg", "error.svg"}) {
    EXPECT_TRUE(eval::ReadFile(dir + "/" + name, &text)) << name << " missing";
    EXPECT_TRUE(CheckXml(text, &error)) << name << ": " << error;
  }
  return folder;
}

}  // namespace relplane::testing
