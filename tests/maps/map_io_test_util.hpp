#pragma once
// Helpers for the map I/O tests: a private temp folder per test and byte writers.

#include <gtest/gtest.h>

#include <cstdint>
#include <filesystem>
#include <fstream>
#include <functional>
#include <initializer_list>
#include <random>
#include <string>
#include <vector>

#include "pgmcl/maps/map_io.hpp"

namespace pgmcl::maps::test {

inline std::string data_dir() {
  return std::string(PGMCL_SOURCE_DIR) + "/data/maps";
}

/// A fresh folder under the system temp dir, removed with everything in it.
class TempDir {
 public:
  TempDir() {
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    std::random_device rd;
    path_ = std::filesystem::temp_directory_path() /
            ("pgmcl_mapio_" + std::string(info != nullptr ? info->name() : "x") + "_" +
             std::to_string(rd()) + std::to_string(rd()));
    std::filesystem::create_directories(path_);
  }
  ~TempDir() {
    std::error_code ec;
    std::filesystem::remove_all(path_, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;

  [[nodiscard]] std::string file(const std::string& name) const { return (path_ / name).string(); }

 private:
  std::filesystem::path path_;
};

inline void write_text(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

inline void write_bytes(const std::string& path, const std::vector<std::uint8_t>& bytes) {
  std::ofstream(path, std::ios::binary)
      .write(reinterpret_cast<const char*>(bytes.data()),
             static_cast<std::streamsize>(bytes.size()));
}

inline std::vector<std::uint8_t> read_bytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

/// A binary P5 greymap, rows top-down as the format stores them.
inline std::vector<std::uint8_t> make_p5(int w, int h, const std::vector<std::uint8_t>& px,
                                         int maxval = 255) {
  const std::string header =
      "P5\n" + std::to_string(w) + " " + std::to_string(h) + "\n" + std::to_string(maxval) + "\n";
  std::vector<std::uint8_t> out(header.begin(), header.end());
  out.insert(out.end(), px.begin(), px.end());
  return out;
}

/// A YAML with the given image and extra lines appended verbatim.
inline std::string map_yaml(const std::string& image, const std::string& extra = "") {
  return "image: " + image +
         "\nresolution: 0.1\norigin: [0.0, 0.0, 0.0]\nnegate: 0\n"
         "occupied_thresh: 0.65\nfree_thresh: 0.196\n" +
         extra;
}

/// Runs `fn`, expects a MapError whose message contains every one of `parts`.
inline void expect_map_error(const std::function<void()>& fn,
                             std::initializer_list<std::string> parts) {
  try {
    fn();
    ADD_FAILURE() << "expected MapError, nothing was thrown";
  } catch (const MapError& e) {
    const std::string what = e.what();
    for (const auto& p : parts) {
      EXPECT_NE(what.find(p), std::string::npos) << "'" << p << "' not in: " << what;
    }
  } catch (const std::exception& e) {
    ADD_FAILURE() << "expected MapError, got another exception: " << e.what();
  }
}

}  // namespace pgmcl::maps::test
