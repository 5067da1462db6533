// Gzip-transparent line reading and writing.

#include "pgmcl/io/line_io.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>
#include <vector>

#include "format_error.hpp"
#include "io_test_util.hpp"
#include "pgmcl/io/errors.hpp"

namespace pgmcl::io {
namespace {

std::vector<std::string> read_all(const std::string& path) {
  LineReader r(path);
  std::vector<std::string> lines;
  std::string_view line;
  while (r.next(line)) {
    lines.emplace_back(line);
    EXPECT_EQ(r.line_number(), lines.size());
  }
  return lines;
}

TEST(LineIo, LongLinesCrlfAndNoFinalNewlinePlainAndGzip) {
  const std::string long_line(100000, 'x');  // far past gzgets' chunk size
  test::TempDir dir;
  for (const char* name : {"a.txt", "a.txt.gz"}) {
    {
      LineWriter w(dir.file(name));
      w.write_line("first");
      w.write_line("");
      w.write_line(long_line);
      w.write_line("crlf\r");
      w.close();
      w.close();  // idempotent
    }
    const auto lines = read_all(dir.file(name));
    ASSERT_EQ(lines.size(), 4u) << name;
    EXPECT_EQ(lines[0], "first");
    EXPECT_EQ(lines[1], "");
    EXPECT_EQ(lines[2], long_line);
    EXPECT_EQ(lines[3], "crlf");
  }
  // Only the .gz file is compressed.
  std::ifstream gz(dir.file("a.txt.gz"), std::ios::binary);
  EXPECT_EQ(gz.get(), 0x1f);
  EXPECT_EQ(gz.get(), 0x8b);
  std::ifstream plain(dir.file("a.txt"), std::ios::binary);
  EXPECT_EQ(plain.get(), 'f');

  std::ofstream(dir.file("b.txt"), std::ios::binary) << "no newline at end";
  EXPECT_EQ(read_all(dir.file("b.txt")), std::vector<std::string>{"no newline at end"});
}

TEST(LineIo, TruncatedGzipIsAnErrorNotAShortFile) {
  test::TempDir dir;
  {
    LineWriter w(dir.file("c.gz"));
    for (int i = 0; i < 20000; ++i) w.write_line("line " + std::to_string(i * 7919));
    w.close();
  }
  const auto size = std::filesystem::file_size(dir.file("c.gz"));
  std::filesystem::resize_file(dir.file("c.gz"), size / 2);
  EXPECT_THROW((void)read_all(dir.file("c.gz")), IoError);
}

TEST(LineIo, OpenFailuresAreIoErrors) {
  EXPECT_THROW(LineReader("/nonexistent/dir/file.log"), IoError);
  EXPECT_THROW(LineWriter("/nonexistent/dir/file.log"), IoError);
  EXPECT_TRUE(is_gzip_path("x.log.gz"));
  EXPECT_FALSE(is_gzip_path("x.gzip"));
}

}  // namespace
}  // namespace pgmcl::io

namespace pgmcl::io {
namespace {

// A line past the limit (a gzip bomb's one endless line) is a FormatError at that line,
// found before the whole line is held in memory; folders are refused when opened.
TEST(LineIo, LinesPastTheLimitAndFoldersAreRefused) {
  const test::TempDir dir("line_io_limits");
  {
    LineWriter w(dir.file("long.txt.gz"));
    w.write_line("short");
    w.write_line(std::string(5000, 'a'));
    w.close();
  }
  LineReader r(dir.file("long.txt.gz"), 4096);
  std::string_view line;
  ASSERT_TRUE(r.next(line));
  (void)testkit::expect_format_error(
      "a 5000-byte line passed a 4096-byte limit", [&] { return r.next(line); }, 2, "line");
  EXPECT_THROW(LineReader{dir.path().string()}, IoError);
  EXPECT_NO_THROW(check_record_memory(kMaxRecordBytes / 8, 8, "f", 3));
  try {
    check_record_memory(kMaxRecordBytes / 8 + 1, 8, "f", 3);
    ADD_FAILURE() << "past the record memory limit";
  } catch (const FormatError& e) {
    EXPECT_EQ(std::string(e.what()).rfind("f:3: file: holds more than", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace pgmcl::io
