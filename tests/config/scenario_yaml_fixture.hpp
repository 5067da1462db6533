#pragma once
// The fixture of the scenario YAML adapter tests (scenario_yaml_fields_test.cpp,
// scenario_yaml_errors_test.cpp): a saved room map and a scenario file next to it.

#include <gtest/gtest.h>

#include <filesystem>
#include <initializer_list>
#include <string>

#include "io_test_util.hpp"
#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::io::test {

/// A 4 x 3 m room at 10 cm (walls on the border), saved as <dir>/maps/room.yaml.
inline maps::OccupancyGrid scenario_room() {
  return walled_room(40, 30, 0.1, Pose2{-1.0, -0.5, 0.0});
}

class ScenarioYaml : public ::testing::Test {
 protected:
  void SetUp() override {
    std::filesystem::create_directories(std::filesystem::path(dir_.file("maps")));
    maps::save_map(scenario_room(), dir_.file("maps/room.yaml"));
  }
  /// Writes `body` (after a `map:` line pointing at the room) to scen/s.yaml.
  std::string scenario(const std::string& body, bool with_map = true) {
    const std::string path = dir_.file("scen/s.yaml");
    testkit::write_text(path, (with_map ? "map: ../maps/room.yaml\n" : "") + body);
    return path;
  }
  /// Loads `body` and returns the error; fails the test if it loads.
  ScenarioError error(const std::string& body, bool with_map = true) {
    const std::string path = scenario(body, with_map);
    try {
      maps::OccupancyGrid map;
      (void)read_scenario_file(path, map);
    } catch (const ScenarioError& e) {
      EXPECT_EQ(e.file(), path);
      return e;
    }
    ADD_FAILURE() << "no ScenarioError for:\n" << body;
    return ScenarioError(path, 0, "", "");
  }
  /// A bad body and where its error must point: the key, its line (0: not checked) and a
  /// piece of its message ("": not checked).
  struct Bad {
    std::string body;
    std::string field;
    unsigned line = 0;
    std::string message{};
    bool with_map = true;
  };
  void expect_errors(std::initializer_list<Bad> cases) {
    for (const Bad& c : cases) {
      SCOPED_TRACE(c.body);
      const ScenarioError e = error(c.body, c.with_map);
      EXPECT_EQ(e.field(), c.field);
      if (c.line != 0) {
        EXPECT_EQ(e.line(), c.line);
      }
      if (!c.message.empty()) {
        EXPECT_NE(e.message().find(c.message), std::string::npos) << e.what();
      }
    }
  }
  TempDir dir_;
};

}  // namespace pgmcl::io::test
