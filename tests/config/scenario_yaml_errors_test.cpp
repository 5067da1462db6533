// The scenario YAML adapter, bad input: every kind of error throws ScenarioError naming
// file, line and key (unknown keys, wrong types, bad names, syntax, map and struct checks).

#include <gtest/gtest.h>

#include <string>

#include "pgmcl/config/scenario_yaml.hpp"
#include "scenario_yaml_fixture.hpp"

namespace pgmcl::io {
namespace {

using test::ScenarioYaml;

TEST_F(ScenarioYaml, UnknownKeysAreReportedWithTheirLine) {
  ScenarioError e = error("seed: 3\nduraton: 5\n");
  EXPECT_EQ(e.field(), "duraton");
  EXPECT_EQ(e.line(), 3U);
  EXPECT_NE(std::string(e.what()).find("unknown key"), std::string::npos);

  e = error("robot:\n  motion: waypoints\n  waypoints:\n    points: [[1, 1]]\n    lookahed: 1\n");
  EXPECT_EQ(e.field(), "robot.waypoints.lookahed");
  EXPECT_EQ(e.line(), 6U);

  e = error(
      "obstacles:\n  discs:\n    - {radius: 0.2, path: {waypoints: [[1, 1]]}, colour: red}\n");
  EXPECT_EQ(e.field(), "obstacles.discs[0].colour");
  EXPECT_EQ(e.line(), 4U);
}

TEST_F(ScenarioYaml, FilterSettingsAreRejectedWithWhereTheyBelong) {
  // No command applies filter settings from a scenario: accepting them would ignore them.
  const ScenarioError e = error("seed: 3\nfilter:\n  particles: 500\n");
  EXPECT_EQ(e.field(), "filter");
  EXPECT_EQ(e.line(), 4U);  // the mapping's first line, as for every value (yaml_reader.hpp)
  EXPECT_NE(e.message().find("experiment file"), std::string::npos);
}

TEST_F(ScenarioYaml, WrongTypesNameTheKey) {
  ScenarioError e = error("duration: fast\n");
  EXPECT_EQ(e.field(), "duration");
  EXPECT_EQ(e.line(), 2U);
  EXPECT_NE(e.message().find("expected a number"), std::string::npos);

  e = error("seed: -3\n");
  EXPECT_EQ(e.field(), "seed");

  e = error("sensor:\n  beam_count: 10.5\n");
  EXPECT_EQ(e.field(), "sensor.beam_count");
  EXPECT_EQ(e.line(), 3U);

  e = error("robot:\n  start: [1, 2]\n");
  EXPECT_EQ(e.field(), "robot.start");
  EXPECT_NE(e.message().find("[x, y, theta]"), std::string::npos);

  e = error("robot:\n  waypoints:\n    points:\n      - [1, 1]\n      - [2, two]\n");
  EXPECT_EQ(e.field(), "robot.waypoints.points[1][1]");
  EXPECT_EQ(e.line(), 6U);

  e = error("noise:\n  dropouts: {enabled: maybe}\n");
  EXPECT_EQ(e.field(), "noise.dropouts.enabled");

  e = error("robot: [1, 2]\n");
  EXPECT_EQ(e.field(), "robot");
  EXPECT_NE(e.message().find("mapping"), std::string::npos);

  e = error("kidnaps: {time: 1}\n");
  EXPECT_EQ(e.field(), "kidnaps");
}

TEST_F(ScenarioYaml, BadNamesListTheChoices) {
  ScenarioError e = error("robot: {motion: fly}\n");
  EXPECT_EQ(e.field(), "robot.motion");
  EXPECT_NE(e.message().find("random_walk"), std::string::npos);

  e = error("sensor: {profile: lidar9000}\n");
  EXPECT_EQ(e.field(), "sensor.profile");
  EXPECT_NE(e.message().find("hokuyo_utm30lx"), std::string::npos);

  e = error("raycast: {unknown: maybe}\n");
  EXPECT_EQ(e.field(), "raycast.unknown");
}

TEST_F(ScenarioYaml, SyntaxDuplicatesAndMissingKeys) {
  ScenarioError e = error("seed: [1, 2\n");
  EXPECT_EQ(e.field(), "yaml");
  EXPECT_GE(e.line(), 2U);

  e = error("seed: 1\nseed: 2\n");
  EXPECT_EQ(e.field(), "seed");
  EXPECT_EQ(e.line(), 3U);
  EXPECT_NE(e.message().find("duplicate"), std::string::npos);

  e = error("seed: 1\n", /*with_map=*/false);
  EXPECT_EQ(e.field(), "map");
  EXPECT_NE(e.message().find("missing"), std::string::npos);

  e = error("kidnaps:\n  - {pose: [1, 1, 0]}\n");
  EXPECT_EQ(e.field(), "kidnaps[0].time");
  EXPECT_EQ(e.line(), 3U);
}

TEST_F(ScenarioYaml, MapProblemsPointAtTheMapKey) {
  const ScenarioError e = error("seed: 1\nmap: ../maps/nowhere.yaml\n", /*with_map=*/false);
  EXPECT_EQ(e.field(), "map");
  EXPECT_EQ(e.line(), 2U);
  EXPECT_NE(e.message().find("nowhere.yaml"), std::string::npos);
}

TEST_F(ScenarioYaml, ChecksAgainstTheMapAreReportedAtTheirKey) {
  // The room spans x in [-1, 3], y in [-0.5, 2.5].
  ScenarioError e = error("robot:\n  motion: stationary\n  start: [10, 1, 0]\n");
  EXPECT_EQ(e.field(), "robot.start");
  EXPECT_EQ(e.line(), 4U);
  EXPECT_NE(e.message().find("inside the map"), std::string::npos);

  e = error(
      "robot: {motion: stationary}\nkidnaps:\n  - {time: 1, pose: [1, 1, 0]}\n"
      "  - {time: 2, pose: [1, 9, 0]}\n");
  EXPECT_EQ(e.field(), "kidnaps[1].pose");
  EXPECT_EQ(e.line(), 5U);

  e = error(
      "robot: {motion: stationary}\nsurfaces:\n  regions:\n"
      "    - {material: marble, min: [0, 0], max: [1, 1]}\n");
  EXPECT_EQ(e.field(), "surfaces.regions[0].material");
  EXPECT_EQ(e.line(), 5U);
  EXPECT_NE(e.message().find("marble"), std::string::npos);

  e = error(
      "robot: {motion: stationary}\nobstacles:\n  boxes:\n"
      "    - {material: marble, path: {waypoints: [[1, 1]]}}\n");
  EXPECT_EQ(e.field(), "obstacles.boxes[0].material");

  e = error("robot:\n  motion: stationary\n  limits: {max_v: 0}\n");
  EXPECT_EQ(e.field(), "robot.limits.max_v");
  EXPECT_EQ(e.line(), 4U);
}

TEST_F(ScenarioYaml, StructChecksAreReportedAtTheirMapping) {
  ScenarioError e = error("sensor:\n  range_min: 5\n  range_max: 1\n");
  EXPECT_EQ(e.field(), "sensor");
  EXPECT_EQ(e.line(), 3U);

  e = error("noise:\n  dropouts: {rate: 1.5}\n");
  EXPECT_EQ(e.field(), "noise");

  e = error("surfaces:\n  materials:\n    - {name: odd, sigma_normal: 0.01, sigma_45: 0.001}\n");
  EXPECT_EQ(e.field(), "surfaces.materials[0]");
  EXPECT_EQ(e.line(), 4U);

  e = error("obstacles:\n  discs:\n    - {radius: 0.2, path: {waypoints: [[1, 1]], speed: -1}}\n");
  EXPECT_EQ(e.field(), "obstacles.discs[0].path");
}

TEST_F(ScenarioYaml, ErrorIsAFormatErrorWithFileLineKeyInWhat) {
  const std::string path = scenario("duration: [1]\n");
  try {
    (void)load_scenario(path);
    FAIL() << "no error";
  } catch (const FormatError& e) {
    EXPECT_EQ(std::string(e.what()), path + ":2: duration: expected a number, got a list");
  }
}

}  // namespace
}  // namespace pgmcl::io
