#pragma once
/// Exit codes of the `pgmcl` command and the one place that turns any exception into a
/// "pgmcl: error: ..." line and an exit code.

#include <functional>
#include <ostream>

namespace pgmcl::app {

/// Exit codes of the pgmcl command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;  ///< bad input file, I/O, runtime failure
inline constexpr int kExitUsage = 2;    ///< bad command line (io::UsageError)
/// Stopped by a signal: 128 + its number (interrupt.hpp), as a shell reports it.
inline constexpr int kExitSigint = 130;
inline constexpr int kExitSigterm = 143;

/// Runs `body`, mapping exceptions to "pgmcl: error: <what>" on `err` and an exit code
/// (no stack traces, no abort). Returns body's result when it does not throw.
[[nodiscard]] int run_reporting_errors(const std::function<int()>& body, std::ostream& err);

}  // namespace pgmcl::app
