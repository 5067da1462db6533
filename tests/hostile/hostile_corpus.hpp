#pragma once
// The hostile corpus (issue 14): corrupt or absurd inputs and runs, each a case with the
// class of outcome it must have, run through the built `pgmcl` binary from the Intel demo
// case (a 5 cm map from the bundled corrected log, a perturbed raw log cut to its first
// scans, the truth).
//
// Classes:
//   kError    - exit code as given, one "pgmcl: error: " naming the culprit (file, line,
//               field or option and value), and nothing written: the case folder is
//               byte-for-byte what the case set up.
//   kWarning  - exit 0, a "pgmcl: warning: " naming the problem (a counted, reported skip
//               or a doubt about the input), and valid outputs.
//   kAccepted - exit 0, no warning, valid outputs.
// Every case: no crash or sanitizer report, no temporary file left behind.

#include <functional>
#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "temp_files.hpp"

namespace pgmcl::hostile {

/// The Intel demo case every corpus case starts from; made once per build of `pgmcl`
/// (cached under the build folder, keyed by the binary's modification time).
struct Base {
  std::string dir;    ///< absolute
  std::string map;    ///< map.yaml, 5 cm, from `pgmcl map`
  std::string image;  ///< map.pgm
  std::string raw;    ///< raw.log.gz: the whole perturbed log
  std::string log;    ///< short.log: its first kShortScans scans, plain text
  std::string truth;  ///< truth.tum (the whole log)
  Pose2 start{};      ///< the truth at short.log's first scan
  Pose2 end{};        ///< the truth at short.log's last scan
  Pose2 raw_end{};    ///< the truth at raw.log.gz's last scan
  Pose2 wall{};       ///< the centre of an occupied cell
  /// `--init` text for `start`.
  [[nodiscard]] std::string init() const;
};
inline constexpr int kShortScans = 120;

[[nodiscard]] const Base& base();

struct RunResult {
  int code = -1;
  std::string out;
  std::string err;
};

/// Runs `pgmcl <args>` (a shell command line) with `cwd` as working folder.
RunResult run_pgmcl(const std::string& args, const std::string& cwd);

/// A case's scratch folder, the working folder of its command.
struct Env {
  const Base& b;
  testkit::TempDir& dir;
  [[nodiscard]] std::string path(const std::string& name) const { return dir.file(name); }
  /// Writes `text` at `name` (parents created); returns the path.
  std::string write(const std::string& name, const std::string& text) const;
  /// Same, gzip-compressed.
  std::string write_gz(const std::string& name, const std::string& text) const;
  /// short.log's lines.
  [[nodiscard]] std::vector<std::string> log_lines() const;
  /// raw.log.gz's lines (the whole log).
  [[nodiscard]] std::vector<std::string> raw_lines() const;
  /// A map YAML beside the case using the base image (absolute path) with `keys` (the
  /// map_server keys after `image:`).
  std::string map_yaml(const std::string& name, const std::string& keys) const;
  /// `localize --map MAP --log LOG --init START --quiet --out out` + extra (without the
  /// base start when `extra` has --init or --global).
  [[nodiscard]] std::string localize(const std::string& extra, const std::string& log = "",
                                     const std::string& map = "") const;
};

enum class Expect { kError, kWarning, kAccepted };

/// Writes a case's inputs into its folder and returns pgmcl's arguments.
using MakeArgs = std::function<std::string(const Env&)>;
/// Extra checks of a case's outputs (oracles), after the generic ones.
using CheckRun = std::function<void(const Env&, const RunResult&)>;

struct Case {
  std::string name;  ///< a gtest name: letters, digits, underscores
  Expect expect = Expect::kError;
  int code = 1;
  MakeArgs make;
  std::vector<std::string> stderr_has;  ///< each must appear in stderr
  CheckRun check = nullptr;
};

/// One builder per class, so that each case is one expression.
[[nodiscard]] Case error_case(std::string name, int code, MakeArgs make,
                              std::vector<std::string> stderr_has, CheckRun check = nullptr);
[[nodiscard]] Case warning_case(std::string name, MakeArgs make,
                                std::vector<std::string> stderr_has, CheckRun check = nullptr);
[[nodiscard]] Case accepted_case(std::string name, MakeArgs make, CheckRun check = nullptr);
/// localize with `--set <assignment>`, a filter setting it must refuse (exit 1).
[[nodiscard]] Case bad_setting(std::string name, const std::string& assignment,
                               std::vector<std::string> stderr_has);

/// The arguments of Env::localize(extra, log, map), for a case that only runs localize.
[[nodiscard]] MakeArgs localize_with(std::string extra, std::string log = "", std::string map = "");
/// localize with `--config cfg.yaml`, cfg.yaml holding `yaml`.
[[nodiscard]] MakeArgs localize_with_config(std::string yaml);
/// localize on the map m.yaml, holding `yaml`.
[[nodiscard]] MakeArgs localize_on_map_yaml(std::string yaml);
/// `perturb-map --map <the base map> <options>`.
[[nodiscard]] MakeArgs perturb_base_map(std::string options);
/// `map --log <the base log> <options>`.
[[nodiscard]] MakeArgs map_base_log(std::string options);

/// The corpus, by issue-14 class.
std::vector<Case> resource_cases();       // crashes, memory and time limits
std::vector<Case> silent_cases();         // silent wrong results turned into errors or warnings
std::vector<Case> start_and_map_cases();  // ... for start poses and maps
std::vector<Case> output_cases();         // in == out, all-or-nothing outputs, re-runs, folders
std::vector<Case> message_cases();        // messages that name the culprit
std::vector<Case> first_round_cases();    // issue 6's inputs, still clear errors or skips

/// A text with `line` repeated to about `bytes` bytes.
[[nodiscard]] std::string repeat(const std::string& line, std::size_t bytes);

/// "x,y,theta" of a pose.
[[nodiscard]] std::string pose_text(const Pose2& p);

/// Replaces the ipc and logger stamps (the last field and the third from last) of ODOM and
/// laser lines with f(stamp).
[[nodiscard]] std::vector<std::string> restamp(const std::vector<std::string>& lines,
                                               const std::function<double(double)>& f,
                                               bool odom = true, bool scans = true);
[[nodiscard]] std::string join(const std::vector<std::string>& lines);

}  // namespace pgmcl::hostile
