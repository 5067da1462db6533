// map_server's YAML format (nav2_map_server map_io.cpp: loadMapYaml / saveMapToFile), with
// every error naming the file, the line (yaml-cpp Marks are 0-based) and the key.

#include <yaml-cpp/yaml.h>

#include <array>
#include <cmath>
#include <filesystem>
#include <map>
#include <set>
#include <string>
#include <vector>

#include "image_codec.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl::maps {

namespace {

namespace fs = std::filesystem;

constexpr std::array<const char*, 7> kKnownKeys = {
    "image", "resolution", "origin", "occupied_thresh", "free_thresh", "negate", "mode"};

int line_of(const YAML::Node& node) {
  const YAML::Mark m = node.Mark();
  return m.is_null() ? 0 : m.line + 1;
}

class YamlReader {
 public:
  YamlReader(const std::string& file, const YAML::Node& root) : file_(file), root_(root) {
    for (const auto& kv : root_) {
      if (kv.first.IsScalar()) key_lines_.emplace(kv.first.Scalar(), line_of(kv.first));
    }
  }

  /// Throws for `field`; the line is the value's, or the key's when the value is empty
  /// (yaml-cpp marks an empty value at the next token).
  [[noreturn]] void fail(const YAML::Node& node, const std::string& field,
                         const std::string& problem) const {
    int line = 0;
    if (node && !node.IsNull()) {
      line = line_of(node);
    } else if (const auto it = key_lines_.find(field.substr(0, field.find('[')));
               it != key_lines_.end()) {
      line = it->second;
    }
    throw MapError(file_, line, field, problem);
  }

  /// The value of `key`, or an undefined node; a present but empty value is an error.
  YAML::Node find(const char* key, bool required) const {
    YAML::Node n = root_[key];
    if (!n) {
      if (required) throw MapError(file_, 0, key, "missing required key");
      return n;
    }
    if (!n.IsScalar() && !n.IsSequence()) fail(n, key, "expected a value");
    return n;
  }

  std::string scalar_text(const YAML::Node& n, const std::string& field) const {
    if (!n.IsScalar()) fail(n, field, "expected a single value, not a list or mapping");
    return n.Scalar();
  }

  double number(const YAML::Node& n, const std::string& field) const {
    const std::string text = scalar_text(n, field);
    double v = 0.0;
    try {
      v = n.as<double>();
    } catch (const YAML::Exception&) {
      fail(n, field, "expected a number, got \"" + text + "\"");
    }
    if (!std::isfinite(v)) fail(n, field, "expected a finite number, got \"" + text + "\"");
    return v;
  }

  bool flag(const YAML::Node& n, const std::string& field) const {
    const std::string text = scalar_text(n, field);
    // map_server reads negate as an int, nav2 also as a bool.
    if (text == "0") return false;
    if (text == "1") return true;
    try {
      return n.as<bool>();
    } catch (const YAML::Exception&) {
      fail(n, field, "expected 0, 1, true or false, got \"" + text + "\"");
    }
  }

  Pose2 pose(const YAML::Node& n, const std::string& field) const {
    if (!n.IsSequence() || n.size() != 3) {
      const std::string got =
          n.IsSequence() ? std::to_string(n.size()) + " elements" : "\"" + n.Scalar() + "\"";
      fail(n, field, "expected a list [x, y, yaw] of 3 numbers, got " + got);
    }
    return {number(n[0], field + "[0] (x)"), number(n[1], field + "[1] (y)"),
            number(n[2], field + "[2] (yaw)")};
  }

 private:
  const std::string& file_;
  const YAML::Node& root_;
  std::map<std::string, int> key_lines_;
};

}  // namespace

namespace {

MapMetadata parse_map_yaml(const std::string& yaml_path, MapLoadReport* report, int* image_line) {
  const detail::Bytes bytes = detail::read_file_bytes(yaml_path, "map YAML file");
  if (detail::is_pnm(bytes) || detail::is_png(bytes) || detail::is_gzip(bytes)) {
    throw MapError(yaml_path, 0, "yaml",
                   "is an image (or gzip), not a map YAML: give the .yaml file that names it "
                   "(image:, resolution:, origin:)");
  }
  YAML::Node root;
  try {
    root = YAML::Load(std::string(bytes.begin(), bytes.end()));
  } catch (const YAML::Exception& e) {
    throw MapError(yaml_path, e.mark.is_null() ? 0 : e.mark.line + 1, "yaml",
                   "not valid YAML: " + e.msg);
  }
  if (!root.IsMap()) {
    throw MapError(yaml_path, line_of(root), "yaml",
                   "expected a mapping of map_server keys (image, resolution, origin, ...)");
  }
  const YamlReader r(yaml_path, root);

  std::set<std::string> seen;
  std::vector<std::string> warnings;
  for (const auto& kv : root) {
    const std::string key = kv.first.IsScalar() ? kv.first.Scalar() : "<non-scalar key>";
    if (!seen.insert(key).second) r.fail(kv.first, key, "duplicate key");
    bool known = false;
    for (const char* k : kKnownKeys) known = known || key == k;
    if (!known) {
      warnings.push_back(yaml_path + ":" + std::to_string(line_of(kv.first)) + ": unknown key '" +
                         key + "' ignored");
    }
  }

  MapMetadata meta;
  detail::MetadataLines lines;
  const YAML::Node image = r.find("image", true);
  meta.image = r.scalar_text(image, "image");
  if (meta.image.empty()) r.fail(image, "image", "must name an image file");
  if (image_line != nullptr) *image_line = line_of(image);

  const YAML::Node res = r.find("resolution", true);
  meta.resolution = r.number(res, "resolution");
  lines.resolution = line_of(res);

  const YAML::Node origin = r.find("origin", true);
  meta.origin = r.pose(origin, "origin");
  lines.origin = line_of(origin);

  // map_server requires these three; nav2's launch files always give them. Missing ones
  // take map_server's documented defaults, with a warning.
  const auto defaulted = [&](const char* key, const std::string& value) {
    warnings.push_back(yaml_path + ": '" + key + "' not set, using map_server's default " + value);
  };
  if (const YAML::Node n = r.find("occupied_thresh", false)) {
    meta.occupied_thresh = r.number(n, "occupied_thresh");
    lines.occupied_thresh = line_of(n);
  } else {
    defaulted("occupied_thresh", detail::format_double(meta.occupied_thresh));
  }
  if (const YAML::Node n = r.find("free_thresh", false)) {
    meta.free_thresh = r.number(n, "free_thresh");
    lines.free_thresh = line_of(n);
  } else {
    defaulted("free_thresh", detail::format_double(meta.free_thresh));
  }
  if (const YAML::Node n = r.find("negate", false)) {
    meta.negate = r.flag(n, "negate");
  } else {
    defaulted("negate", "0");
  }
  if (const YAML::Node n = r.find("mode", false)) {
    const std::string text = r.scalar_text(n, "mode");
    try {
      meta.mode = map_mode_from_string(text);
    } catch (const std::invalid_argument& e) {
      r.fail(n, "mode", e.what());
    }
  }
  detail::validate_metadata(meta, yaml_path, lines);

  if (report != nullptr) {
    report->metadata = meta;
    report->warnings.insert(report->warnings.end(), warnings.begin(), warnings.end());
  }
  return meta;
}

}  // namespace

MapMetadata read_map_yaml(const std::string& yaml_path, MapLoadReport* report) {
  return parse_map_yaml(yaml_path, report, nullptr);
}

OccupancyGrid load_map(const std::string& yaml_path, MapLoadReport* report) {
  MapLoadReport local;
  MapLoadReport& rep = report != nullptr ? *report : local;
  int image_line = 0;
  const MapMetadata meta = parse_map_yaml(yaml_path, &rep, &image_line);

  fs::path image = meta.image;
  if (image.is_relative()) image = fs::path(yaml_path).parent_path() / image;
  rep.image_path = image.string();
  try {
    return load_map_image(rep.image_path, meta);
  } catch (const MapError& e) {
    // Point back at the YAML that named the image.
    throw MapError(
        e.file(), e.line(), e.field().empty() ? "image" : e.field(),
        e.problem() + " (image named in " + yaml_path + ":" + std::to_string(image_line) + ")");
  }
}

std::string map_yaml_text(const OccupancyGrid& grid, const std::string& image_name, MapMode mode,
                          const std::string& yaml_path) {
  MapMetadata meta;
  meta.resolution = grid.resolution();
  meta.origin = grid.origin();
  detail::validate_metadata(meta, yaml_path);
  // Keys and order as nav2's map_saver writes them.
  YAML::Emitter out;
  out << YAML::BeginMap;
  out << YAML::Key << "image" << YAML::Value << image_name;
  out << YAML::Key << "mode" << YAML::Value << to_string(mode);
  out << YAML::Key << "resolution" << YAML::Value << detail::format_double(grid.resolution());
  out << YAML::Key << "origin" << YAML::Value << YAML::Flow << YAML::BeginSeq
      << detail::format_double(grid.origin().x) << detail::format_double(grid.origin().y)
      << detail::format_double(grid.origin().theta) << YAML::EndSeq;
  out << YAML::Key << "negate" << YAML::Value << 0;
  out << YAML::Key << "occupied_thresh" << YAML::Value << "0.65";
  out << YAML::Key << "free_thresh" << YAML::Value << "0.196";
  out << YAML::EndMap;
  if (!out.good()) throw MapError(yaml_path, 0, "yaml", "emitter error: " + out.GetLastError());
  return std::string(out.c_str()) + "\n";
}

void save_map(const OccupancyGrid& grid, const std::string& yaml_path,
              const std::string& image_name, MapMode mode) {
  fs::path yaml(yaml_path);
  std::string name = image_name;
  if (name.empty()) name = yaml.stem().string() + (mode == MapMode::kScale ? ".png" : ".pgm");
  const std::string text = map_yaml_text(grid, name, mode, yaml_path);
  const fs::path image = fs::path(name).is_absolute() ? fs::path(name) : yaml.parent_path() / name;
  save_map_image(grid, image.string(), mode);
  detail::write_file_bytes(yaml_path, detail::Bytes(text.begin(), text.end()));
}

}  // namespace pgmcl::maps
