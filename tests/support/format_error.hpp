#pragma once
// The check that a parse throws io::FormatError at a given line and field, shared by the io
// and stress suites.

#include <gtest/gtest.h>

#include <cstddef>
#include <string>

#include "pgmcl/io/errors.hpp"

namespace pgmcl::testkit {

/// Runs `parse`, which must throw io::FormatError at `line` naming `field` (`accepted` is the
/// failure message when it does not throw); returns the error's text for further checks, ""
/// when there was none.
template <class F>
std::string expect_format_error(const char* accepted, F&& parse, std::size_t line,
                                const std::string& field) {
  try {
    (void)parse();
    ADD_FAILURE() << accepted;
  } catch (const io::FormatError& e) {
    EXPECT_EQ(e.line(), line) << e.what();
    EXPECT_EQ(e.field(), field) << e.what();
    return e.what();
  }
  return "";
}

}  // namespace pgmcl::testkit
