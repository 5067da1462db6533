#include "pgmcl/io/line_io.hpp"

#include <zlib.h>

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <system_error>
#include <utility>

#include "pgmcl/io/errors.hpp"

namespace pgmcl::io {
namespace {

gzFile as_gz(void* f) noexcept {
  return static_cast<gzFile>(f);
}

std::string gz_message(void* f) {
  int code = Z_OK;
  const char* msg = gzerror(as_gz(f), &code);
  if (code == Z_ERRNO) return std::strerror(errno);
  return msg != nullptr ? msg : "unknown zlib error";
}

}  // namespace

void check_record_memory(std::size_t records, std::size_t record_bytes, const std::string& source,
                         std::size_t line) {
  if (records * record_bytes <= kMaxRecordBytes) return;
  throw FormatError(source, line, "file",
                    "holds more than " + std::to_string(kMaxRecordBytes >> 20) +
                        " MiB of records by this line (" + std::to_string(records) + " of " +
                        std::to_string(record_bytes) + " bytes each); split it");
}

bool is_gzip_path(std::string_view path) noexcept {
  return path.size() >= 3 && path.substr(path.size() - 3) == ".gz";
}

LineReader::LineReader(std::string path, std::size_t max_line_bytes)
    : path_(std::move(path)), max_line_bytes_(max_line_bytes) {
  // gzopen opens a folder and then fails on the first read with a vague message.
  std::error_code ec;
  if (std::filesystem::is_directory(path_, ec)) {
    throw IoError("cannot read '" + path_ + "': it is a folder, not a file");
  }
  file_ = gzopen(path_.c_str(), "rb");
  if (file_ == nullptr) {
    throw IoError("cannot open '" + path_ + "' for reading: " + std::strerror(errno));
  }
  gzbuffer(as_gz(file_), 1 << 17);
}

LineReader::~LineReader() {
  if (file_ != nullptr) gzclose(as_gz(file_));
}

bool LineReader::next(std::string_view& line) {
  buffer_.clear();
  bool got_any = false;
  // Byte by byte through zlib's buffered gzgetc: a line may hold NUL bytes (corrupt logs),
  // which a gzgets + strlen reader would mistake for the end of the chunk and so merge
  // the next line into this one.
  for (int c = gzgetc(as_gz(file_)); c != -1; c = gzgetc(as_gz(file_))) {
    got_any = true;
    if (c == '\n') break;
    if (buffer_.size() >= max_line_bytes_) {
      throw FormatError(path_, line_number_ + 1, "line",
                        "longer than " + std::to_string(max_line_bytes_ >> 20) + " MiB (" +
                            std::to_string(max_line_bytes_) +
                            " bytes) without a line break: not a text log, or corrupt");
    }
    buffer_.push_back(static_cast<char>(c));
  }
  int code = Z_OK;
  gzerror(as_gz(file_), &code);
  if (code != Z_OK) {
    throw IoError("error reading '" + path_ + "' " + (got_any ? "at" : "after") + " line " +
                  std::to_string(line_number_ + (got_any ? 1 : 0)) + ": " + gz_message(file_));
  }
  if (!got_any) return false;
  // One CR of a CRLF ending, exactly as parse_carmen strips it from in-memory text.
  if (!buffer_.empty() && buffer_.back() == '\r') buffer_.pop_back();
  ++line_number_;
  line = buffer_;
  return true;
}

LineWriter::LineWriter(std::string path) : path_(std::move(path)) {
  // "T" writes uncompressed through the same zlib API (zlib >= 1.2.6).
  file_ = gzopen(path_.c_str(), is_gzip_path(path_) ? "wb6" : "wbT");
  if (file_ == nullptr) {
    throw IoError("cannot open '" + path_ + "' for writing: " + std::strerror(errno));
  }
}

LineWriter::~LineWriter() {
  if (file_ != nullptr) gzclose(as_gz(file_));
}

void LineWriter::write_line(std::string_view line) {
  if (file_ == nullptr) throw IoError("write to closed file '" + path_ + "'");
  const bool ok = (line.empty() ||
                   gzwrite(as_gz(file_), line.data(), static_cast<unsigned>(line.size())) > 0) &&
                  gzputc(as_gz(file_), '\n') != -1;
  if (!ok) throw IoError("error writing '" + path_ + "': " + gz_message(file_));
}

void LineWriter::close() {
  if (file_ == nullptr) return;
  const int rc = gzclose(as_gz(file_));
  file_ = nullptr;
  if (rc != Z_OK)
    throw IoError("error closing '" + path_ + "' (zlib code " + std::to_string(rc) + ")");
}

}  // namespace pgmcl::io
