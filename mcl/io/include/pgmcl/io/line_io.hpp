#pragma once
/// Line-oriented text I/O that is transparent to gzip: zlib's gzopen reads plain files as
/// they are, so every reader in pgmcl::io accepts `foo.log` and `foo.log.gz` alike.

#include <cstddef>
#include <string>
#include <string_view>

namespace pgmcl::io {

/// True when the path ends in ".gz" (the writers compress exactly then).
[[nodiscard]] bool is_gzip_path(std::string_view path) noexcept;

/// Longest line any reader accepts: a CARMEN line of the most readings a message may
/// declare (2^20 ranges and as many remissions) fits; a gzip bomb's one endless line does not.
inline constexpr std::size_t kMaxLineBytes = std::size_t{64} << 20;

/// Memory the records of one file may take (CARMEN, TUM, relations): a gzip bomb of valid
/// lines is refused at the line that crosses it instead of exhausting memory.
inline constexpr std::size_t kMaxRecordBytes = std::size_t{4} << 30;

/// Throws FormatError(source, line, "file", ...) once `records` records of `record_bytes`
/// each would take more than kMaxRecordBytes.
void check_record_memory(std::size_t records, std::size_t record_bytes, const std::string& source,
                         std::size_t line);

/// Reads a text file (plain or gzip) line by line and counts lines from 1.
class LineReader {
 public:
  /// Throws IoError when the file cannot be opened or is a folder.
  explicit LineReader(std::string path, std::size_t max_line_bytes = kMaxLineBytes);
  ~LineReader();
  LineReader(const LineReader&) = delete;
  LineReader& operator=(const LineReader&) = delete;

  /// Next line without its "\n" or "\r\n"; false at end of file. The view stays valid until
  /// the next call. Throws IoError on a read error or a truncated/corrupt gzip stream, and
  /// FormatError (file, line, "line") for a line longer than max_line_bytes.
  bool next(std::string_view& line);

  /// 1-based number of the line last returned by next() (0 before the first call).
  [[nodiscard]] std::size_t line_number() const noexcept { return line_number_; }
  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  void* file_ = nullptr;  // gzFile, kept opaque so users do not need zlib.h
  std::string buffer_;
  std::size_t line_number_ = 0;
  std::size_t max_line_bytes_ = kMaxLineBytes;
};

/// Writes lines to a file, gzip-compressed when the path ends in ".gz".
class LineWriter {
 public:
  /// Throws IoError when the file cannot be created.
  explicit LineWriter(std::string path);
  ~LineWriter();  ///< closes without throwing; call close() to see errors
  LineWriter(const LineWriter&) = delete;
  LineWriter& operator=(const LineWriter&) = delete;

  /// Writes `line` followed by "\n". Throws IoError on a write error.
  void write_line(std::string_view line);
  /// Flushes and closes; throws IoError if anything failed. Idempotent.
  void close();

  [[nodiscard]] const std::string& path() const noexcept { return path_; }

 private:
  std::string path_;
  void* file_ = nullptr;  // gzFile
};

}  // namespace pgmcl::io
