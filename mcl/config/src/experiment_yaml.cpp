#include "pgmcl/config/experiment_yaml.hpp"

#include <filesystem>

#include "config_yaml_detail.hpp"
#include "pgmcl/io/values.hpp"
#include "yaml_reader.hpp"

namespace pgmcl::io {
namespace {

namespace fs = std::filesystem;
using detail::YamlMap;

std::string resolve(const fs::path& base, const std::string& p) {
  if (p.empty()) return p;
  const fs::path path(p);
  return path.is_absolute() ? p : (base / path).lexically_normal().string();
}

ExperimentInit read_init(const std::string& file, const YAML::Node& n, const std::string& field,
                         std::size_t line) {
  ExperimentInit init;
  if (!n || n.IsNull()) return init;
  if (n.IsScalar()) {
    if (n.Scalar() == "global") {
      init.kind = ExperimentInit::Kind::kGlobal;
    } else if (n.Scalar() == "truth") {
      init.kind = ExperimentInit::Kind::kTruth;
    } else {
      throw ConfigError(
          file, detail::yaml_line(n) ? detail::yaml_line(n) : line, field,
          "expected global, truth, [x, y, theta] or {pose, sigma}, got \"" + n.Scalar() + "\"");
    }
    return init;
  }
  if (n.IsSequence()) {
    init.kind = ExperimentInit::Kind::kPose;
    init.pose = detail::yaml_pose(file, n, field, line);
    return init;
  }
  YamlMap m(file, n, field, line);
  if (!m.pose("pose", init.pose)) m.fail("pose", "missing required key");
  init.kind = ExperimentInit::Kind::kPose;
  if (m.has("sigma")) {
    const auto items = m.sequence("sigma");
    if (items.size() != 3) m.fail("sigma", "expected [sx, sy, stheta] (m, m, rad)");
    double s[3];
    for (int i = 0; i < 3; ++i) {
      s[i] = detail::yaml_number(file, items[i].first, items[i].second, m.line("sigma"));
      if (!(s[i] > 0.0)) m.fail("sigma", "every sigma must be > 0");
    }
    init.sigma_x = s[0];
    init.sigma_y = s[1];
    init.sigma_theta = s[2];
  }
  m.finish();
  return init;
}

void read_file(const std::string& path, Experiment& e) {
  const fs::path base = fs::path(path).parent_path();
  const YAML::Node doc = detail::load_yaml_file(path);
  YamlMap root(path, doc, "");
  e.name = fs::path(path).stem().string();
  root.text("name", e.name);
  if (root.text("map", e.map)) e.map = resolve(base, e.map);
  {
    YamlMap d = root.child("data");
    if (d.text("log", e.log)) e.log = resolve(base, e.log);
    if (d.text("scenario", e.scenario)) e.scenario = resolve(base, e.scenario);
    if (d.text("truth", e.truth)) e.truth = resolve(base, e.truth);
    if (d.text("relations", e.relations)) e.relations = resolve(base, e.relations);
    d.number("time_offset", e.time_offset);
    if (e.log.empty() == e.scenario.empty()) {
      root.fail("data", "needs exactly one of data.log and data.scenario");
    }
    d.finish();
  }
  if (e.map.empty() && e.scenario.empty()) root.fail("map", "missing required key");
  e.init = read_init(path, root.take("init"), root.field("init"), root.line("init"));
  const YAML::Node f = root.take("filter");
  if (f && f.IsScalar()) {
    read_localizer_config(resolve(base, f.Scalar()), e.filter);
  } else {
    detail::read_localizer_node(path, f, "filter", e.filter);
  }
  if (root.text("out", e.out)) e.out = resolve(base, e.out);
  root.finish();
}

void apply_set(const std::string& assignment, Experiment& e) {
  const auto [key, value] = parse_key_value(assignment, "--set");
  if (key.rfind("filter.", 0) == 0) {
    try {
      apply_localizer_override(key.substr(7), value, e.filter);
    } catch (const ConfigError& err) {
      throw UsageError("--set " + assignment + ": filter." + err.field() + ": " + err.message());
    }
    return;
  }
  if (key == "init") {
    YAML::Node n;
    try {
      n = YAML::Load(value);
      e.init = read_init("--set " + assignment, n, "init", 0);
    } catch (const YAML::Exception& ex) {
      throw UsageError("--set " + assignment + ": not valid YAML: " + ex.msg);
    } catch (const FormatError& err) {
      throw UsageError("--set " + assignment + ": " + err.message());
    }
    return;
  }
  if (key == "data.time_offset") {
    e.time_offset = parse_number(value, "--set " + key);
    return;
  }
  std::string* target = nullptr;
  if (key == "name") target = &e.name;
  if (key == "map") target = &e.map;
  if (key == "out") target = &e.out;
  if (key == "data.log") {
    target = &e.log;
    e.scenario.clear();
  }
  if (key == "data.scenario") {
    target = &e.scenario;
    e.log.clear();
  }
  if (key == "data.truth") target = &e.truth;
  if (key == "data.relations") target = &e.relations;
  if (target == nullptr) {
    throw UsageError("--set " + assignment +
                     ": unknown experiment key (filter.*, name, map, out, init, data.log, "
                     "data.scenario, data.truth, data.relations, data.time_offset)");
  }
  *target = value;
}

}  // namespace

Experiment read_experiment(const std::string& path, const std::vector<std::string>& sets) {
  Experiment e;
  e.path = path;
  try {
    read_file(path, e);
  } catch (const ConfigError&) {
    throw;
  } catch (const FormatError& err) {
    throw ConfigError(err.file(), err.line(), err.field(), err.message());
  }
  for (const auto& s : sets) apply_set(s, e);
  if (e.out.empty()) e.out = (fs::path("pgmcl-out") / e.name).string();
  return e;
}

}  // namespace pgmcl::io
