#pragma once
// Helpers shared by the pgmcl::io tests: bundled data paths, scratch files, exact comparisons.

#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <filesystem>
#include <string>

#include "pgmcl/maps/se2.hpp"

namespace pgmcl::io::test {

inline std::string data_path(const std::string& rel) {
  return std::string(PGMCL_SOURCE_DIR) + "/data/" + rel;
}

/// A per-test scratch directory, removed when the object goes away.
class ScratchDir {
 public:
  ScratchDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    dir_ =
        std::filesystem::temp_directory_path() / ("pgmcl_io_" + std::to_string(::getpid()) + "_" +
                                                  info->test_suite_name() + "_" + info->name());
    std::filesystem::create_directories(dir_);
  }
  ~ScratchDir() {
    std::error_code ec;
    std::filesystem::remove_all(dir_, ec);
  }
  ScratchDir(const ScratchDir&) = delete;
  ScratchDir& operator=(const ScratchDir&) = delete;
  [[nodiscard]] std::string file(const std::string& name) const { return (dir_ / name).string(); }

 private:
  std::filesystem::path dir_;
};

/// Bit-identical, with NaN equal to NaN.
inline bool same(double a, double b) {
  return (std::isnan(a) && std::isnan(b)) || a == b;
}

inline ::testing::AssertionResult same_pose(const Pose2& a, const Pose2& b) {
  if (same(a.x, b.x) && same(a.y, b.y) && same(a.theta, b.theta)) {
    return ::testing::AssertionSuccess();
  }
  return ::testing::AssertionFailure() << "(" << a.x << ", " << a.y << ", " << a.theta << ") != ("
                                       << b.x << ", " << b.y << ", " << b.theta << ")";
}

}  // namespace pgmcl::io::test
