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
  expect_errors({
      {"seed: 3\nduraton: 5\n", "duraton", 3, "unknown key"},
      {"robot:\n  motion: waypoints\n  waypoints:\n    points: [[1, 1]]\n    lookahed: 1\n",
       "robot.waypoints.lookahed", 6},
      {"obstacles:\n  discs:\n    - {radius: 0.2, path: {waypoints: [[1, 1]]}, colour: red}\n",
       "obstacles.discs[0].colour", 4},
  });
}

TEST_F(ScenarioYaml, FilterSettingsAreRejectedWithWhereTheyBelong) {
  // No command applies filter settings from a scenario: accepting them would ignore them.
  // Line 4 is the mapping's first line, as for every value (yaml_reader.hpp).
  expect_errors({{"seed: 3\nfilter:\n  particles: 500\n", "filter", 4, "experiment file"}});
}

TEST_F(ScenarioYaml, WrongTypesNameTheKey) {
  expect_errors({
      {"duration: fast\n", "duration", 2, "expected a number"},
      {"seed: -3\n", "seed"},
      {"sensor:\n  beam_count: 10.5\n", "sensor.beam_count", 3},
      {"robot:\n  start: [1, 2]\n", "robot.start", 0, "[x, y, theta]"},
      {"robot:\n  waypoints:\n    points:\n      - [1, 1]\n      - [2, two]\n",
       "robot.waypoints.points[1][1]", 6},
      {"noise:\n  dropouts: {enabled: maybe}\n", "noise.dropouts.enabled"},
      {"robot: [1, 2]\n", "robot", 0, "mapping"},
      {"kidnaps: {time: 1}\n", "kidnaps"},
  });
}

TEST_F(ScenarioYaml, BadNamesListTheChoices) {
  expect_errors({
      {"robot: {motion: fly}\n", "robot.motion", 0, "random_walk"},
      {"sensor: {profile: lidar9000}\n", "sensor.profile", 0, "hokuyo_utm30lx"},
      {"raycast: {unknown: maybe}\n", "raycast.unknown"},
  });
}

TEST_F(ScenarioYaml, SyntaxDuplicatesAndMissingKeys) {
  const ScenarioError e = error("seed: [1, 2\n");
  EXPECT_EQ(e.field(), "yaml");
  EXPECT_GE(e.line(), 2U);
  expect_errors({
      {"seed: 1\nseed: 2\n", "seed", 3, "duplicate"},
      {"seed: 1\n", "map", 0, "missing", /*with_map=*/false},
      {"kidnaps:\n  - {pose: [1, 1, 0]}\n", "kidnaps[0].time", 3},
  });
}

TEST_F(ScenarioYaml, MapProblemsPointAtTheMapKey) {
  expect_errors({{"seed: 1\nmap: ../maps/nowhere.yaml\n", "map", 2, "nowhere.yaml",
                  /*with_map=*/false}});
}

TEST_F(ScenarioYaml, ChecksAgainstTheMapAreReportedAtTheirKey) {
  // The room spans x in [-1, 3], y in [-0.5, 2.5].
  expect_errors({
      {"robot:\n  motion: stationary\n  start: [10, 1, 0]\n", "robot.start", 4, "inside the map"},
      {"robot: {motion: stationary}\nkidnaps:\n  - {time: 1, pose: [1, 1, 0]}\n"
       "  - {time: 2, pose: [1, 9, 0]}\n",
       "kidnaps[1].pose", 5},
      {"robot: {motion: stationary}\nsurfaces:\n  regions:\n"
       "    - {material: marble, min: [0, 0], max: [1, 1]}\n",
       "surfaces.regions[0].material", 5, "marble"},
      {"robot: {motion: stationary}\nobstacles:\n  boxes:\n"
       "    - {material: marble, path: {waypoints: [[1, 1]]}}\n",
       "obstacles.boxes[0].material"},
      {"robot:\n  motion: stationary\n  limits: {max_v: 0}\n", "robot.limits.max_v", 4},
  });
}

TEST_F(ScenarioYaml, StructChecksAreReportedAtTheirMapping) {
  expect_errors({
      {"sensor:\n  range_min: 5\n  range_max: 1\n", "sensor", 3},
      {"noise:\n  dropouts: {rate: 1.5}\n", "noise"},
      {"surfaces:\n  materials:\n    - {name: odd, sigma_normal: 0.01, sigma_45: 0.001}\n",
       "surfaces.materials[0]", 4},
      {"obstacles:\n  discs:\n    - {radius: 0.2, path: {waypoints: [[1, 1]], speed: -1}}\n",
       "obstacles.discs[0].path"},
  });
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
