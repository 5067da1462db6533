#include "pgmcl/io/file_kind.hpp"

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <set>
#include <sstream>
#include <string_view>

#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/line_io.hpp"
#include "pgmcl/io/values.hpp"

namespace pgmcl::io {
namespace {

constexpr std::size_t kMaxLines = 200;

std::string_view trim(std::string_view s) {
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.front()))) s.remove_prefix(1);
  while (!s.empty() && std::isspace(static_cast<unsigned char>(s.back()))) s.remove_suffix(1);
  return s;
}

/// "key" of a top-level YAML line "key: ..." (no indentation), else "".
std::string top_level_key(std::string_view line) {
  if (line.empty() || !(std::isalpha(static_cast<unsigned char>(line[0])) || line[0] == '_'))
    return {};
  std::size_t i = 0;
  while (i < line.size() &&
         (std::isalnum(static_cast<unsigned char>(line[i])) || line[i] == '_' || line[i] == '-'))
    ++i;
  if (i < line.size() && line[i] == ':' && (i + 1 == line.size() || line[i + 1] == ' '))
    return std::string(line.substr(0, i));
  return {};
}

/// A CARMEN message name: upper-case letters and digits, starting with a letter.
bool carmen_word(std::string_view w) {
  if (w.size() < 3 || !std::isupper(static_cast<unsigned char>(w[0]))) return false;
  return std::all_of(w.begin(), w.end(), [](char c) {
    return std::isupper(static_cast<unsigned char>(c)) ||
           std::isdigit(static_cast<unsigned char>(c));
  });
}

std::size_t count_numbers(std::string_view line) {
  std::istringstream in{std::string(line)};
  std::size_t n = 0;
  for (std::string tok; in >> tok; ++n) {
    try {
      (void)parse_number(tok, "x");
    } catch (const std::exception&) {
      return 0;
    }
  }
  return n;
}

FileKind yaml_kind(const std::set<std::string>& keys) {
  auto has = [&](const char* k) { return keys.count(k) != 0; };
  if (has("image") && has("resolution")) return FileKind::kMapYaml;
  if (has("data")) return FileKind::kExperiment;
  for (const char* k : {"robot", "sensor", "duration", "scan_rate", "kidnaps", "obstacles",
                        "surfaces", "odometry", "raycast"})
    if (has(k)) return FileKind::kScenario;
  static const std::set<std::string> filter{"motion",         "likelihood", "filter",
                                            "gating",         "estimate",   "hypotheses",
                                            "time_backwards", "threads",    "seed"};
  bool all_filter = true, any_section = false;
  for (const std::string& k : keys) {
    all_filter = all_filter && filter.count(k) != 0;
    any_section = any_section || (filter.count(k) != 0 && k != "seed" && k != "threads");
  }
  if (all_filter && any_section) return FileKind::kFilterYaml;
  return FileKind::kOtherYaml;
}

/// What to do with a file of kind `got` given where it was put.
std::string advice(FileKind got, const std::string& path) {
  switch (got) {
    case FileKind::kPgmImage:
    case FileKind::kPngImage:
      return "a map is its YAML (image:, resolution:, origin:), which names the image; a bare "
             "image has no resolution or origin";
    case FileKind::kMapYaml:
      return "a map goes to --map (or an experiment's map:)";
    case FileKind::kFilterYaml:
      return "a filter configuration goes to --config (or an experiment's filter:)";
    case FileKind::kExperiment:
      return "run it with `pgmcl run " + path +
             "` (a data.scenario is simulated first; the filter: block is its filter "
             "configuration)";
    case FileKind::kScenario:
      return "simulate it with `pgmcl simulate " + path +
             " --out LOG`, or run it from an experiment file with data: {scenario: " + path +
             "} (configs/experiments/lab.yaml)";
    case FileKind::kCarmenLog:
      return "a log goes to --log; localize it first (pgmcl localize --out DIR writes "
             "DIR/trajectory.tum), or give a corrected log as --truth";
    case FileKind::kNumberTable:
      return "a TUM trajectory goes to --truth or --estimate";
    default:
      return "";
  }
}

}  // namespace

const char* describe(FileKind kind) noexcept {
  switch (kind) {
    case FileKind::kUnknown:
      return "a file of unknown kind";
    case FileKind::kEmpty:
      return "empty";
    case FileKind::kPgmImage:
      return "a PGM image";
    case FileKind::kPngImage:
      return "a PNG image";
    case FileKind::kMapYaml:
      return "a map YAML (map_server)";
    case FileKind::kFilterYaml:
      return "a filter configuration";
    case FileKind::kExperiment:
      return "an experiment file (pgmcl run)";
    case FileKind::kScenario:
      return "a simulated scenario (pgmcl simulate)";
    case FileKind::kOtherYaml:
      return "a YAML file";
    case FileKind::kCarmenLog:
      return "a CARMEN log";
    case FileKind::kNumberTable:
      return "a TUM trajectory (8 numbers per line)";
  }
  return "?";
}

FileKind detect_file_kind(const std::string& path) noexcept {
  // A FIFO or a device is read once: peeking at it would eat what the command then reads.
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) return FileKind::kUnknown;
  try {
    LineReader in(path);
    std::string_view line;
    std::set<std::string> yaml_keys;
    std::size_t n = 0, numbers8 = 0, carmen = 0, other = 0, meaningful = 0;
    while (n < kMaxLines && in.next(line)) {
      ++n;
      if (n == 1) {
        if (line.substr(0, 4) == "\x89PNG") return FileKind::kPngImage;
        const std::string_view t = trim(line);
        if ((t.substr(0, 2) == "P5" || t.substr(0, 2) == "P2") &&
            (t.size() == 2 || std::isspace(static_cast<unsigned char>(t[2]))))
          return FileKind::kPgmImage;
      }
      const std::string_view t = trim(line);
      if (t.empty() || t.front() == '#' || t == "---") continue;
      ++meaningful;
      if (const std::string key = top_level_key(line); !key.empty()) {
        yaml_keys.insert(key);
        continue;
      }
      if (line.front() == ' ' || line.front() == '-') continue;  // YAML nesting
      const std::string_view word = t.substr(0, t.find_first_of(" \t"));
      if (carmen_word(word)) {
        ++carmen;
      } else if (count_numbers(t) == 8) {
        ++numbers8;
      } else {
        ++other;
      }
    }
    if (meaningful == 0) return FileKind::kEmpty;
    const std::size_t lines = carmen + numbers8 + other;
    if (!yaml_keys.empty() && lines == 0) return yaml_kind(yaml_keys);
    if (yaml_keys.empty() && carmen > 0 && carmen * 2 >= lines) return FileKind::kCarmenLog;
    if (yaml_keys.empty() && numbers8 > 0 && numbers8 * 10 >= lines * 9)
      return FileKind::kNumberTable;
  } catch (...) {
  }
  return FileKind::kUnknown;
}

std::string file_kind_problem(const std::string& path, const std::vector<FileKind>& accepted,
                              const std::string& wanted) {
  const FileKind got = detect_file_kind(path);
  if (got == FileKind::kUnknown || got == FileKind::kEmpty) return {};
  if (std::find(accepted.begin(), accepted.end(), got) != accepted.end()) return {};
  std::string msg = "'" + path + "' is " + describe(got) + ", not " + wanted;
  if (const std::string a = advice(got, path); !a.empty()) msg += "; " + a;
  return msg;
}

void expect_file_kind(const std::string& path, const std::string& option,
                      const std::vector<FileKind>& accepted, const std::string& wanted) {
  const std::string problem = file_kind_problem(path, accepted, wanted);
  if (!problem.empty()) throw UsageError(option + ": " + problem);
}

}  // namespace pgmcl::io
