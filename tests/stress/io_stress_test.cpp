// Hostile log input at the io boundary: a 1081-beam scan line whose header disagrees with
// its readings, absurd counts, and timestamps that repeat or go backwards. The reader must
// count and report each (line, field), keep going, and in strict mode stop with FormatError.

#include <gtest/gtest.h>

#include <algorithm>
#include <fstream>
#include <iterator>
#include <string>
#include <vector>

#include "format_error.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/errors.hpp"
#include "pgmcl/sims/sensor_profile.hpp"

namespace pgmcl::io {
namespace {

// A UTM-30LX scan (1081 beams, not the SICK layout) as a ROBOTLASER1 line.
std::string utm_line(double stamp) {
  const sims::SensorProfile p = sims::utm30lx();
  std::vector<float> ranges(1081);
  for (std::size_t i = 0; i < ranges.size(); ++i) ranges[i] = 1.0f + 0.001f * i;
  const CarmenScan rec = make_scan_record(p.make_scan(ranges, {0.1, 0, 0}), stamp, {1, 2, 0.3});
  EXPECT_EQ(rec.message, LaserMessage::kRobotLaser1);
  return format_scan(rec);
}

// Replaces the first occurrence of " <from> " in `line` (the reading count) by " <to> ".
std::string recount(std::string line, const std::string& from, const std::string& to) {
  const auto at = line.find(" " + from + " ");
  EXPECT_NE(at, std::string::npos);
  return line.replace(at + 1, from.size(), to);
}

TEST(StressCarmen, BeamCountDisagreeingWithItsHeaderIsCountedAndReported) {
  const std::string good = utm_line(10.0);
  const std::string text = good + "\n" + recount(utm_line(10.1), "1081", "1080") + "\n" +
                           recount(utm_line(10.2), "1081", "1082") + "\n" +
                           recount(utm_line(10.3), "1081", "999999999") + "\n" +
                           recount(utm_line(10.4), "1081", "-1081") + "\n" + utm_line(10.5) + "\n";
  const CarmenLog log = parse_carmen(text, "utm.log");
  ASSERT_EQ(log.scans.size(), 2u) << log.report.summary();
  EXPECT_EQ(log.scans[0].scan.ranges.size(), 1081u);
  EXPECT_EQ(log.scans[1].line, 6u);
  const ParseReport& r = log.report;
  ASSERT_EQ(r.malformed, 4u) << r.summary();
  for (std::size_t i = 0; i < 4; ++i) {
    const LineIssue& is = r.malformed_lines[i];
    EXPECT_EQ(is.line, i + 2);
    EXPECT_EQ(is.message_type, "ROBOTLASER1");
    EXPECT_EQ(is.field, "num_readings") << is.message;
  }
  EXPECT_NE(r.malformed_lines[0].message.find("1080"), std::string::npos);
  EXPECT_NE(r.malformed_lines[2].message.find("999999999"), std::string::npos);
  EXPECT_NE(r.summary().find("utm.log"), std::string::npos);

  CarmenReadOptions strict;
  strict.strict = true;
  const std::string error = testkit::expect_format_error(
      "strict mode accepted a miscounted scan",
      [&] { return parse_carmen(text, "utm.log", strict); }, 2, "num_readings");
  EXPECT_NE(error.find("utm.log:2: num_readings"), std::string::npos) << error;
}

TEST(StressCarmen, FlaserWithOneReadingTooFewOrTooMany) {
  std::string ranges;
  for (int i = 0; i < 180; ++i) ranges += " 1.5";
  const std::string tail = " 0 0 0 0 0 0 5.0 h 5.0";
  const std::string text = "FLASER 180" + ranges + tail + "\nFLASER 181" + ranges + tail +
                           "\nFLASER 179" + ranges + tail + "\n";
  const CarmenLog log = parse_carmen(text, "f.log");
  ASSERT_EQ(log.scans.size(), 1u);
  ASSERT_EQ(log.report.malformed, 2u);
  EXPECT_EQ(log.report.malformed_lines[0].line, 2u);
  EXPECT_EQ(log.report.malformed_lines[0].field, "num_readings");
  EXPECT_EQ(log.report.malformed_lines[1].line, 3u);
  EXPECT_EQ(log.report.malformed_lines[1].field, "num_readings");
}

// Repeated stamps are not "backwards"; decreasing ones are counted per type with the line,
// and the records are kept (the engine decides what to do with them).
TEST(StressCarmen, RepeatedAndBackwardsTimestamps) {
  const std::string text =
      "ODOM 0 0 0 0 0 0 5.0 h 5.0\n"
      "ODOM 0.1 0 0 0 0 0 5.0 h 5.0\n"        // repeated: fine
      "ODOM 100.1 0 0 0 0 0 5.1 h 5.1\n"      // a 100 m odometry jump: kept as logged
      "ODOM 0.2 0 0 0 0 0 4.0 h 4.0\n"        // backwards
      "ODOM 0.3 0 0 0 0 0 -1e9 h 0\n"         // far backwards
      "FLASER 2 1 1 0 0 0 0 0 0 3.0 h 3.0\n"  // other types keep their own clock
      "FLASER 2 1 1 0 0 0 0 0 0 3.0 h 3.0\n";
  const CarmenLog log = parse_carmen(text, "t.log");
  EXPECT_EQ(log.odometry.size(), 5u);
  EXPECT_EQ(log.scans.size(), 2u);
  EXPECT_EQ(log.odometry[2].pose.x, 100.1);
  ASSERT_EQ(log.report.backwards, 2u) << log.report.summary();
  EXPECT_EQ(log.report.backwards_by_type.at("ODOM"), 2u);
  EXPECT_EQ(log.report.backwards_lines[0].line, 4u);
  EXPECT_EQ(log.report.backwards_lines[1].line, 5u);
  EXPECT_EQ(log.report.malformed, 0u);
}

// Regression (found by fuzz_carmen's file-vs-memory oracle; fixed in 842f048): read_carmen
// (path) and parse_carmen(text) must agree on the same bytes. inputs/carmen_nul_bytes.log has NUL
// bytes inside a ROBOTLASER1 line: LineReader measured gzgets' chunk with strlen, missed
// the newline after the NUL and merged the next line (TRUEPOS) into it: 3 lines instead of
// 4, the TRUEPOS record lost. inputs/carmen_double_cr.log ends a line in "\r\r\n":
// LineReader stripped both '\r', parse_carmen one (its last field is then malformed).
TEST(StressCarmen, FileAndMemoryReadersAgree) {
  for (const char* name : {"carmen_nul_bytes.log", "carmen_double_cr.log"}) {
    SCOPED_TRACE(name);
    const std::string path = std::string(PGMCL_SOURCE_DIR) + "/tests/stress/inputs/" + name;
    std::ifstream in(path, std::ios::binary);
    ASSERT_TRUE(in) << path;
    const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
    const CarmenLog memory = parse_carmen(text, path);
    const CarmenLog file = read_carmen(path);
    EXPECT_EQ(file.report.lines, memory.report.lines);
    EXPECT_EQ(file.report.lines,
              static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n')));
    EXPECT_EQ(file.report.malformed, memory.report.malformed);
    EXPECT_EQ(file.scans.size(), memory.scans.size());
    EXPECT_EQ(file.odometry.size(), memory.odometry.size());
    EXPECT_EQ(file.truepos.size(), memory.truepos.size());
  }
}

}  // namespace
}  // namespace pgmcl::io
