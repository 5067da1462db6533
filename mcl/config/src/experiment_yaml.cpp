#include "pgmcl/config/experiment_yaml.hpp"

#include <filesystem>
#include <map>
#include <sstream>

#include "config_yaml_detail.hpp"
#include "pgmcl/config/key_hints.hpp"
#include "pgmcl/io/file_kind.hpp"
#include "pgmcl/io/values.hpp"
#include "yaml_reader.hpp"

namespace pgmcl::io {
namespace {

namespace fs = std::filesystem;
using detail::YamlMap;

/// Where an input path of the experiment came from, for messages: the key's line and the
/// text as written in the file, or the --set that replaced it.
struct PathOrigin {
  std::size_t line = 0;
  std::string written;
  std::string set;  ///< "--set data.log=..." when an override gave it
};
using PathOrigins = std::map<std::string, PathOrigin>;

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
  const bool has_pose = m.pose("pose", init.pose);
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
  m.finish();  // a misspelt key is named before the missing one
  if (!has_pose) m.fail("pose", "missing required key");
  return init;
}

/// Reads the path at `key` of `m` (if present), resolved against `base`, noting its origin.
void read_path(YamlMap& m, const char* key, const fs::path& base, std::string& out,
               PathOrigins& origins) {
  if (!m.text(key, out)) return;
  origins[m.field(key)] = {m.line(key), out, ""};
  out = resolve(base, out);
}

/// "'PATH' does not exist (written 'TEXT', resolved against FROM)". Appended piecewise:
/// GCC 12 misreports "a" + b + "c" chains (-Wrestrict).
std::string missing(const std::string& path, const std::string& written, const std::string& from) {
  std::string m = "'";
  m.append(path).append("' does not exist (written '").append(written);
  m.append("', resolved against ").append(from).append(")");
  return m;
}

/// Every input path must exist and be of its kind, before any work: the message names the
/// experiment file, the key and how the path was resolved.
void check_inputs(const Experiment& e, const PathOrigins& origins) {
  const std::string folder = fs::path(e.path).parent_path().string();
  auto check = [&](const std::string& key, const std::string& path,
                   std::initializer_list<FileKind> kinds, const char* wanted) {
    if (path.empty()) return;
    const auto it = origins.find(key);
    const PathOrigin o = it != origins.end() ? it->second : PathOrigin{};
    if (!fs::exists(path)) {
      if (!o.set.empty()) {
        std::string m = o.set;
        m.append(": '").append(path).append(
            "' does not exist (paths on the command line are "
            "relative to the current directory)");
        throw UsageError(m);
      }
      std::string from = "the current directory (the experiment's folder)";
      if (!folder.empty()) from = std::string("the experiment's folder '").append(folder) + "'";
      throw ConfigError(e.path, o.line, key, missing(path, o.written, from));
    }
    std::string option = o.set;
    if (option.empty()) {
      option = e.path;
      if (o.line) option.append(":").append(std::to_string(o.line));
      option.append(": ").append(key);
    }
    expect_file_kind(path, option, kinds, wanted);
  };
  check("map", e.map, {FileKind::kMapYaml, FileKind::kOtherYaml},
        "a map YAML (map_server: image, resolution, origin)");
  check("data.log", e.log, {FileKind::kCarmenLog}, "a CARMEN log");
  check("data.scenario", e.scenario, {FileKind::kScenario, FileKind::kOtherYaml},
        "a scenario (configs/scenarios/)");
  check("data.truth", e.truth, {FileKind::kNumberTable, FileKind::kCarmenLog},
        "a TUM trajectory or a corrected CARMEN log");
  check("data.relations", e.relations, {FileKind::kNumberTable},
        "a relations file (t1 t2 x y z roll pitch yaw per line)");
}

void read_file(const std::string& path, Experiment& e, PathOrigins& origins) {
  const fs::path base = fs::path(path).parent_path();
  const YAML::Node doc = detail::load_yaml_file(path);
  YamlMap root(path, doc, "");
  e.name = fs::path(path).stem().string();
  root.text("name", e.name);
  read_path(root, "map", base, e.map, origins);
  {
    YamlMap d = root.child("data");
    read_path(d, "log", base, e.log, origins);
    read_path(d, "scenario", base, e.scenario, origins);
    read_path(d, "truth", base, e.truth, origins);
    read_path(d, "relations", base, e.relations, origins);
    d.number("time_offset", e.time_offset);
    d.finish();
  }
  e.init = read_init(path, root.take("init"), root.field("init"), root.line("init"));
  const YAML::Node f = root.take("filter");
  if (f && f.IsScalar()) {
    const std::string file = resolve(base, f.Scalar());
    if (!fs::exists(file)) {
      root.fail("filter", missing(file, f.Scalar(),
                                  std::string("the experiment's folder '") + base.string() + "'"));
    }
    std::string option = path;
    option.append(":").append(std::to_string(root.line("filter"))).append(": filter");
    expect_file_kind(file, option, {FileKind::kFilterYaml, FileKind::kOtherYaml},
                     "a filter configuration (configs/filters/)");
    read_localizer_config(file, e.filter);
  } else {
    detail::read_localizer_node(path, f, "filter", e.filter);
  }
  if (root.text("out", e.out)) e.out = resolve(base, e.out);
  // Unknown keys first: `mapp:` is a misspelt map, not a missing one.
  root.finish();
  if (e.log.empty() == e.scenario.empty()) {
    root.fail("data", "needs exactly one of data.log and data.scenario");
  }
  if (e.map.empty() && e.scenario.empty()) root.fail("map", "missing required key");
}

/// "1,2,3" (x, y, theta) or "1,2,3,0.1,0.1,0.05" (and sigmas), as --init takes them, in
/// the YAML form init: reads; anything else unchanged.
std::string init_value(const std::string& value) {
  if (value.find(',') == std::string::npos || value.find_first_of("[{") != std::string::npos)
    return value;
  std::vector<std::string> parts;
  std::stringstream ss(value);
  for (std::string p; std::getline(ss, p, ',');) parts.push_back(p);
  auto list = [&](std::size_t from) {
    return "[" + parts[from] + ", " + parts[from + 1] + ", " + parts[from + 2] + "]";
  };
  if (parts.size() == 3) return list(0);
  if (parts.size() == 6) return "{pose: " + list(0) + ", sigma: " + list(3) + "}";
  return value;
}

const std::vector<std::string> kExperimentKeys = {"name",
                                                  "map",
                                                  "out",
                                                  "init",
                                                  "data.log",
                                                  "data.scenario",
                                                  "data.truth",
                                                  "data.relations",
                                                  "data.time_offset"};

/// The error for a --set key that is neither an experiment key nor a filter key: the
/// filter's message, with the nearest of either kind of key when it has no hint of its own.
std::string unknown_set_key(const std::string& key, const ConfigError& filter_error) {
  std::string message = filter_error.what();
  const std::string unknown = ": unknown key";
  const std::size_t at = message.find(unknown);
  if (at != std::string::npos && message.compare(at + unknown.size(), 1, ";") == 0) {
    std::vector<std::string> keys = kExperimentKeys;
    const std::vector<std::string> filter_keys = localizer_config_keys();
    keys.insert(keys.end(), filter_keys.begin(), filter_keys.end());
    if (const std::string near = nearest_key(key, keys); !near.empty()) {
      message.insert(at + unknown.size(), " (did you mean '" + near + "'?)");
    }
  }
  std::string list;
  for (const std::string& k : kExperimentKeys) list += (list.empty() ? "" : ", ") + k;
  return message + "; experiment keys: " + list;
}

void apply_set(const std::string& assignment, Experiment& e, PathOrigins& origins,
               std::vector<std::string>& notes) {
  const auto [key, value] = parse_key_value(assignment, "--set");
  if (key == "init") {
    YAML::Node n;
    try {
      n = YAML::Load(init_value(value));
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
  if (target != nullptr) {
    if (key != "name" && key != "out") origins[key] = {0, value, "--set " + assignment};
    *target = value;
    return;
  }
  // Anything else is a filter key, with the same path as `pgmcl localize --set`.
  try {
    apply_localizer_override(key, value, e.filter);
    return;
  } catch (const ConfigError& err) {
    // The old spelling: the filter key under the experiment's filter: block.
    if (key.rfind("filter.", 0) == 0) {
      try {
        apply_localizer_override(key.substr(7), value, e.filter);
        notes.push_back("--set " + assignment + ": the experiment's filter keys have the same " +
                        "path as pgmcl localize's now: write --set " + key.substr(7) + "=" + value +
                        " (the old filter." + key.substr(7) + " works for one release)");
        return;
      } catch (const ConfigError&) {
      }
    }
    throw UsageError(unknown_set_key(key, err));
  }
}

}  // namespace

Experiment read_experiment(const std::string& path, const std::vector<std::string>& sets) {
  Experiment e;
  e.path = path;
  PathOrigins origins;
  try {
    read_file(path, e, origins);
  } catch (const ConfigError&) {
    throw;
  } catch (const FormatError& err) {
    throw ConfigError(err.file(), err.line(), err.field(), err.message());
  }
  for (const auto& s : sets) apply_set(s, e, origins, e.notes);
  check_inputs(e, origins);
  if (e.out.empty()) e.out = (fs::path("pgmcl-out") / e.name).string();
  return e;
}

}  // namespace pgmcl::io
