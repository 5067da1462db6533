#pragma once
/// Typed exceptions thrown at pgmcl's file boundaries.

#include <cstddef>
#include <stdexcept>
#include <string>
#include <utility>

namespace pgmcl::io {

/// A file could not be opened, read or written (missing file, corrupt gzip stream, full disk).
class IoError : public std::runtime_error {
 public:
  explicit IoError(const std::string& what) : std::runtime_error(what) {}
};

/// A line of a text format is malformed. what() reads "file:line: field: message", so the
/// message alone tells the user where to look. Line 0 means the input has no lines (a
/// command-line override such as "--set key=value"): what() is then "file: field: message".
class FormatError : public std::runtime_error {
 public:
  FormatError(std::string file, std::size_t line, std::string field, std::string message)
      : std::runtime_error(describe(file, line, field, message)),
        file_(std::move(file)),
        line_(line),
        field_(std::move(field)),
        message_(std::move(message)) {}

  [[nodiscard]] const std::string& file() const noexcept { return file_; }
  [[nodiscard]] std::size_t line() const noexcept { return line_; }  ///< 1-based
  [[nodiscard]] const std::string& field() const noexcept { return field_; }
  [[nodiscard]] const std::string& message() const noexcept { return message_; }

 private:
  static std::string describe(const std::string& file, std::size_t line, const std::string& field,
                              const std::string& message) {
    std::string out = file;
    if (line > 0) out.append(":").append(std::to_string(line));
    out.append(": ").append(field).append(": ").append(message);
    return out;
  }

  std::string file_;
  std::size_t line_;
  std::string field_;
  std::string message_;
};

}  // namespace pgmcl::io
