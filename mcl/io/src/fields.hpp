#pragma once
/// Private helpers shared by the text-format readers and writers: tokenising, strict number
/// parsing with field names for error messages, and round-trip number formatting.

#include <cstddef>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io::detail {

/// Thrown by a line parser; the file-level reader adds file and line and decides whether it
/// is an error (strict) or a counted, reported malformed line.
struct FieldError {
  std::string field;
  std::string message;
};

/// Splits on spaces and tabs, dropping empty tokens.
void split_fields(std::string_view line, std::vector<std::string_view>& out);

/// The whole token as a double ("nan" and "inf" included); nullopt if any character is left
/// over or the value overflows. A leading '+' is accepted (strtod does).
[[nodiscard]] std::optional<double> parse_double(std::string_view token) noexcept;
[[nodiscard]] std::optional<long long> parse_integer(std::string_view token) noexcept;

/// Shortest text that reads back to the same value (std::to_chars): exact round trips.
void append_number(std::string& out, double v);
void append_number(std::string& out, float v);
/// Same, never in scientific notation (timestamps stay readable).
void append_fixed(std::string& out, double v);

/// Walks the tokens of one line, naming each field it takes so errors say which one failed.
class FieldCursor {
 public:
  FieldCursor(std::span<const std::string_view> tokens, std::size_t start) noexcept
      : tokens_(tokens), pos_(start) {}

  /// A finite number; missing, non-numeric or non-finite tokens raise FieldError.
  double finite(std::string_view name);
  /// Any number, NaN and Inf included (ranges: such beams are invalid, not the line).
  double number(std::string_view name, std::size_t index);
  /// A count in [0, max].
  std::size_t count(std::string_view name, std::size_t max);
  int integer(std::string_view name);
  std::string_view text(std::string_view name);
  /// Raises FieldError if tokens are left over.
  void expect_end(std::string_view last_field) const;

  [[nodiscard]] std::size_t position() const noexcept { return pos_; }
  [[nodiscard]] std::size_t remaining() const noexcept { return tokens_.size() - pos_; }

 private:
  std::string_view take(std::string_view name, std::size_t index, bool indexed);
  std::span<const std::string_view> tokens_;
  std::size_t pos_;
};

/// "range[17]"
[[nodiscard]] std::string indexed_name(std::string_view name, std::size_t index);

/// For the simple formats (TUM, relations): exactly names.size() finite numbers into `out`,
/// else FormatError(source, line, field, ...). The last name stands for extra fields.
void parse_fixed_numbers(std::span<const std::string_view> tokens,
                         std::span<const std::string_view> names, std::span<double> out,
                         const std::string& source, std::size_t line);

/// Calls fn(line, line_number) for every line of `text`, without "\n" or "\r\n".
template <typename Fn>
void for_each_text_line(std::string_view text, Fn&& fn) {
  std::size_t line_no = 0;
  while (!text.empty()) {
    const std::size_t eol = text.find('\n');
    std::string_view line = text.substr(0, eol);
    text.remove_prefix(eol == std::string_view::npos ? text.size() : eol + 1);
    if (!line.empty() && line.back() == '\r') line.remove_suffix(1);
    fn(line, ++line_no);
  }
}

/// Same for a file, plain or gzip (IoError if unreadable).
template <typename Fn>
void for_each_file_line(const std::string& path, Fn&& fn) {
  LineReader reader(path);
  std::string_view line;
  while (reader.next(line)) fn(line, reader.line_number());
}

}  // namespace pgmcl::io::detail
