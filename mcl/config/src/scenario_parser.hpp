#pragma once
// Private to the scenario adapter (scenario_yaml*.cpp): the parser class and its helpers.

#include <initializer_list>
#include <map>
#include <stdexcept>
#include <string>
#include <utility>

#include "pgmcl/config/scenario_yaml.hpp"
#include "yaml_reader.hpp"

namespace pgmcl::io::detail::scenario {

template <class E>
E choice(YamlMap& m, const char* key, std::initializer_list<std::pair<const char*, E>> options,
         E fallback) {
  std::string name;
  if (!m.text(key, name)) return fallback;
  std::string known;
  for (const auto& [text, value] : options) {
    if (name == text) return value;
    known += (known.empty() ? "" : ", ") + std::string(text);
  }
  m.fail(key, "unknown value '" + name + "' (expected one of: " + known + ")");
}

/// Reads a sims struct and reports its own validate() failures at the mapping's line.
template <class F>
void checked(const YamlMap& m, F&& validate) {
  try {
    validate();
  } catch (const std::invalid_argument& e) {
    throw FormatError(m.file(), m.line(), m.path(), e.what());
  }
}

class ScenarioParser {
 public:
  explicit ScenarioParser(std::string path) : path_(std::move(path)) {}

  ScenarioFile parse(maps::OccupancyGrid& map);

 private:
  // Where each sims field came from, keyed as sims names it in validate() messages
  // ("Scenario.start", "SurfaceLayout.regions[1]"), so grid-dependent checks are reported
  // at the YAML key they concern.
  void note(const std::string& sims_field, const YamlMap& m, const char* key) {
    where_[sims_field] = {m.field(key), m.line(key)};
  }
  void note_map(const std::string& sims_field, const YamlMap& m) {
    where_[sims_field] = {m.path(), m.line()};
  }
  [[noreturn]] void validation_failed(const std::string& message) const;
  /// Refuses a duration that asks for more scans or control steps than memory and time allow.
  void check_size(const sims::Scenario& sc) const;
  [[nodiscard]] std::string resolve(const std::string& relative) const;

  void read_sensor(YamlMap m, sims::Scenario& sc);
  void read_noise(YamlMap m, sims::BeamNoise& n);
  void read_surfaces(YamlMap m, sims::SurfaceLayout& s);
  void read_path(YamlMap m, sims::ObstaclePath& p);
  void read_obstacles(YamlMap m, sims::Scenario& sc);
  void read_robot(YamlMap m, sims::Scenario& sc);
  void read_odometry(YamlMap m, sims::OdometrySettings& o);
  void read_kidnaps(YamlMap& root, sims::Scenario& sc);
  void load_labels(const maps::OccupancyGrid& map, sims::SurfaceLayout& s) const;

  std::string path_;
  std::map<std::string, std::pair<std::string, std::size_t>> where_;
  std::string labels_path_;
  std::size_t labels_line_ = 0;
};

}  // namespace pgmcl::io::detail::scenario
