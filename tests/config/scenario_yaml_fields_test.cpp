// The scenario YAML adapter, well-formed input: every field reaches sims::Scenario, absent
// keys keep the structs' defaults, relative paths resolve against the YAML's folder, and the
// shipped scenarios load.

#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <string>

#include "pgmcl/config/scenario_yaml.hpp"
#include "pgmcl/map_io/map_io.hpp"
#include "scenario_yaml_fixture.hpp"

namespace pgmcl::io {
namespace {

namespace fs = std::filesystem;
using test::ScenarioYaml;

using testkit::write_text;

TEST_F(ScenarioYaml, MinimalFileKeepsEveryDefault) {
  maps::OccupancyGrid map;
  const ScenarioFile f = read_scenario_file(scenario("robot: {motion: stationary}\n"), map);
  EXPECT_EQ(map.width(), 40);
  EXPECT_EQ(f.name, "s");
  EXPECT_EQ(fs::path(f.map_path), fs::path(dir_.file("maps/room.yaml")).lexically_normal());
  const sims::Scenario d;
  const sims::Scenario& s = f.scenario;
  EXPECT_EQ(s.sensor.name, d.sensor.name);
  EXPECT_EQ(s.sensor.beam_count, d.sensor.beam_count);
  EXPECT_EQ(s.seed, d.seed);
  EXPECT_EQ(s.duration, d.duration);
  EXPECT_EQ(s.scan_rate, d.scan_rate);
  EXPECT_EQ(s.control_rate, d.control_rate);
  EXPECT_EQ(s.noise.sigma_y, d.noise.sigma_y);
  EXPECT_EQ(s.noise.dropouts.enabled, d.noise.dropouts.enabled);
  EXPECT_EQ(s.surfaces.materials.size(), d.surfaces.materials.size());
  EXPECT_EQ(s.surfaces.default_material, d.surfaces.default_material);
  EXPECT_EQ(s.odometry.alphas.a3, d.odometry.alphas.a3);
  EXPECT_FALSE(s.odometry.origin.has_value());
  EXPECT_EQ(s.limits.max_v, d.limits.max_v);
  EXPECT_EQ(s.random_walk.max_leg, d.random_walk.max_leg);
  EXPECT_TRUE(s.kidnaps.empty());
  EXPECT_TRUE(s.discs.empty());
}

TEST_F(ScenarioYaml, EveryFieldReachesTheStruct) {
  // Label image: same size as the map, pixel value = palette index (2 = cardboard_box).
  maps::OccupancyGrid labels(40, 30, 0.1, Pose2{-1.0, -0.5, 0.0}, maps::kUnknown);
  fs::create_directories(dir_.file("scen"));
  save_map_image(labels, dir_.file("scen/labels.pgm"));  // 205 everywhere: no label
  const std::string body = R"(name: full
description: every key
seed: 1234
duration: 7.5
scan_rate: 12.5
control_rate: 25
sensor:
  profile: sick_lms_1deg
  angle_min: -1.5
  angle_increment: 0.02
  beam_count: 151
  range_min: 0.05
  range_max: 20
  scan_rate: 30
  scan_time: 0.02
  mount: [0.2, -0.1, 0.05]
noise:
  preset: none
  along_beam: true
  range_growth: 0.001
  across_beam: true
  sigma_y: 0.004
  quantum: 0.001
  dropouts: {enabled: true, rate: 0.02}
  short_returns: {enabled: true, rate: 0.03, lambda: 0.7}
  specular: {enabled: true, rate: 0.4, min_incidence: 0.6}
raycast: {unknown: block}
surfaces:
  default: fabric
  materials:
    - {name: fabric, sigma_normal: 0.004, sigma_45: 0.005, grazing_limit: 1.2, specular: true}
    - {name: glass, sigma_normal: 0.01, sigma_45: 0.02}
  labels: labels.pgm
  regions:
    - {material: glass, min: [0.0, 0.0], max: [1.0, 0.5]}
obstacles:
  discs:
    - {radius: 0.3, material: glass, path: {waypoints: [[0.5, 0.5], [1.5, 0.5]], speed: 0.7, start_offset: 0.2}}
  boxes:
    - half_length: 0.4
      half_width: 0.2
      yaw: 0.3
      material: white_paper
      path: {waypoints: [[2.0, 1.5]], speed: 0}
robot:
  start: [0.5, 1.0, 0.25]
  motion: random_walk
  limits: {max_v: 0.8, max_omega: 1.5}
  waypoints:
    points: [[1.0, 1.0], [2.0, 1.5]]
    controller: turn_then_drive
    lookahead: 0.4
    goal_tolerance: 0.06
    heading_tolerance: 0.07
    loop: true
  random_walk: {clearance: 0.25, goal_tolerance: 0.08, min_leg: 0.6, max_leg: 2.0, max_retries: 20}
odometry:
  random_noise: false
  model: omnidirectional
  alphas: {a1: 0.1, a2: 0.2, a3: 0.3, a4: 0.4, a5: 0.5}
  wheel_radius_bias: 0.01
  wheelbase_bias: -0.02
  yaw_drift_per_metre: 0.003
  origin: [10, 20, 1.0]
kidnaps:
  - {time: 3.0, pose: [2.0, 1.0, -1.0]}
)";
  maps::OccupancyGrid map;
  const ScenarioFile f = read_scenario_file(scenario(body), map);
  EXPECT_EQ(f.name, "full");
  EXPECT_EQ(f.description, "every key");
  const sims::Scenario& s = f.scenario;
  EXPECT_EQ(s.seed, 1234U);
  EXPECT_EQ(s.duration, 7.5);
  EXPECT_EQ(s.scan_rate, 12.5);
  EXPECT_EQ(s.control_rate, 25.0);
  EXPECT_EQ(s.sensor.name, "sick_lms_1deg");
  EXPECT_EQ(s.sensor.angle_min, -1.5);
  EXPECT_EQ(s.sensor.angle_increment, 0.02);
  EXPECT_EQ(s.sensor.beam_count, 151);
  EXPECT_EQ(s.sensor.range_min, 0.05);
  EXPECT_EQ(s.sensor.range_max, 20.0);
  EXPECT_EQ(s.sensor.scan_rate, 30.0);
  EXPECT_EQ(s.sensor.scan_time, 0.02);
  EXPECT_TRUE(test::same_pose(s.sensor_mount, Pose2{0.2, -0.1, 0.05}));
  EXPECT_TRUE(s.noise.along_beam);
  EXPECT_EQ(s.noise.range_growth, 0.001);
  EXPECT_TRUE(s.noise.across_beam);
  EXPECT_EQ(s.noise.sigma_y, 0.004);
  EXPECT_EQ(s.noise.quantum, 0.001);
  EXPECT_TRUE(s.noise.dropouts.enabled);
  EXPECT_EQ(s.noise.dropouts.rate, 0.02);
  EXPECT_TRUE(s.noise.short_returns.enabled);
  EXPECT_EQ(s.noise.short_returns.rate, 0.03);
  EXPECT_EQ(s.noise.short_returns.lambda, 0.7);
  EXPECT_TRUE(s.noise.specular.enabled);
  EXPECT_EQ(s.noise.specular.rate, 0.4);
  EXPECT_EQ(s.noise.specular.min_incidence, 0.6);
  EXPECT_EQ(s.raycast.unknown, sims::UnknownCellPolicy::kBlock);
  // Palette: the seven defaults, fabric modified in place, glass appended.
  ASSERT_EQ(s.surfaces.materials.size(), sims::default_materials().size() + 1);
  const sims::SurfaceMaterial& fabric = s.surfaces.materials[3];
  EXPECT_EQ(fabric.name, "fabric");
  EXPECT_EQ(fabric.sigma.sigma_normal, 0.004);
  EXPECT_EQ(fabric.sigma.sigma_45, 0.005);
  EXPECT_EQ(fabric.sigma.grazing_limit, 1.2);
  EXPECT_TRUE(fabric.specular);
  EXPECT_EQ(s.surfaces.materials.back().name, "glass");
  EXPECT_EQ(s.surfaces.materials.back().sigma.sigma_45, 0.02);
  EXPECT_FALSE(s.surfaces.materials.back().specular);
  EXPECT_EQ(s.surfaces.default_material, "fabric");
  ASSERT_EQ(s.surfaces.labels.size(), map.size());
  EXPECT_EQ(s.surfaces.labels.front(), sims::SurfaceLayout::kNoLabel);
  ASSERT_EQ(s.surfaces.regions.size(), 1U);
  EXPECT_EQ(s.surfaces.regions[0].material, "glass");
  EXPECT_EQ(s.surfaces.regions[0].x_max, 1.0);
  EXPECT_EQ(s.surfaces.regions[0].y_max, 0.5);
  ASSERT_EQ(s.discs.size(), 1U);
  EXPECT_EQ(s.discs[0].radius, 0.3);
  EXPECT_EQ(s.discs[0].material, "glass");
  ASSERT_EQ(s.discs[0].path.waypoints.size(), 2U);
  EXPECT_EQ(s.discs[0].path.waypoints[1].x, 1.5);
  EXPECT_EQ(s.discs[0].path.speed, 0.7);
  EXPECT_EQ(s.discs[0].path.start_offset, 0.2);
  ASSERT_EQ(s.boxes.size(), 1U);
  EXPECT_EQ(s.boxes[0].half_length, 0.4);
  EXPECT_EQ(s.boxes[0].half_width, 0.2);
  EXPECT_EQ(s.boxes[0].yaw, 0.3);
  EXPECT_EQ(s.boxes[0].material, "white_paper");
  EXPECT_EQ(s.boxes[0].path.speed, 0.0);
  EXPECT_TRUE(test::same_pose(s.start, Pose2{0.5, 1.0, 0.25}));
  EXPECT_EQ(s.motion, sims::MotionMode::kRandomWalk);
  EXPECT_EQ(s.limits.max_v, 0.8);
  EXPECT_EQ(s.limits.max_omega, 1.5);
  ASSERT_EQ(s.waypoints.waypoints.size(), 2U);
  EXPECT_EQ(s.waypoints.waypoints[1].y, 1.5);
  EXPECT_EQ(s.waypoints.controller, sims::Controller::kTurnThenDrive);
  EXPECT_EQ(s.waypoints.lookahead, 0.4);
  EXPECT_EQ(s.waypoints.goal_tolerance, 0.06);
  EXPECT_EQ(s.waypoints.heading_tolerance, 0.07);
  EXPECT_TRUE(s.waypoints.loop);
  EXPECT_EQ(s.random_walk.clearance, 0.25);
  EXPECT_EQ(s.random_walk.goal_tolerance, 0.08);
  EXPECT_EQ(s.random_walk.min_leg, 0.6);
  EXPECT_EQ(s.random_walk.max_leg, 2.0);
  EXPECT_EQ(s.random_walk.max_retries, 20);
  EXPECT_FALSE(s.odometry.random_noise);
  EXPECT_EQ(s.odometry.kind, MotionModelKind::kOmnidirectional);
  EXPECT_EQ(s.odometry.alphas.a1, 0.1);
  EXPECT_EQ(s.odometry.alphas.a5, 0.5);
  EXPECT_EQ(s.odometry.wheel_radius_bias, 0.01);
  EXPECT_EQ(s.odometry.wheelbase_bias, -0.02);
  EXPECT_EQ(s.odometry.yaw_drift_per_metre, 0.003);
  ASSERT_TRUE(s.odometry.origin.has_value());
  EXPECT_TRUE(test::same_pose(*s.odometry.origin, Pose2{10.0, 20.0, 1.0}));
  ASSERT_EQ(s.kidnaps.size(), 1U);
  EXPECT_EQ(s.kidnaps[0].time, 3.0);
  EXPECT_TRUE(test::same_pose(s.kidnaps[0].pose, Pose2{2.0, 1.0, -1.0}));
}

TEST_F(ScenarioYaml, LabelImagePixelsArePaletteIndices) {
  // Raw pixel values (save_map_image would write trinary shades).
  std::string pgm = "P5\n40 30\n255\n";
  std::string pixels(40 * 30, static_cast<char>(255));
  pixels[0] = 2;            // top-left pixel = grid row 29, col 0
  pixels[40 * 29 + 5] = 6;  // bottom row, col 5
  write_text(dir_.file("scen/lab.pgm"), pgm + pixels);
  maps::OccupancyGrid map;
  const ScenarioFile f = read_scenario_file(
      scenario("surfaces: {labels: lab.pgm}\nrobot: {motion: stationary}\n"), map);
  const auto& l = f.scenario.surfaces.labels;
  ASSERT_EQ(l.size(), map.size());
  EXPECT_EQ(l[map.index(0, 29)], 2);
  EXPECT_EQ(l[map.index(5, 0)], 6);
  EXPECT_EQ(l[map.index(1, 1)], sims::SurfaceLayout::kNoLabel);
}

TEST_F(ScenarioYaml, ShippedScenariosLoadAndValidate) {
  const fs::path dir = fs::path(PGMCL_SOURCE_DIR) / "configs" / "scenarios";
  std::size_t n = 0;
  for (const auto& entry : fs::directory_iterator(dir)) {
    if (entry.path().extension() != ".yaml") continue;
    SCOPED_TRACE(entry.path().string());
    maps::OccupancyGrid map;
    const ScenarioFile f = read_scenario_file(entry.path().string(), map);
    EXPECT_FALSE(map.empty());
    EXPECT_EQ(f.name, entry.path().stem().string());
    EXPECT_FALSE(f.description.empty());
    ++n;
  }
  EXPECT_GE(n, 5U);
}

TEST_F(ScenarioYaml, LoadScenarioHandsOutTheMap) {
  maps::OccupancyGrid map;
  const sims::Scenario s =
      load_scenario(scenario("seed: 77\nrobot: {motion: stationary, start: [1, 1, 0]}\n"), &map);
  EXPECT_EQ(s.seed, 77U);
  EXPECT_EQ(map.width(), 40);
  EXPECT_EQ(map.height(), 30);
  EXPECT_DOUBLE_EQ(map.origin().x, -1.0);
}

}  // namespace
}  // namespace pgmcl::io
