#pragma once
/// Strict parsers for option values and the typed usage error they throw: the command line,
/// `--set` overrides and the Python bindings share them, so a bad value always names the
/// option and quotes the text.

#include <cstddef>
#include <initializer_list>
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

/// The shortest text that reads back as exactly `v` ("0.05", not "0.050000000000000003"),
/// with ".0" on whole numbers so a YAML reader sees a real number: what files pgmcl writes
/// for people to read use.
[[nodiscard]] std::string format_number(double v);

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

}  // namespace pgmcl::io
