// map.json, metrics.json, map.svg and error.svg parse back (JSON grammar, XML well-formedness)
// and carry what they promise.
#include <gtest/gtest.h>

#include <cstdio>
#include <cstdlib>
#include <fstream>

#include "fixtures.hpp"
#include "json_check.hpp"
#include "relplane/eval/json_writer.hpp"
#include "relplane/eval/map_metrics.hpp"
#include "relplane/eval/report_json.hpp"
#include "relplane/eval/svg.hpp"
#include "xml_check.hpp"

namespace relplane::eval {
namespace {

using testing::Json;

MapSnapshot GroupedMap() {
  MapSnapshot map;
  map.seq = 42;
  map.planes = {testing::Wall(7, {-1, -2}, {5, -2}), testing::Wall(8, {5, -2}, {5, 2}),
                testing::Wall(9, {5, 2}, {-1, 2})};
  map.groups = {{3, 7, {7, 8}}, {1, 9, {8, 9}}};
  return map;
}

RunMetrics SomeMetrics() {
  RunMetrics m;
  const std::vector<PoseSample> truth = testing::LoopInRoom();
  m.trajectory = ComputeTrajectoryMetrics(MatchBySeq(truth, truth), 1.0);
  m.map = ComputeMapMetrics(testing::Room(), GroupedMap(), truth, EvalOptions{});
  m.timing.services["relplane-\"odd\"\nname"].reports = 1;  // escaping must hold
  m.expectations = {{"ate_rmse_max_m", 0.05, 0.0, true, true}};
  return m;
}

Json Parsed(const std::string& text) {
  Json json;
  std::string error;
  EXPECT_TRUE(testing::ParseJson(text, &json, &error)) << error << "\n" << text;
  return json;
}

// xmllint (libxml2-utils) is the independent check when the machine has it.
void ExpectXmllintAccepts(const std::string& svg, const std::string& name) {
  if (std::system("command -v xmllint >/dev/null 2>&1") != 0) return;
  const std::string path = ::testing::TempDir() + name;
  std::ofstream(path) << svg;
  EXPECT_EQ(std::system(("xmllint --noout " + path).c_str()), 0) << path;
}

TEST(Outputs, MapJsonHoldsPlanesGroupsAndMembership) {
  const Json json = Parsed(MapToJson(GroupedMap()));
  EXPECT_EQ(json["seq"].number, 42);
  ASSERT_EQ(json["planes"].items.size(), 3u);
  const Json& plane = json["planes"][1];
  EXPECT_EQ(plane["id"].number, 8);
  EXPECT_EQ(plane["vertices"].items.size(), 4u);
  EXPECT_EQ(plane["normal"].items.size(), 3u);
  EXPECT_EQ(plane["observations"].number, 10);
  // Plane 8 belongs to both groups.
  ASSERT_EQ(plane["groups"].items.size(), 2u);
  EXPECT_EQ(plane["groups"][0].number, 3);
  EXPECT_EQ(plane["groups"][1].number, 1);
  ASSERT_EQ(json["groups"].items.size(), 2u);
  // Labels follow the group id order: group 1 is X1, group 3 is X2.
  EXPECT_EQ(json["groups"][0]["label"].text, "X2");
  EXPECT_EQ(json["groups"][1]["label"].text, "X1");
  EXPECT_EQ(json["groups"][0]["basis"].number, 7);
}

TEST(Outputs, MetricsJsonParsesWithNullForMissingNumbers) {
  RunMetrics m = SomeMetrics();
  const Json json = Parsed(MetricsToJson(m, "test"));
  EXPECT_EQ(json["schema"].text, "relplane-metrics/1");
  EXPECT_NEAR(json["trajectory"]["ate_rmse_m"].number, 0.0, 1e-12);
  EXPECT_EQ(json["map"]["walls_mapped"].number, 3);
  EXPECT_EQ(json["map"]["walls"].items.size(), 4u);
  EXPECT_TRUE(json["timing"]["end_to_end"]["p50_ms"].IsNull());  // no latency samples
  EXPECT_EQ(json["expect"][0]["key"].text, "ate_rmse_max_m");
  EXPECT_TRUE(json["expect"][0]["pass"].boolean);
  EXPECT_TRUE(json["expect_pass"].boolean);
  EXPECT_EQ(json["timing"]["services"].fields.size(), 1u);
  // The estimate is the truth: every frame lies within 3 sigma of even a zero covariance.
  const size_t frames = testing::LoopInRoom().size();
  EXPECT_EQ(json["trajectory"]["consistency"]["frames"].number, static_cast<double>(frames));
  EXPECT_EQ(json["trajectory"]["consistency"]["position_within_3sigma"].number, 1.0);
  const auto by_status = json["trajectory"]["consistency_by_status"];
  EXPECT_EQ(by_status.fields.size(), 4u);
  EXPECT_EQ(by_status["tracking"]["yaw_within_3sigma"].number, 1.0);
  EXPECT_TRUE(by_status["lost"]["yaw_within_3sigma"].IsNull());  // no LOST frame
  // An empty run is valid JSON too.
  const Json empty = Parsed(MetricsToJson(RunMetrics{}, "test"));
  EXPECT_TRUE(empty["trajectory"]["ate_rmse_m"].IsNull());
  EXPECT_TRUE(empty["expect_pass"].IsNull());
}

TEST(Outputs, JsonWriterEscapesAndNestsCompactly) {
  JsonWriter json;
  json.BeginObject().Field("a\"b", "line\nbreak\t\x01").Key("v").BeginArray(true);
  json.Value(1.5).Value(static_cast<int64_t>(-2)).Null().Value(true).EndArray().EndObject();
  const Json parsed = Parsed(json.Str());
  EXPECT_EQ(parsed["a\"b"].text, "line\nbreak\t?");
  EXPECT_EQ(parsed["v"].items.size(), 4u);
  EXPECT_EQ(parsed["v"][1].number, -2);
}

TEST(Outputs, MapSvgIsWellFormedWithWallsGroupsTrajectoriesAndLegend) {
  const MapSnapshot world = testing::Room();
  const MapSnapshot map = GroupedMap();
  const std::vector<PoseSample> truth = testing::LoopInRoom();
  const RunMetrics metrics = SomeMetrics();
  MapPicture picture;
  picture.world = &world;
  picture.map = &map;
  picture.truth = &truth;
  picture.estimate = &truth;
  picture.metrics = &metrics;
  const std::string svg = RenderMapSvg(picture);
  std::string error;
  std::map<std::string, int> counts;
  ASSERT_TRUE(testing::CheckXml(svg, &error, &counts)) << error;
  ExpectXmllintAccepts(svg, "map.svg");
  EXPECT_EQ(counts["svg"], 1);
  EXPECT_EQ(counts["polyline"], 2);  // true and estimated trajectories
  // Labels X1 and X2 at the two group centroids, and the scale bar in metres.
  EXPECT_NE(svg.find(">X1</text>"), std::string::npos);
  EXPECT_NE(svg.find(">X2</text>"), std::string::npos);
  EXPECT_NE(svg.find(" m</text>"), std::string::npos);
  EXPECT_NE(svg.find("true wall"), std::string::npos);
  EXPECT_NE(svg.find("estimated trajectory"), std::string::npos);
  // Lines: grid + 4 true walls + 3 mapped walls + 4 group links + legend 5 + scale bar 3.
  EXPECT_GE(counts["line"], 4 + 3 + 4 + 5 + 3);
}

TEST(Outputs, MapSvgSetsSpuriousPlanesApart) {
  const MapSnapshot world = testing::Room();
  MapSnapshot map = GroupedMap();
  map.planes.push_back(testing::Wall(30, {1, -1}, {2, 1}));  // diagonal: matches no wall
  const std::vector<PoseSample> truth = testing::LoopInRoom();
  RunMetrics metrics;
  metrics.map = ComputeMapMetrics(world, map, truth, EvalOptions{});
  ASSERT_EQ(metrics.map.spurious_ids, std::vector<int64_t>{30});
  MapPicture picture;
  picture.world = &world;
  picture.map = &map;
  picture.truth = &truth;
  picture.metrics = &metrics;
  const std::string svg = RenderMapSvg(picture);
  EXPECT_NE(svg.find("<title>mapped plane matching no true wall 30</title>"), std::string::npos);
  EXPECT_NE(svg.find("<title>mapped plane 7</title>"), std::string::npos);
  EXPECT_EQ(svg.find("<title>mapped plane 30</title>"), std::string::npos);
}

TEST(Outputs, EmptyPicturesAreWellFormedToo) {
  std::string error;
  EXPECT_TRUE(testing::CheckXml(RenderMapSvg(MapPicture{}), &error)) << error;
  EXPECT_TRUE(testing::CheckXml(RenderErrorSvg(TrajectoryMetrics{}), &error)) << error;
}

TEST(Outputs, ErrorSvgHasAxesUnitsAndBothSeries) {
  const std::string svg = RenderErrorSvg(SomeMetrics().trajectory);
  std::string error;
  std::map<std::string, int> counts;
  ASSERT_TRUE(testing::CheckXml(svg, &error, &counts)) << error;
  ExpectXmllintAccepts(svg, "error.svg");
  // The two error series, and the signed errors along and across the heading in front of
  // their +-2 sigma bands.
  EXPECT_EQ(counts["polyline"], 4);
  EXPECT_EQ(counts["polygon"], 2);
  EXPECT_NE(svg.find("+-2 sigma"), std::string::npos);
  EXPECT_NE(svg.find("time (s)"), std::string::npos);
  EXPECT_NE(svg.find("position error (m)"), std::string::npos);
}

TEST(Outputs, XmlCheckerRejectsBrokenDocuments) {
  std::string error;
  EXPECT_FALSE(testing::CheckXml("<svg><g></svg>", &error));
  EXPECT_FALSE(testing::CheckXml("<svg a=1/>", &error));
  EXPECT_FALSE(testing::CheckXml("<svg>&bogus;</svg>", &error));
  EXPECT_FALSE(testing::CheckXml("<a/><b/>", &error));
  EXPECT_TRUE(
      testing::CheckXml("<?xml version=\"1.0\"?>\n<a x=\"&lt;\"><!-- c --><b/>t</a>\n", &error))
      << error;
}

TEST(Outputs, NiceStepsAreOneTwoOrFive) {
  EXPECT_DOUBLE_EQ(NiceStep(10.0, 5.0), 2.0);
  EXPECT_DOUBLE_EQ(NiceStep(0.7, 5.0), 0.2);
  EXPECT_DOUBLE_EQ(NiceStep(45.0, 10.0), 5.0);
}

}  // namespace
}  // namespace relplane::eval
