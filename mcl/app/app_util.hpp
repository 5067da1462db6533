#pragma once
/// Small helpers shared by the pgmcl subcommands.

#include <CLI/CLI.hpp>
#include <filesystem>
#include <string>
#include <string_view>

#include "pgmcl/io/carmen.hpp"

namespace pgmcl::app {

/// Throws NotAvailableError: "<command>: not available yet (<why>)".
[[noreturn]] void not_available(std::string_view command, std::string_view why);

/// Creates `dir` (and parents) if needed; throws IoError naming it on failure.
std::filesystem::path ensure_directory(const std::string& dir);

/// Creates the parent folder of a file about to be written; throws IoError on failure.
void ensure_parent_directory(const std::string& file);

/// Reads a CARMEN log (non-strict unless `strict`): malformed lines are dropped and reported
/// as one "pgmcl: warning: ..." line on stderr naming the first of them (file:line: field).
[[nodiscard]] io::CarmenLog read_log(const std::string& path, const io::CarmenReadOptions& opt,
                                     bool strict);

/// True for CARMEN log names: *.log, *.clf, optionally followed by .gz.
[[nodiscard]] bool is_carmen_path(const std::string& path);

/// Ground truth from a TUM file, or from a CARMEN log (the robot poses of its laser scans,
/// io::scan_truth, of the first laser message type with poses), chosen by is_carmen_path.
[[nodiscard]] io::Trajectory load_truth(const std::string& path);

/// CLI11 checks with short messages ("must be > 0" rather than CLI11's range dump).
[[nodiscard]] CLI::Validator positive();
[[nodiscard]] CLI::Validator non_negative();

/// "12.3 s" / "1.23 ms" style durations for summaries.
[[nodiscard]] std::string format_seconds(double s);

}  // namespace pgmcl::app
