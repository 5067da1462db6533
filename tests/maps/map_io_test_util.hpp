#pragma once
// Helpers for the map I/O tests: a private temp folder per test and byte writers.

#include <gtest/gtest.h>

#include <cstdint>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include "pgmcl/map_io/map_io.hpp"
#include "temp_files.hpp"

namespace pgmcl::maps::test {

inline std::string data_dir() {
  return std::string(PGMCL_SOURCE_DIR) + "/data/maps";
}

using testkit::read_bytes;
using testkit::TempDir;
using testkit::write_bytes;
using testkit::write_text;

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
