#include "yaml_reader.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <fstream>
#include <sstream>

#include "pgmcl/config/key_hints.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::io::detail {

namespace {

std::string describe(const YAML::Node& n) {
  if (!n || n.IsNull()) return "nothing";
  if (n.IsSequence()) return "a list";
  if (n.IsMap()) return "a mapping";
  return "\"" + n.Scalar() + "\"";
}

std::string join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

}  // namespace

std::size_t yaml_line(const YAML::Node& node) {
  if (!node) return 0;
  const YAML::Mark m = node.Mark();
  return m.is_null() ? 0 : static_cast<std::size_t>(m.line) + 1;
}

YAML::Node load_yaml_file(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw IoError(path + ": cannot open");
  std::ostringstream text;
  text << in.rdbuf();
  if (in.bad()) throw IoError(path + ": read failed");
  try {
    return YAML::Load(text.str());
  } catch (const YAML::Exception& e) {
    const std::size_t line = e.mark.is_null() ? 0 : static_cast<std::size_t>(e.mark.line) + 1;
    throw FormatError(path, line, "yaml", "not valid YAML: " + e.msg);
  }
}

void set_dotted(YAML::Node& doc, const std::string& key, const std::string& value) {
  const std::string source = "--set " + key + "=" + value;
  YAML::Node leaf;
  try {
    leaf = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw UsageError(source + ": value is not valid YAML: " + e.msg);
  }
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw UsageError(source + ": empty component in the dotted key");
    parts.push_back(part);
  }
  if (parts.empty()) throw UsageError(source + ": empty key");
  if (!doc || doc.IsNull()) doc = YAML::Node(YAML::NodeType::Map);
  if (!doc.IsMap()) throw UsageError(source + ": the file is not a mapping of keys");
  YAML::Node node = doc;
  for (std::size_t i = 0; i + 1 < parts.size(); ++i) {
    YAML::Node child = node[parts[i]];
    if (!child || child.IsNull()) {
      node[parts[i]] = YAML::Node(YAML::NodeType::Map);
      child = node[parts[i]];
    }
    if (!child.IsMap()) throw UsageError(source + ": " + parts[i] + " is not a mapping");
    node.reset(child);
  }
  node[parts.back()] = leaf;
}

YamlMap::YamlMap(std::string file, YAML::Node node, std::string path, std::size_t parent_line)
    : file_(std::move(file)), node_(std::move(node)), path_(std::move(path)) {
  line_ = node_ && !node_.IsNull() ? yaml_line(node_) : parent_line;
  if (line_ == 0) line_ = parent_line;
  if (!node_ || node_.IsNull()) {
    node_ = YAML::Node(YAML::NodeType::Map);
    return;
  }
  if (!node_.IsMap()) {
    throw FormatError(file_, line_, path_.empty() ? "yaml" : path_,
                      "expected a mapping of keys, got " + describe(node_));
  }
  std::set<std::string> seen;
  for (const auto& kv : node_) {
    if (!kv.first.IsScalar()) {
      throw FormatError(file_, yaml_line(kv.first), join(path_, "?"), "keys must be plain names");
    }
    if (!seen.insert(kv.first.Scalar()).second) {
      throw FormatError(file_, yaml_line(kv.first), join(path_, kv.first.Scalar()),
                        "duplicate key");
    }
  }
}

bool YamlMap::has(const char* key) const {
  return static_cast<bool>(node_[key]);
}

YAML::Node YamlMap::take(const char* key) {
  read_.insert(key);
  return node_[key];
}

std::string YamlMap::field(const std::string& key) const {
  return join(path_, key);
}

std::size_t YamlMap::line(const char* key) const {
  for (const auto& kv : node_) {
    if (kv.first.Scalar() != key) continue;
    // yaml-cpp marks an empty value at the next token: use the key's line then.
    if (kv.second && !kv.second.IsNull()) return yaml_line(kv.second);
    return yaml_line(kv.first);
  }
  return line_;
}

void YamlMap::fail(const char* key, const std::string& problem) const {
  throw FormatError(file_, line(key), field(key), problem);
}

void YamlMap::fail_at(const YAML::Node& node, const std::string& field,
                      const std::string& problem) const {
  const std::size_t l = node && !node.IsNull() ? yaml_line(node) : 0;
  throw FormatError(file_, l != 0 ? l : line_, field, problem);
}

YAML::Node YamlMap::require(const char* key) {
  if (!has(key)) throw FormatError(file_, line_, field(key), "missing required key");
  return take(key);
}

bool YamlMap::number(const char* key, double& out) {
  const YAML::Node n = take(key);
  if (!n) return false;
  out = yaml_number(file_, n, field(key), line(key));
  return true;
}

bool YamlMap::integer(const char* key, int& out, long long min, long long max) {
  const YAML::Node n = take(key);
  if (!n) return false;
  long long v = 0;
  const std::string text = n.IsScalar() ? n.Scalar() : std::string();
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (!n.IsScalar() || ec != std::errc() || ptr != text.data() + text.size() || text.empty()) {
    fail(key, "expected an integer, got " + describe(n));
  }
  if (v < min || v > max) {
    fail(key, "must be in [" + std::to_string(min) + ", " + std::to_string(max) + "], got " + text);
  }
  out = static_cast<int>(v);
  return true;
}

bool YamlMap::uint64(const char* key, std::uint64_t& out) {
  const YAML::Node n = take(key);
  if (!n) return false;
  std::uint64_t v = 0;
  const std::string text = n.IsScalar() ? n.Scalar() : std::string();
  const auto [ptr, ec] = std::from_chars(text.data(), text.data() + text.size(), v);
  if (!n.IsScalar() || ec != std::errc() || ptr != text.data() + text.size() || text.empty()) {
    fail(key, "expected a non-negative integer, got " + describe(n));
  }
  out = v;
  return true;
}

bool YamlMap::boolean(const char* key, bool& out) {
  const YAML::Node n = take(key);
  if (!n) return false;
  if (!n.IsScalar()) fail(key, "expected true or false, got " + describe(n));
  try {
    out = n.as<bool>();
  } catch (const YAML::Exception&) {
    fail(key, "expected true or false, got " + describe(n));
  }
  return true;
}

bool YamlMap::text(const char* key, std::string& out) {
  const YAML::Node n = take(key);
  if (!n) return false;
  if (!n.IsScalar() || n.Scalar().empty()) fail(key, "expected a name or text, got " + describe(n));
  out = n.Scalar();
  return true;
}

bool YamlMap::pose(const char* key, Pose2& out) {
  const YAML::Node n = take(key);
  if (!n) return false;
  out = yaml_pose(file_, n, field(key), line(key));
  return true;
}

YamlMap YamlMap::child(const char* key) {
  const YAML::Node n = take(key);
  YamlMap m(file_, n, field(key), line(key));
  m.hint_ = hint_;
  return m;
}

std::vector<std::pair<YAML::Node, std::string>> YamlMap::sequence(const char* key) {
  const YAML::Node n = take(key);
  std::vector<std::pair<YAML::Node, std::string>> out;
  if (!n || n.IsNull()) return out;
  if (!n.IsSequence()) fail(key, "expected a list, got " + describe(n));
  for (std::size_t i = 0; i < n.size(); ++i) {
    out.emplace_back(n[i], field(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

void YamlMap::finish() const {
  for (const auto& kv : node_) {
    const std::string& key = kv.first.Scalar();
    if (read_.count(key) != 0) continue;
    std::string problem = "unknown key";
    const std::string hint = hint_ ? hint_(field(key)) : std::string();
    if (!hint.empty()) {
      problem += ": " + hint;
    } else if (const std::string near = closest_key(key); !near.empty()) {
      problem += " (did you mean '" + near + "'?)";
    }
    if (!read_.empty()) {
      std::string keys;
      for (const std::string& k : read_) keys += (keys.empty() ? "" : ", ") + k;
      problem +=
          "; keys " + (path_.empty() ? std::string("at the top") : "under " + path_) + ": " + keys;
    }
    throw FormatError(file_, yaml_line(kv.first), field(key), problem);
  }
}

std::string YamlMap::closest_key(const std::string& key) const {
  return nearest_key(key, {read_.begin(), read_.end()});
}

double yaml_number(const std::string& file, const YAML::Node& n, const std::string& field,
                   std::size_t fallback_line) {
  const std::size_t l = n && !n.IsNull() && yaml_line(n) != 0 ? yaml_line(n) : fallback_line;
  if (!n || !n.IsScalar())
    throw FormatError(file, l, field, "expected a number, got " + describe(n));
  double v = 0.0;
  try {
    v = n.as<double>();
  } catch (const YAML::Exception&) {
    throw FormatError(file, l, field, "expected a number, got " + describe(n));
  }
  if (!std::isfinite(v)) throw FormatError(file, l, field, "expected a finite number");
  return v;
}

Pose2 yaml_pose(const std::string& file, const YAML::Node& n, const std::string& field,
                std::size_t fallback_line) {
  const std::size_t l = n && yaml_line(n) != 0 ? yaml_line(n) : fallback_line;
  if (!n || !n.IsSequence() || n.size() != 3) {
    throw FormatError(file, l, field, "expected [x, y, theta] (m, m, rad), got " + describe(n));
  }
  return {yaml_number(file, n[0], field + "[0]", l), yaml_number(file, n[1], field + "[1]", l),
          wrap_angle(yaml_number(file, n[2], field + "[2]", l))};
}

std::pair<double, double> yaml_xy(const std::string& file, const YAML::Node& n,
                                  const std::string& field, std::size_t fallback_line) {
  const std::size_t l = n && yaml_line(n) != 0 ? yaml_line(n) : fallback_line;
  if (!n || !n.IsSequence() || n.size() != 2) {
    throw FormatError(file, l, field, "expected [x, y] (m), got " + describe(n));
  }
  return {yaml_number(file, n[0], field + "[0]", l), yaml_number(file, n[1], field + "[1]", l)};
}

}  // namespace pgmcl::io::detail
