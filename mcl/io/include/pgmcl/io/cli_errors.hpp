#pragma once
/// Error reporting for the `pgmcl` command: a typed usage error, strict parsers for option
/// values (they name the option and quote the bad text), and the one place that turns any
/// exception into a "pgmcl: error: ..." line and an exit code.

#include <cstddef>
#include <functional>
#include <initializer_list>
#include <iosfwd>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace pgmcl::io {

/// A bad command line: missing or malformed option value. Exit code 2.
class UsageError : public std::runtime_error {
 public:
  explicit UsageError(const std::string& what) : std::runtime_error(what) {}
};

/// A feature that is registered but not built yet. Exit code 3.
class NotAvailableError : public std::runtime_error {
 public:
  explicit NotAvailableError(const std::string& what) : std::runtime_error(what) {}
};

/// Parses one finite number; the whole text must be consumed. Throws UsageError naming
/// `option` ("--resolution: expected a number, got 'abc'").
[[nodiscard]] double parse_number(std::string_view text, std::string_view option);

/// Parses "a,b,c" into numbers; the count must be one of `counts`. Throws UsageError
/// naming `option`, the expected form (`form`, e.g. "X,Y,THETA[,SX,SY,STH]") and the text.
[[nodiscard]] std::vector<double> parse_number_list(std::string_view text, std::string_view option,
                                                    std::initializer_list<std::size_t> counts,
                                                    std::string_view form);

/// Splits "key=value" (the key may be dotted); throws UsageError naming `option`.
[[nodiscard]] std::pair<std::string, std::string> parse_key_value(std::string_view text,
                                                                  std::string_view option);

/// Exit codes of the pgmcl command.
inline constexpr int kExitOk = 0;
inline constexpr int kExitFailure = 1;       ///< bad input file, I/O, runtime failure
inline constexpr int kExitUsage = 2;         ///< bad command line
inline constexpr int kExitNotAvailable = 3;  ///< command not implemented yet

/// Runs `body`, mapping exceptions to "pgmcl: error: <what>" on `err` and an exit code
/// (no stack traces, no abort). Returns body's result when it does not throw.
[[nodiscard]] int run_reporting_errors(const std::function<int()>& body, std::ostream& err);

}  // namespace pgmcl::io
