// io::format_number: the shortest text that reads back exactly, in a form YAML 1.1 and 1.2
// readers both take for a real number.

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <string>

#include "pgmcl/io/values.hpp"

namespace pgmcl::io {
namespace {

TEST(FormatNumber, ShortestTextThatReadsBackExactly) {
  EXPECT_EQ(format_number(0.05), "0.05");
  EXPECT_EQ(format_number(-27.4), "-27.4");
  EXPECT_EQ(format_number(0.0005), "0.0005");
  EXPECT_EQ(format_number(1.0), "1.0");
  EXPECT_EQ(format_number(0.0), "0.0");
  EXPECT_EQ(format_number(20000.0), "20000.0");
  EXPECT_EQ(format_number(0.1 + 0.2), "0.30000000000000004");  // a different double
  EXPECT_EQ(format_number(418 * 0.05), "20.900000000000002");
  EXPECT_EQ(format_number(1e-9), "1.0e-09");
  EXPECT_EQ(format_number(2.5e20), "2.5e+20");
  EXPECT_EQ(format_number(INFINITY), ".inf");
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> mant(-10.0, 10.0);
  std::uniform_int_distribution<int> exp(-12, 18);
  for (int i = 0; i < 20000; ++i) {
    const double v = mant(rng) * std::pow(10.0, exp(rng));
    const std::string s = format_number(v);
    EXPECT_EQ(parse_number(s, "x"), v) << s;
    EXPECT_NE(s.find('.'), std::string::npos) << s;
  }
}

}  // namespace
}  // namespace pgmcl::io
