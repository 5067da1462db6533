#include "pgmcl/config/config_yaml.hpp"

#include <algorithm>
#include <cstdint>
#include <cstdio>
#include <map>
#include <sstream>
#include <stdexcept>
#include <type_traits>
#include <utility>
#include <vector>

#include "config_yaml_detail.hpp"
#include "pgmcl/io/values.hpp"
#include "pgmcl/mcl/config_schema.hpp"
#include "yaml_reader.hpp"

namespace pgmcl::io {
namespace {

using detail::YamlMap;

namespace schema = pgmcl::config_schema;

/// "a, b, c": the names written for an enumeration (aliases left out).
template <class E, std::size_t N>
std::string canonical_names(const std::array<schema::EnumName<E>, N>& names) {
  std::string out;
  for (const auto& n : names) {
    if (schema::name_of(n.value, names) != n.name) continue;
    out += (out.empty() ? "" : ", ") + std::string(n.name);
  }
  return out;
}

/// The line of `field` or of its closest enclosing key that was written.
std::size_t line_of(const std::string& field, const std::map<std::string, std::size_t>& lines,
                    std::size_t fallback) {
  for (std::string key = field; !key.empty();) {
    const auto it = lines.find(key);
    if (it != lines.end()) return it->second;
    const std::size_t dot = key.rfind('.');
    key = dot == std::string::npos ? std::string() : key.substr(0, dot);
  }
  return fallback;
}

/// Reads every field the schema describes from a YAML mapping tree, remembering the line of
/// each dotted key so that a validate() failure is reported where the value was written.
/// Absent keys keep the struct's values; unread keys are errors (YamlMap::finish).
class ReadVisitor {
 public:
  ReadVisitor(YamlMap& root, std::map<std::string, std::size_t>& lines)
      : maps_{&root}, lines_(&lines) {}

  template <class Body>
  void section(const char* name, Body&& body) {
    YamlMap child = top().child(name);
    maps_.push_back(&child);
    body();
    maps_.pop_back();
    child.finish();
  }
  void number(const schema::Field& f, double& v, const schema::Bounds&) {
    note(f.name, top().number(f.name, v));
  }
  void flag(const schema::Field& f, bool& v) { note(f.name, top().boolean(f.name, v)); }
  template <class T>
  void integer(const schema::Field& f, T& v, const schema::IntRange& r) {
    if constexpr (std::is_signed_v<T>) {
      int i = static_cast<int>(v);
      const auto hi = static_cast<long long>(std::min<std::uint64_t>(r.hi, INT32_MAX));
      if (top().integer(f.name, i, r.lo, hi)) {
        v = static_cast<T>(i);
        note(f.name, true);
      }
    } else {
      std::uint64_t u = v;
      if (top().uint64(f.name, u)) {
        if (std::cmp_less(u, r.lo) || u > r.hi)
          top().fail(f.name, "must be " + r.text() + ", got " + std::to_string(u) + r.memory(u));
        v = static_cast<T>(u);
        note(f.name, true);
      }
    }
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E& v, const std::array<schema::EnumName<E>, N>& names) {
    std::string text;
    if (!top().text(f.name, text)) return;
    for (const auto& n : names) {
      if (text == n.name) {
        v = n.value;
        note(f.name, true);
        return;
      }
    }
    top().fail(f.name, "expected one of " + canonical_names(names) + ", got \"" + text + "\"");
  }
  void rule(const char*, bool, const char*) const {}  // validate() checks after reading

 private:
  YamlMap& top() { return *maps_.back(); }
  void note(const char* key, bool present) {
    if (present) (*lines_)[top().field(key)] = top().line(key);
  }
  std::vector<YamlMap*> maps_;
  std::map<std::string, std::size_t>* lines_;
};

/// Writes every field in the schema's order.
class WriteVisitor {
 public:
  explicit WriteVisitor(YAML::Emitter& out) : out_(&out) {}
  template <class Body>
  void section(const char* name, Body&& body) {
    *out_ << YAML::Key << name << YAML::Value << YAML::BeginMap;
    body();
    *out_ << YAML::EndMap;
  }
  void number(const schema::Field& f, double v, const schema::Bounds&) { put(f, v); }
  void flag(const schema::Field& f, bool v) { put(f, v); }
  template <class T>
  void integer(const schema::Field& f, T v, const schema::IntRange&) {
    if constexpr (std::is_signed_v<T>)
      put(f, static_cast<long long>(v));
    else
      put(f, static_cast<unsigned long long>(v));
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E v, const std::array<schema::EnumName<E>, N>& names) {
    put(f, schema::name_of(v, names));
  }
  void rule(const char*, bool, const char*) const {}

 private:
  template <class T>
  void put(const schema::Field& f, const T& v) {
    *out_ << YAML::Key << f.name << YAML::Value << v;
  }
  YAML::Emitter* out_;
};

/// One Markdown row per field: key, default, unit, allowed values, meaning.
class ReferenceVisitor {
 public:
  explicit ReferenceVisitor(std::ostringstream& out) : out_(&out) {}
  template <class Body>
  void section(const char* name, Body&& body) {
    path_.push_back(name);
    body();
    path_.pop_back();
  }
  void number(const schema::Field& f, double v, const schema::Bounds& b) {
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.6g", v);
    row(f, buf, b.text());
  }
  void flag(const schema::Field& f, bool v) { row(f, v ? "true" : "false", "true, false"); }
  template <class T>
  void integer(const schema::Field& f, T v, const schema::IntRange& r) {
    row(f, std::to_string(v), r.text());
  }
  template <class E, std::size_t N>
  void choice(const schema::Field& f, E v, const std::array<schema::EnumName<E>, N>& names) {
    row(f, schema::name_of(v, names), canonical_names(names));
  }
  void rule(const char* name, bool, const char* problem) {
    std::string r = "`";  // appended piecewise: GCC 12 misreports "a" + b + "c" (-Wrestrict)
    r.append(key(name)).append("` ").append(problem);
    rules_.push_back(std::move(r));
  }
  [[nodiscard]] const std::vector<std::string>& rules() const noexcept { return rules_; }

 private:
  [[nodiscard]] std::string key(const char* name) const {
    std::string k;
    for (const char* p : path_) k += std::string(p) + ".";
    return k + name;
  }
  void row(const schema::Field& f, const std::string& value, const std::string& allowed) {
    *out_ << "| `" << key(f.name) << "` | " << value << " | " << f.unit << " | " << allowed << " | "
          << f.doc << " |\n";
  }
  std::ostringstream* out_;
  std::vector<const char*> path_;
  std::vector<std::string> rules_;
};

}  // namespace

namespace detail {

void read_localizer_node(const std::string& file, const YAML::Node& node, const std::string& path,
                         LocalizerConfig& cfg) {
  std::map<std::string, std::size_t> lines;
  LocalizerConfig c = cfg;
  std::size_t root_line = 0;
  try {
    YamlMap root(file, node, path);
    root_line = root.line();
    ReadVisitor reader(root, lines);
    schema::describe_config(reader, c);
    root.finish();
  } catch (const ConfigError&) {
    throw;
  } catch (const FormatError& e) {
    throw ConfigError(e.file(), e.line(), e.field(), e.message());
  }
  try {
    c.validate();
  } catch (const InvalidConfigField& e) {
    const std::string field = path.empty() ? e.field() : path + "." + e.field();
    throw ConfigError(file, line_of(field, lines, root_line), field, e.problem());
  }
  cfg = c;
}

}  // namespace detail

void read_localizer_config(const std::string& path, LocalizerConfig& cfg) {
  YAML::Node node;
  try {
    node = detail::load_yaml_file(path);
  } catch (const FormatError& e) {
    throw ConfigError(e.file(), e.line(), e.field(), e.message());
  }
  detail::read_localizer_node(path, node, "", cfg);
}

void parse_localizer_config(std::string_view text, const std::string& source,
                            LocalizerConfig& cfg) {
  YAML::Node node;
  try {
    node = YAML::Load(std::string(text));
  } catch (const YAML::Exception& e) {
    const std::size_t line = e.mark.is_null() ? 0 : static_cast<std::size_t>(e.mark.line) + 1;
    throw ConfigError(source, line, "yaml", "not valid YAML: " + e.msg);
  }
  detail::read_localizer_node(source, node, "", cfg);
}

void apply_localizer_override(const std::string& key, const std::string& value,
                              LocalizerConfig& cfg) {
  const std::string source = "--set " + key + "=" + value;
  YAML::Node leaf;
  try {
    leaf = YAML::Load(value);
  } catch (const YAML::Exception& e) {
    throw ConfigError(source, 0, key, "value is not valid YAML: " + e.msg);
  }
  // Build {a: {b: {c: value}}} from "a.b.c".
  std::vector<std::string> parts;
  std::stringstream ss(key);
  for (std::string part; std::getline(ss, part, '.');) {
    if (part.empty()) throw ConfigError(source, 0, key, "empty component in the dotted key");
    parts.push_back(part);
  }
  if (parts.empty()) throw ConfigError(source, 0, key, "empty key");
  YAML::Node node = leaf;
  for (auto it = parts.rbegin(); it != parts.rend(); ++it) {
    YAML::Node parent(YAML::NodeType::Map);
    parent[*it] = node;
    node = parent;
  }
  try {
    detail::read_localizer_node(source, node, "", cfg);
  } catch (const ConfigError& e) {  // the value's own line 1 would point nowhere
    throw ConfigError(source, 0, e.field(), e.message());
  }
}

void apply_localizer_overrides(const std::vector<std::string>& assignments, LocalizerConfig& cfg) {
  for (const std::string& a : assignments) {
    const auto [key, value] = parse_key_value(a, "--set");
    apply_localizer_override(key, value, cfg);
  }
}

std::string localizer_config_reference() {
  std::ostringstream out;
  out << "# Filter configuration reference\n\n"
         "Generated by `pgmcl config --reference` from the schema in\n"
         "`mcl/include/pgmcl/mcl/config_schema.hpp`; a test fails when this file is not\n"
         "current. Every key is optional in a filter YAML file (`--config`), an experiment's\n"
         "`filter:` block and `--set key=value`; absent keys keep the default. Numbers must be\n"
         "finite. Why the defaults are what they are: `configs/experiments/README.md`.\n\n"
         "| key | default | unit | allowed | meaning |\n|---|---|---|---|---|\n";
  ReferenceVisitor reference(out);
  const LocalizerConfig defaults;
  schema::describe_config(reference, defaults);
  out << "\nChecks across fields:\n\n";
  for (const std::string& r : reference.rules()) out << "- " << r << "\n";
  return out.str();
}

std::string localizer_config_yaml(const LocalizerConfig& c) {
  YAML::Emitter out;
  out.SetDoublePrecision(17);
  out << YAML::Comment("pgmcl LocalizerConfig (units: metres, radians)");
  out << YAML::BeginMap;
  WriteVisitor writer(out);
  schema::describe_config(writer, c);
  out << YAML::EndMap;
  return std::string(out.c_str()) + "\n";
}

}  // namespace pgmcl::io
