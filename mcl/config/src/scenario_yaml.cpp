// Scenario YAML -> sims::Scenario. The schema is documented in scenario_yaml.hpp; every
// key read here is a field of a sims struct, so absent keys keep the structs' defaults.
// The world sections (surfaces, obstacles, label image) are in scenario_yaml_world.cpp.

#include <cmath>
#include <cstdio>
#include <filesystem>

#include "pgmcl/map_io/map_io.hpp"
#include "scenario_parser.hpp"

namespace pgmcl::io {
namespace detail::scenario {

namespace fs = std::filesystem;

std::string ScenarioParser::resolve(const std::string& relative) const {
  const fs::path p(relative);
  if (p.is_absolute()) return p.string();
  return (fs::path(path_).parent_path() / p).lexically_normal().string();
}

void ScenarioParser::read_sensor(YamlMap m, sims::Scenario& sc) {
  std::string profile;
  if (m.text("profile", profile)) {
    try {
      sc.sensor = sims::sensor_profile_by_name(profile);
    } catch (const std::invalid_argument& e) {
      m.fail("profile", e.what());
    }
  }
  auto& s = sc.sensor;
  m.number("angle_min", s.angle_min);
  m.number("angle_increment", s.angle_increment);
  m.integer("beam_count", s.beam_count, 1, 1'000'000);
  m.number("range_min", s.range_min);
  m.number("range_max", s.range_max);
  m.number("scan_rate", s.scan_rate);
  m.number("scan_time", s.scan_time);
  m.pose("mount", sc.sensor_mount);
  note("Scenario.sensor_mount", m, "mount");
  note_map("Scenario.sensor", m);
  m.finish();
  checked(m, [&] { s.validate(); });
}

void ScenarioParser::read_noise(YamlMap m, sims::BeamNoise& n) {
  const auto preset = choice<int>(m, "preset", {{"default", 0}, {"none", 1}}, 0);
  n = preset == 1 ? sims::BeamNoise::none() : sims::BeamNoise{};
  m.boolean("along_beam", n.along_beam);
  m.number("range_growth", n.range_growth);
  m.boolean("across_beam", n.across_beam);
  m.number("sigma_y", n.sigma_y);
  m.number("quantum", n.quantum);
  {
    YamlMap d = m.child("dropouts");
    d.boolean("enabled", n.dropouts.enabled);
    d.number("rate", n.dropouts.rate);
    d.finish();
  }
  {
    YamlMap s = m.child("short_returns");
    s.boolean("enabled", n.short_returns.enabled);
    s.number("rate", n.short_returns.rate);
    s.number("lambda", n.short_returns.lambda);
    s.finish();
  }
  {
    YamlMap s = m.child("specular");
    s.boolean("enabled", n.specular.enabled);
    s.number("rate", n.specular.rate);
    s.number("min_incidence", n.specular.min_incidence);
    s.finish();
  }
  m.finish();
  checked(m, [&] { n.validate(); });
}

void ScenarioParser::read_robot(YamlMap m, sims::Scenario& sc) {
  m.pose("start", sc.start);
  note("Scenario.start", m, "start");
  sc.motion = choice<sims::MotionMode>(m, "motion",
                                       {{"waypoints", sims::MotionMode::kWaypoints},
                                        {"random_walk", sims::MotionMode::kRandomWalk},
                                        {"stationary", sims::MotionMode::kStationary}},
                                       sc.motion);
  {
    YamlMap l = m.child("limits");
    l.number("max_v", sc.limits.max_v);
    l.number("max_omega", sc.limits.max_omega);
    note("Scenario.limits.max_v", l, "max_v");
    note("Scenario.limits.max_omega", l, "max_omega");
    l.finish();
  }
  {
    YamlMap w = m.child("waypoints");
    auto& plan = sc.waypoints;
    const auto points = w.sequence("points");
    for (std::size_t i = 0; i < points.size(); ++i) {
      const auto xy =
          detail::yaml_xy(w.file(), points[i].first, points[i].second, w.line("points"));
      plan.waypoints.push_back({xy.first, xy.second});
      where_["Scenario.waypoints.waypoints[" + std::to_string(i) + "]"] = {
          points[i].second, detail::yaml_line(points[i].first)};
    }
    plan.controller =
        choice<sims::Controller>(w, "controller",
                                 {{"pure_pursuit", sims::Controller::kPurePursuit},
                                  {"turn_then_drive", sims::Controller::kTurnThenDrive}},
                                 plan.controller);
    w.number("lookahead", plan.lookahead);
    w.number("goal_tolerance", plan.goal_tolerance);
    w.number("heading_tolerance", plan.heading_tolerance);
    w.boolean("loop", plan.loop);
    for (const char* k : {"lookahead", "goal_tolerance", "heading_tolerance"}) {
      note(std::string("Scenario.waypoints.") + k, w, k);
    }
    w.finish();  // no points: the robot stands still (sims::WaypointFollower)
  }
  {
    YamlMap r = m.child("random_walk");
    auto& plan = sc.random_walk;
    r.number("clearance", plan.clearance);
    r.number("goal_tolerance", plan.goal_tolerance);
    r.number("min_leg", plan.min_leg);
    r.number("max_leg", plan.max_leg);
    r.integer("max_retries", plan.max_retries, 1, 1'000'000);
    if (!(plan.clearance >= 0.0)) r.fail("clearance", "must be >= 0 (m)");
    if (!(plan.goal_tolerance > 0.0)) r.fail("goal_tolerance", "must be > 0 (m)");
    if (!(plan.min_leg > 0.0 && plan.min_leg <= plan.max_leg)) {
      r.fail("min_leg", "need 0 < min_leg <= max_leg (m)");
    }
    r.finish();
  }
  m.finish();
}

void ScenarioParser::read_odometry(YamlMap m, sims::OdometrySettings& o) {
  note_map("Scenario.odometry", m);
  m.boolean("random_noise", o.random_noise);
  o.kind = choice<MotionModelKind>(m, "model",
                                   {{"differential_drive", MotionModelKind::kDifferentialDrive},
                                    {"omnidirectional", MotionModelKind::kOmnidirectional}},
                                   o.kind);
  {
    YamlMap a = m.child("alphas");
    a.number("a1", o.alphas.a1);
    a.number("a2", o.alphas.a2);
    a.number("a3", o.alphas.a3);
    a.number("a4", o.alphas.a4);
    a.number("a5", o.alphas.a5);
    note_map("Scenario.odometry.alphas", a);
    a.finish();
  }
  m.number("wheel_radius_bias", o.wheel_radius_bias);
  m.number("wheelbase_bias", o.wheelbase_bias);
  m.number("yaw_drift_per_metre", o.yaw_drift_per_metre);
  Pose2 origin;
  if (m.pose("origin", origin)) o.origin = origin;
  note("Scenario.odometry.origin", m, "origin");
  m.finish();
}

void ScenarioParser::read_kidnaps(YamlMap& root, sims::Scenario& sc) {
  const std::size_t line = root.line("kidnaps");
  const auto kidnaps = root.sequence("kidnaps");
  for (std::size_t i = 0; i < kidnaps.size(); ++i) {
    YamlMap k(root.file(), kidnaps[i].first, kidnaps[i].second, line);
    sims::KidnapEvent event;
    event.time = detail::yaml_number(k.file(), k.require("time"), k.field("time"), k.line("time"));
    event.pose = detail::yaml_pose(k.file(), k.require("pose"), k.field("pose"), k.line("pose"));
    if (event.time < 0.0) k.fail("time", "must be >= 0 (s)");
    k.finish();
    const std::string f = "Scenario.kidnaps[" + std::to_string(i) + "]";
    note_map(f, k);
    note(f + ".time", k, "time");
    note(f + ".pose", k, "pose");
    sc.kidnaps.push_back(event);
  }
}

void ScenarioParser::validation_failed(const std::string& message) const {
  // The longest registered sims field that prefixes the message names the YAML key.
  const std::pair<std::string, std::size_t>* best = nullptr;
  std::size_t best_len = 0;
  for (const auto& [sims_field, where] : where_) {
    if (sims_field.size() <= best_len || message.compare(0, sims_field.size(), sims_field) != 0) {
      continue;
    }
    const char next = message.size() > sims_field.size() ? message[sims_field.size()] : ':';
    if (next == ':' || next == '.' || next == ' ' || next == '[') {
      best = &where;
      best_len = sims_field.size();
    }
  }
  if (best == nullptr) throw FormatError(path_, 0, "scenario", message);
  std::string problem = message.substr(best_len);
  if (problem.rfind(": ", 0) == 0) problem.erase(0, 2);
  throw FormatError(path_, best->second, best->first, problem.empty() ? message : problem);
}

void ScenarioParser::check_size(const sims::Scenario& sc) const {
  // The simulation holds every scan in memory (and the log built from it once more), and
  // steps the robot at control_rate: both grow with duration.
  constexpr double kMaxScans = 1e7;
  constexpr double kMaxScanBytes = 2.0 * (1u << 30);
  constexpr double kMaxControlSteps = 1e8;
  const double scans = std::floor(sc.duration * sc.effective_scan_rate()) + 1.0;
  const double bytes = scans * (4.0 * sc.sensor.beam_count + sizeof(sims::SimulationRecord));
  const auto where = where_.find("Scenario.duration");
  const std::string field = where != where_.end() ? where->second.first : "duration";
  const std::size_t line = where != where_.end() ? where->second.second : 0;
  char buf[400];
  if (!(scans <= kMaxScans && bytes <= kMaxScanBytes)) {
    std::snprintf(buf, sizeof buf,
                  "%g s at scan_rate %g Hz asks for %.3g scans of %d beams (%.3g GB); the "
                  "limits are %.0g scans and %.0f GB: shorten the run or lower scan_rate",
                  sc.duration, sc.effective_scan_rate(), scans, sc.sensor.beam_count, bytes / 1e9,
                  kMaxScans, kMaxScanBytes / 1e9);
    throw FormatError(path_, line, field, buf);
  }
  if (!(sc.duration * sc.control_rate <= kMaxControlSteps)) {
    std::snprintf(buf, sizeof buf,
                  "%g s at control_rate %g Hz asks for %.3g control steps (limit %.0g): shorten "
                  "the run or lower control_rate",
                  sc.duration, sc.control_rate, sc.duration * sc.control_rate, kMaxControlSteps);
    throw FormatError(path_, line, field, buf);
  }
}

ScenarioFile ScenarioParser::parse(maps::OccupancyGrid& map) {
  ScenarioFile out;
  out.path = path_;
  out.name = fs::path(path_).stem().string();
  sims::Scenario& sc = out.scenario;

  YamlMap root(path_, detail::load_yaml_file(path_), "", 1);
  root.text("name", out.name);
  YAML::Node description = root.take("description");
  if (description) {
    if (!description.IsScalar()) root.fail("description", "expected text");
    out.description = description.Scalar();
  }
  std::string map_rel;
  (void)root.require("map");
  root.text("map", map_rel);
  const std::size_t map_line = root.line("map");
  out.map_path = resolve(map_rel);
  note("Scenario.map", root, "map");

  root.uint64("seed", sc.seed);
  root.number("duration", sc.duration);
  root.number("scan_rate", sc.scan_rate);
  root.number("control_rate", sc.control_rate);
  for (const char* k : {"duration", "scan_rate", "control_rate"}) {
    note(std::string("Scenario.") + k, root, k);
  }
  read_sensor(root.child("sensor"), sc);
  read_noise(root.child("noise"), sc.noise);
  {
    YamlMap r = root.child("raycast");
    sc.raycast.unknown =
        choice<sims::UnknownCellPolicy>(r, "unknown",
                                        {{"pass_through", sims::UnknownCellPolicy::kPassThrough},
                                         {"block", sims::UnknownCellPolicy::kBlock},
                                         {"absorb", sims::UnknownCellPolicy::kAbsorb}},
                                        sc.raycast.unknown);
    r.finish();
  }
  read_surfaces(root.child("surfaces"), sc.surfaces);
  read_obstacles(root.child("obstacles"), sc);
  read_robot(root.child("robot"), sc);
  read_odometry(root.child("odometry"), sc.odometry);
  read_kidnaps(root, sc);
  // A scenario is the world; filter settings read here would be silently ignored by every
  // command, so they are an error that says where they belong.
  if (root.has("filter")) {
    root.fail("filter",
              "a scenario describes the world only; put filter settings in the experiment "
              "file's `filter:` (pgmcl run) or a filter YAML (pgmcl localize --config)");
  }
  root.finish();

  try {
    map = maps::load_map(out.map_path);
  } catch (const std::exception& e) {
    throw FormatError(path_, map_line, "map", e.what());
  }
  load_labels(map, sc.surfaces);
  try {
    sc.validate(map);
  } catch (const std::invalid_argument& e) {
    validation_failed(e.what());
  }
  check_size(sc);
  return out;
}

}  // namespace detail::scenario

ScenarioFile read_scenario_file(const std::string& yaml_path, maps::OccupancyGrid& map) {
  try {
    return detail::scenario::ScenarioParser(yaml_path).parse(map);
  } catch (const ScenarioError&) {
    throw;
  } catch (const FormatError& e) {
    throw ScenarioError(e.file(), e.line(), e.field(), e.message());
  }
}

sims::Scenario load_scenario(const std::string& yaml_path, maps::OccupancyGrid* map_out) {
  maps::OccupancyGrid map;
  ScenarioFile f = read_scenario_file(yaml_path, map);
  if (map_out != nullptr) *map_out = std::move(map);
  return std::move(f.scenario);
}

}  // namespace pgmcl::io
