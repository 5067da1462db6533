#pragma once
// Test-only scratch files shared by the suites: a private temporary folder per test and
// whole-file text and byte readers and writers.

#include <gtest/gtest.h>
#include <unistd.h>

#include <algorithm>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <random>
#include <string>
#include <vector>

namespace pgmcl::testkit {

/// A fresh folder under the system temp dir, removed with everything in it at scope exit.
/// Named pgmcl_<tag>_<pid>_<suite>_<test>_<random> so that tests running in parallel
/// processes, and two folders in one test, never share one.
class TempDir {
 public:
  explicit TempDir(const std::string& tag = "test") {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::string test =
        info != nullptr ? std::string(info->test_suite_name()) + "_" + info->name() : "none";
    std::replace(test.begin(), test.end(), '/', '_');  // parameterised tests: Inst/Suite.Name/0
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("pgmcl_" + tag + "_" + std::to_string(::getpid()) + "_" + test + "_" +
             std::to_string(rd()));
    std::filesystem::remove_all(path_);
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }
  [[nodiscard]] const std::filesystem::path& path() const { return path_; }

 private:
  std::filesystem::path path_;
};

/// The whole file as bytes in a string ("" when it cannot be read).
inline std::string read_text(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// Writes `text` verbatim, creating the parent folders first.
inline void write_text(const std::string& path, const std::string& text) {
  const std::filesystem::path parent = std::filesystem::path(path).parent_path();
  if (!parent.empty()) std::filesystem::create_directories(parent);
  std::ofstream(path, std::ios::binary) << text;
}

inline void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

}  // namespace pgmcl::testkit
