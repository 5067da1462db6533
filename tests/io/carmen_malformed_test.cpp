// Malformed CARMEN lines are counted and reported with line number and field name, never
// silently dropped; strict mode turns them into FormatError.

#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "format_error.hpp"
#include "io_test_util.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/io/line_io.hpp"

namespace pgmcl::io {
namespace {

// One problem per line; the line numbers below are the oracle.
const char* const kSnippet =
    "# hand-written snippet: one problem per line\n"                               // 1
    "PARAM robot_front_laser_max 50 nohost 0\n"                                    // 2
    "ODOM 0 0 0 0 0 0 1.0 h 1.0\n"                                                 // 3
    "FLASER 3 1 2 3 0 0 0 0 0 0 1.5 h 1.5\n"                                       // 4 ok
    "FLASER 5 1 2 3 4 5 6 0 0 0 0 0 0 2.0 h 2.0\n"                                 // 5 count
    "ODOM 1 0 0 abc 0 0 2.5 h 2.5\n"                                               // 6 text
    "FLASER 180 1 2 3 4\n"                                                         // 7 cut
    "ODOM 2 0 0 0 0 0 0.5 h 0.5\n"                                                 // 8 back
    "FLASER 2 -1 nan 0 0 0 0 0 0 3.0 h 3.0\n"                                      // 9 beams
    "NEFF 15\n"                                                                    // 10 skip
    "ODOM 0 nan 0 0 0 0 3.5 h 3.5\n"                                               // 11 NaN
    "ROBOTLASER1 0 -1 2 1 10 0 0 3 1 2 3 2 0.5 0 0 0 0 0 0 0 0 0 0 0 4.0 h 4.0\n"  // 12
    "ODOM 0 0 0 0 0 0 4.5 h\n"                                                     // 13
    "TRUEPOS 0 0 0 0 0 0 5 h 5 extra\n"                                            // 14
    "FLASER 2 1 2 0 0 0 0 0 0 1.2 h 1.2\n"                                         // 15 back
    "FLASER 5 1 2 3 4 0 0 0 0 0 0 6.0 h 6.0\n";                                    // 16 count

struct Expected {
  std::size_t line;
  const char* type;
  const char* field;
  const char* message;
};

TEST(CarmenMalformed, CountedWithLineAndField) {
  const CarmenLog log = parse_carmen(kSnippet, "snippet.log");
  const ParseReport& r = log.report;
  const std::vector<Expected> expected = {
      {5, "FLASER", "num_readings", "declares 5 readings but the line holds 6"},
      {6, "ODOM", "tv", "not a number: 'abc'"},
      {7, "FLASER", "range[4]", "missing (the line ends after 6 fields)"},
      {11, "ODOM", "y", "not finite: 'nan'"},
      {12, "ROBOTLASER1", "num_remissions", "declares 2 remissions but the line holds 1"},
      {13, "ODOM", "logger_timestamp", "missing (the line ends after 9 fields)"},
      {14, "TRUEPOS", "logger_timestamp", "1 unexpected field(s) after it, from 'extra'"},
      {16, "FLASER", "num_readings", "declares 5 readings but the line holds 4"},
  };
  ASSERT_EQ(r.malformed, expected.size()) << r.summary();
  ASSERT_EQ(r.malformed_lines.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    const LineIssue& is = r.malformed_lines[i];
    EXPECT_EQ(is.line, expected[i].line);
    EXPECT_EQ(is.message_type, expected[i].type);
    EXPECT_EQ(is.field, expected[i].field) << "line " << is.line;
    EXPECT_EQ(is.message, expected[i].message) << "line " << is.line;
  }
  ASSERT_EQ(r.backwards, 2u);
  EXPECT_EQ(r.backwards_lines[0].line, 8u);
  EXPECT_EQ(r.backwards_lines[0].message_type, "ODOM");
  EXPECT_EQ(r.backwards_lines[0].field, "timestamp");
  EXPECT_EQ(r.backwards_lines[0].message, "goes backwards: 0.5 after 1 (previous ODOM on line 3)");
  EXPECT_EQ(r.backwards_lines[1].line, 15u);
  EXPECT_EQ(r.backwards_lines[1].message_type, "FLASER");
  EXPECT_EQ(r.invalid_beams, 2u);
  EXPECT_EQ(r.skipped.at("NEFF"), 1u);
  EXPECT_EQ(r.records.at("ODOM"), 2u);    // lines 3, 8 (backwards records are kept)
  EXPECT_EQ(r.records.at("FLASER"), 3u);  // lines 4, 9, 15
  EXPECT_EQ(r.records.at("PARAM"), 1u);
  EXPECT_EQ(r.records.count("ROBOTLASER1"), 0u);
  EXPECT_EQ(r.lines, 16u);
  ASSERT_EQ(log.scans.size(), 3u);
  EXPECT_EQ(log.scans[1].line, 9u);
  // The summary names the file, the line and the field.
  EXPECT_NE(r.summary().find("snippet.log:7: FLASER range[4]: missing"), std::string::npos)
      << r.summary();
}

TEST(CarmenMalformed, StrictModeThrowsFileLineField) {
  test::TempDir dir;
  const std::string path = dir.file("snippet.log");
  {
    LineWriter w(path);
    w.write_line(std::string(kSnippet).substr(0, std::string(kSnippet).size() - 1));
    w.close();
  }
  CarmenReadOptions strict;
  strict.strict = true;
  EXPECT_EQ(testkit::expect_format_error(
                "strict mode accepted a malformed line", [&] { return read_carmen(path, strict); },
                5, "num_readings"),
            path + ":5: num_readings: declares 5 readings but the line holds 6");
  // Lenient reading of the same file agrees with the in-memory parse.
  EXPECT_EQ(read_carmen(path).report.malformed, 8u);

  // A backwards timestamp alone is an error in strict mode too.
  const std::string backwards = "ODOM 0 0 0 0 0 0 2 h 2\nNEFF 1\nODOM 0 0 0 0 0 0 1 h 1\n";
  const std::string error = testkit::expect_format_error(
      "strict mode accepted a backwards timestamp",
      [&] { return parse_carmen(backwards, "b.log", strict); }, 3, "timestamp");
  EXPECT_EQ(error.rfind("b.log:3: timestamp: goes backwards", 0), 0u) << error;
}

// Cutting a valid line after every possible field must always be reported, naming exactly
// the first field that is missing.
TEST(CarmenMalformed, EveryTruncationNamesTheFirstMissingField) {
  struct Case {
    std::vector<std::string> tokens, names;
  };
  const std::vector<Case> cases = {
      {{"FLASER", "3", "1", "2", "3", "0", "0", "0", "0", "0", "0", "1.5", "h", "1.5"},
       {"", "num_readings", "range[0]", "range[1]", "range[2]", "x", "y", "theta", "odom_x",
        "odom_y", "odom_theta", "timestamp", "hostname", "logger_timestamp"}},
      {{"RAWLASER1", "0", "-1", "2", "1", "10", "0", "0", "2", "1", "2", "1", "0.5", "4", "h", "4"},
       {"", "laser_type", "start_angle", "field_of_view", "angular_resolution", "maximum_range",
        "accuracy", "remission_mode", "num_readings", "range[0]", "range[1]", "num_remissions",
        "remission[0]", "timestamp", "hostname", "logger_timestamp"}},
      {{"TRUEPOS", "1", "2", "3", "4", "5", "6", "7", "h", "7"},
       {"", "true_x", "true_y", "true_theta", "odom_x", "odom_y", "odom_theta", "timestamp",
        "hostname", "logger_timestamp"}},
  };
  for (const Case& c : cases) {
    std::string full;
    for (const auto& t : c.tokens) full += t + " ";
    EXPECT_EQ(parse_carmen(full, "t").report.malformed, 0u) << full;
    for (std::size_t k = 1; k < c.tokens.size(); ++k) {
      std::string line;
      for (std::size_t i = 0; i < k; ++i) line += c.tokens[i] + " ";
      const ParseReport r = parse_carmen(line, "t").report;
      ASSERT_EQ(r.malformed, 1u) << line;
      EXPECT_EQ(r.malformed_lines[0].field, c.names[k]) << line;
    }
  }
}

}  // namespace
}  // namespace pgmcl::io

namespace pgmcl::io {
namespace {

// The records' memory is capped (CarmenReadOptions::max_bytes): the error names the line
// that crosses it, strict or not.
TEST(CarmenMalformed, RecordsPastTheMemoryLimitAreAnErrorAtTheirLine) {
  std::string text;
  for (int i = 0; i < 50; ++i) text += "ODOM 0 0 0 0 0 0 " + std::to_string(i) + " h 0\n";
  CarmenReadOptions opt;
  opt.max_bytes = 20 * sizeof(OdomRecord);
  (void)testkit::expect_format_error(
      "50 records passed a limit of 20", [&] { return parse_carmen(text, "big.log", opt); }, 21,
      "log");
  opt.max_bytes = 50 * sizeof(OdomRecord);
  EXPECT_EQ(parse_carmen(text, "big.log", opt).odometry.size(), 50u);
}

// A ROBOTLASER1 / RAWLASER header whose field of view disagrees with resolution x readings
// drops the line (field_of_view); fov = res x (n - 1) and res x n are both accepted.
TEST(CarmenMalformed, FieldOfViewMustSpanTheReadings) {
  const auto raw = [](const std::string& fov) {
    return "RAWLASER1 0 -1.5 " + fov + " 1.5 8 0.01 0 3 1 2 3 0 1 h 1\n";
  };
  EXPECT_EQ(parse_carmen(raw("3"), "t").report.malformed, 0u);    // 1.5 x (3 - 1)
  EXPECT_EQ(parse_carmen(raw("4.5"), "t").report.malformed, 0u);  // 1.5 x 3
  const CarmenLog bad = parse_carmen(raw("1"), "t");
  ASSERT_EQ(bad.report.malformed, 1u);
  EXPECT_EQ(bad.report.malformed_lines[0].field, "field_of_view");
  CarmenReadOptions strict;
  strict.strict = true;
  EXPECT_THROW((void)parse_carmen(raw("1"), "t", strict), FormatError);
}

}  // namespace
}  // namespace pgmcl::io
