#pragma once
/// Private helper for strict YAML adapters: walks one mapping, reads typed values into
/// plain-struct fields (a key that is absent leaves the struct's documented default), and
/// throws io::FormatError naming the file, the line and the dotted key for wrong types and
/// for keys nobody read (typos must not be ignored silently).

#include <yaml-cpp/yaml.h>

#include <cstdint>
#include <functional>
#include <set>
#include <string>
#include <utility>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/io/errors.hpp"

namespace pgmcl::io::detail {

/// 1-based line of a node, 0 when yaml-cpp has no mark for it.
[[nodiscard]] std::size_t yaml_line(const YAML::Node& node);

/// Parses a whole YAML document; syntax errors become FormatError(file, line, "yaml", ...).
[[nodiscard]] YAML::Node load_yaml_file(const std::string& path);

/// Sets the dotted `key` ("robot.start") of the mapping `doc` to `value` read as YAML,
/// creating mappings on the way: a command line's `--set key=value`. Throws UsageError
/// naming `--set key=value` for bad YAML, an empty key part, or a key part under a value
/// that is not a mapping.
void set_dotted(YAML::Node& doc, const std::string& key, const std::string& value);

/// A mapping under construction. `path` is the dotted key of the mapping itself ("" for the
/// document root); fields are reported as path + "." + key. Not copyable by design of use:
/// create one per mapping, read its keys, call finish().
class YamlMap {
 public:
  /// Throws unless `node` is a mapping (or null/absent, read as an empty mapping).
  YamlMap(std::string file, YAML::Node node, std::string path, std::size_t parent_line = 0);

  [[nodiscard]] bool has(const char* key) const;
  /// The value node (undefined if absent) and marks the key as read.
  [[nodiscard]] YAML::Node take(const char* key);
  /// Dotted field name of `key` ("robot.start").
  [[nodiscard]] std::string field(const std::string& key) const;
  /// Line of `key`'s value, else of the key, else of the mapping.
  [[nodiscard]] std::size_t line(const char* key) const;
  [[nodiscard]] std::size_t line() const noexcept { return line_; }
  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

  // Optional scalars: absent keys leave `out` unchanged. Each returns whether it was set.
  bool number(const char* key, double& out);
  bool integer(const char* key, int& out, long long min, long long max);
  bool uint64(const char* key, std::uint64_t& out);
  bool boolean(const char* key, bool& out);
  bool text(const char* key, std::string& out);
  /// [x, y, theta] (metres, metres, radians).
  bool pose(const char* key, Pose2& out);

  /// Required variants throw "missing required key".
  [[nodiscard]] YAML::Node require(const char* key);

  /// A nested mapping (absent -> empty mapping).
  [[nodiscard]] YamlMap child(const char* key);
  /// Elements of a sequence (absent -> empty); each element's field is key[i].
  [[nodiscard]] std::vector<std::pair<YAML::Node, std::string>> sequence(const char* key);

  /// Throws for the first key that was not read: "unknown key", then the hint for its
  /// dotted field if there is one (set_hint), else the nearest key that was asked for
  /// ("(did you mean 'particles'?)"), then the keys asked for at this level.
  void finish() const;
  /// What to say about an unknown key (its dotted field), or ""; inherited by child().
  using KeyHint = std::function<std::string(const std::string& field)>;
  void set_hint(KeyHint hint) { hint_ = std::move(hint); }
  /// The key asked for (read or looked up) that is nearest `key` in edit distance, or "".
  [[nodiscard]] std::string closest_key(const std::string& key) const;

  [[noreturn]] void fail(const char* key, const std::string& problem) const;
  [[noreturn]] void fail_at(const YAML::Node& node, const std::string& field,
                            const std::string& problem) const;

 private:
  std::string file_;
  YAML::Node node_;
  std::string path_;
  std::size_t line_ = 0;
  std::set<std::string> read_;
  KeyHint hint_;
};

// Free readers for values that are not directly in a mapping (sequence elements).
[[nodiscard]] double yaml_number(const std::string& file, const YAML::Node& n,
                                 const std::string& field, std::size_t fallback_line);
[[nodiscard]] Pose2 yaml_pose(const std::string& file, const YAML::Node& n,
                              const std::string& field, std::size_t fallback_line);
/// [x, y] as a pair of doubles.
[[nodiscard]] std::pair<double, double> yaml_xy(const std::string& file, const YAML::Node& n,
                                                const std::string& field,
                                                std::size_t fallback_line);

}  // namespace pgmcl::io::detail
