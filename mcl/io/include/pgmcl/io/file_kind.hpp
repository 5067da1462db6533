#pragma once
/// What kind of pgmcl input a file is, from its first lines (gzip or not): so that a PGM
/// passed as --map, a CARMEN log passed as --estimate or an experiment passed as --config
/// gets "X is a ..., --map wants a ..." instead of the parse error of the wrong reader.
/// Detection is conservative: a file it cannot place is kUnknown, and callers then leave the
/// verdict to the format's own reader.

#include <string>
#include <vector>

namespace pgmcl::io {

enum class FileKind {
  kUnknown,     ///< none of the below (or unreadable): the reader decides
  kEmpty,       ///< no content besides blank and comment lines
  kPgmImage,    ///< P2 / P5 image
  kPngImage,    ///< PNG image
  kMapYaml,     ///< map_server YAML (image:, resolution:)
  kFilterYaml,  ///< LocalizerConfig YAML (only filter sections at the top)
  kExperiment,  ///< `pgmcl run` file (a data: block)
  kScenario,    ///< simulated scenario (robot:, sensor:, duration:, ...)
  kOtherYaml,   ///< YAML mapping of none of the kinds above
  kCarmenLog,   ///< lines starting with a CARMEN message name (FLASER, ODOM, PARAM, ...)
  kNumberTable  ///< 8 numbers per line: a TUM trajectory (or benchmark relations)
};

/// "a PGM image", "a CARMEN log", ...: the kind as a noun phrase for messages.
[[nodiscard]] const char* describe(FileKind kind) noexcept;

/// Reads at most the first 200 lines of `path` (gzip-transparent); anything but a regular
/// file (a FIFO, a device) is kUnknown, unread. Never throws.
[[nodiscard]] FileKind detect_file_kind(const std::string& path) noexcept;

/// "" when `path` may be one of `accepted`, else what is wrong and what to do instead:
/// "'m.pgm' is a PGM image, not a map YAML (...); a map is its YAML ...".
[[nodiscard]] std::string file_kind_problem(const std::string& path,
                                            const std::vector<FileKind>& accepted,
                                            const std::string& wanted);

/// Throws UsageError when `path` is positively another kind than every one of `accepted`:
/// "--map: 'm.pgm' is a PGM image, not a map YAML (...); " plus what to do instead.
/// `option` names the option or key ("--map", "e.yaml:3: data.log"); `wanted` says what it
/// takes. kUnknown and kEmpty files pass (their reader reports what is wrong).
void expect_file_kind(const std::string& path, const std::string& option,
                      const std::vector<FileKind>& accepted, const std::string& wanted);

}  // namespace pgmcl::io
