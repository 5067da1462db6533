#pragma once
/// Small helpers shared by the pgmcl subcommands.

#include <CLI/CLI.hpp>
#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <initializer_list>
#include <limits>
#include <string>
#include <string_view>
#include <vector>

#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/file_kind.hpp"

namespace pgmcl::app {

/// Reads a CARMEN log (non-strict unless `strict`): malformed lines are dropped and reported
/// as a "pgmcl: warning: ..." on stderr listing them (file:line: field); `warnings`, if
/// given, receives the warning's first line.
[[nodiscard]] io::CarmenLog read_log(const std::string& path, const io::CarmenReadOptions& opt,
                                     bool strict, std::vector<std::string>* warnings = nullptr);

/// The image file a map YAML names, resolved against the YAML's folder (reads the YAML only).
[[nodiscard]] std::string map_image_path(const std::string& map_yaml);

/// Ground truth from a TUM file, or from a CARMEN log (the robot poses of its laser scans,
/// io::scan_truth, of the first laser message type with poses), chosen by the content
/// (io::detect_file_kind), else by io::is_carmen_path.
[[nodiscard]] io::Trajectory load_truth(const std::string& path);

/// CLI11 check that an input is the kind of file its option takes (io::file_kind_problem):
/// "--map: 'm.pgm' is a PGM image, not a map YAML ...; a map is its YAML ...".
[[nodiscard]] CLI::Validator file_kind(std::initializer_list<io::FileKind> accepted,
                                       std::string wanted);
/// The common ones: a map YAML, a CARMEN log, a TUM trajectory (or, with `log_ok`, a
/// corrected CARMEN log), a filter configuration, an experiment, a scenario, a relations file.
[[nodiscard]] CLI::Validator map_file();
[[nodiscard]] CLI::Validator log_file();
[[nodiscard]] CLI::Validator trajectory_file(bool log_ok);
[[nodiscard]] CLI::Validator filter_file();
[[nodiscard]] CLI::Validator experiment_file();
[[nodiscard]] CLI::Validator scenario_file();
[[nodiscard]] CLI::Validator relations_file();

/// A length with an optional unit ("5", "5mm", "0.5cm", "0.005m"), converted to `unit`
/// ("mm" or "m"): a bare number is already in `unit`, which the option's help says.
[[nodiscard]] CLI::Validator length_in(const std::string& unit);

/// CLI11 checks with short messages ("must be > 0" rather than CLI11's range dump).
[[nodiscard]] CLI::Validator positive();
[[nodiscard]] CLI::Validator non_negative();
/// Digits only, within [lo, hi]: "-1" and "18446744073709551616" are refused instead of
/// wrapping to 2^64 - 1 as strtoull would.
[[nodiscard]] CLI::Validator whole_number(
    std::uint64_t lo = 0, std::uint64_t hi = std::numeric_limits<std::uint64_t>::max());

/// A --seed option (any unsigned 64-bit value, checked as whole_number).
CLI::Option* add_seed_option(CLI::App& sub, std::uint64_t& seed, const std::string& help);

/// An input file option: the file must exist, and then be of a kind `kind` accepts (map_file(),
/// log_file(), ...), so a missing file is reported as missing rather than as the wrong kind.
CLI::Option* add_input_file(CLI::App& sub, const std::string& name, std::string& path,
                            const std::string& help, const CLI::Validator& kind);

/// A --threads option: a whole number in [0, config_schema::kMaxThreads], 0 = OpenMP default.
CLI::Option* add_threads_option(CLI::App& sub, int& threads, const std::string& help);

/// The filter configuration options of localize and config: --config FILE and --set KEY=VALUE...
struct FilterOptions {
  CLI::Option* config = nullptr;
  CLI::Option* sets = nullptr;
};
FilterOptions add_filter_options(CLI::App& sub, std::string& config,
                                 std::vector<std::string>& sets);

/// --strict, for the commands that read CARMEN logs.
CLI::Option* add_strict_flag(CLI::App& sub, bool& strict);

/// "threads = N is more than ..." when N is above this machine's core count, else "".
[[nodiscard]] std::string threads_warning(int threads);

/// One number of a comma-separated option value ("--glitch RATE,DEG") and the interval it
/// must lie in.
struct ValueRule {
  std::string_view name;  ///< as in the help text: "RATE", "DEG"
  double lo = -std::numeric_limits<double>::infinity();
  double hi = std::numeric_limits<double>::infinity();
  bool lo_open = false;  ///< true: lo itself is refused
  bool hi_open = false;  ///< true: hi itself is refused
  bool integer = false;  ///< a whole number
};

/// Parses `text` as NAME1,NAME2,... following `rules`: the first `required` numbers must be
/// given, the others are optional (the result holds only those given). Every number must be
/// finite and within its rule. Throws UsageError naming the option, the number and the text:
/// "--glitch: RATE must be in [0, 1], got 1.5 (in '1.5,30')".
[[nodiscard]] std::vector<double> parse_checked_list(std::string_view text, std::string_view option,
                                                     std::initializer_list<ValueRule> rules,
                                                     std::size_t required);

/// An option's old name, kept working as an alias: both names set the same variable, at most
/// one of them may be given, and using the old one prints a one-line note on stderr.
class DeprecatedName {
 public:
  DeprecatedName() = default;
  /// Registers `old_name` on `sub` for the variable of `current` (group "Deprecated").
  DeprecatedName(CLI::App& sub, CLI::Option* current, const std::string& old_name,
                 std::string& target);
  /// The name the user gave (the old one if it was used, else the current one).
  [[nodiscard]] const std::string& used() const noexcept;
  /// "pgmcl: warning: --truth is deprecated, use --truth-out" if the old name was used.
  void note_if_used() const;

 private:
  const CLI::Option* old_ = nullptr;
  std::string old_name_;
  std::string new_name_;
};

/// Writes `text` to `path`; throws IoError naming it when the file cannot be written whole
/// (a full disk included).
void write_text_file(const std::string& path, const std::string& text);

/// "12.3 s" / "1.23 ms" style durations for summaries.
[[nodiscard]] std::string format_seconds(double s);

}  // namespace pgmcl::app
