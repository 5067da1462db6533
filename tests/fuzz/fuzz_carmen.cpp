// libFuzzer target: the CARMEN log parser (pgmcl::io::parse_carmen) and writer.
// Oracles beyond "no crash":
//  - lenient parsing never throws (carmen.hpp: FormatError only in strict mode);
//  - strict parsing throws FormatError exactly when the lenient report has malformed lines
//    or backwards timestamps, and otherwise returns the same records;
//  - report.lines counts the input's lines;
//  - every record the reader kept is written back by format_* and re-read identically
//    (carmen_writer.hpp: "read_carmen(write_carmen(log)) gives back the same values");
//  - read_carmen on the same bytes in a file (LineReader, gzip-transparent) gives the same
//    records and line count as parse_carmen in memory (carmen.hpp: "Same, from text").

#include <algorithm>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "fuzz_util.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/errors.hpp"

namespace {

using namespace pgmcl;
using namespace pgmcl::io;

bool same(double a, double b) {
  return a == b || (std::isnan(a) && std::isnan(b));
}
bool same(const Pose2& a, const Pose2& b) {
  return same(a.x, b.x) && same(a.y, b.y) && same(a.theta, b.theta);
}
bool same(const std::vector<float>& a, const std::vector<float>& b) {
  return std::equal(a.begin(), a.end(), b.begin(), b.end(),
                    [](float x, float y) { return same(x, y); });
}

bool same(const CarmenScan& a, const CarmenScan& b) {
  const LaserScan &s = a.scan, &t = b.scan;
  return a.message == b.message && same(a.stamp, b.stamp) && same(s.angle_min, t.angle_min) &&
         same(s.angle_increment, t.angle_increment) && same(s.range_min, t.range_min) &&
         same(s.range_max, t.range_max) && same(s.ranges, t.ranges) &&
         same(s.sensor_pose, t.sensor_pose) && a.config.laser_type == b.config.laser_type &&
         same(a.config.field_of_view, b.config.field_of_view) &&
         same(a.config.accuracy, b.config.accuracy) &&
         a.config.remission_mode == b.config.remission_mode && same(a.remissions, b.remissions) &&
         a.has_poses == b.has_poses && same(a.laser_pose, b.laser_pose) &&
         same(a.odom_pose, b.odom_pose) && same(a.extras.tv, b.extras.tv) &&
         same(a.extras.rv, b.extras.rv) &&
         same(a.extras.forward_safety_dist, b.extras.forward_safety_dist) &&
         same(a.extras.side_safety_dist, b.extras.side_safety_dist) &&
         same(a.extras.turn_axis, b.extras.turn_axis) && a.host == b.host &&
         same(a.logger_stamp, b.logger_stamp);
}
bool same(const OdomRecord& a, const OdomRecord& b) {
  return same(a.pose, b.pose) && same(a.tv, b.tv) && same(a.rv, b.rv) && same(a.accel, b.accel) &&
         same(a.stamp, b.stamp) && a.host == b.host && same(a.logger_stamp, b.logger_stamp);
}
bool same(const TruePosRecord& a, const TruePosRecord& b) {
  return same(a.true_pose, b.true_pose) && same(a.odom_pose, b.odom_pose) &&
         same(a.stamp, b.stamp) && a.host == b.host && same(a.logger_stamp, b.logger_stamp);
}

template <class T>
void expect_same_records(const std::vector<T>& a, const std::vector<T>& b, const char* what) {
  if (a.size() != b.size())
    fuzz::fail(what, "count " + std::to_string(a.size()) + " vs " + std::to_string(b.size()));
  for (std::size_t i = 0; i < a.size(); ++i) {
    if (!same(a[i], b[i])) fuzz::fail(what, "record " + std::to_string(i) + " differs");
  }
}

void expect_same_log(const CarmenLog& a, const CarmenLog& b, const char* what) {
  if (a.params != b.params) fuzz::fail(what, "params differ");
  expect_same_records(a.scans, b.scans, what);
  expect_same_records(a.odometry, b.odometry, what);
  expect_same_records(a.truepos, b.truepos, what);
}

std::size_t count_lines(std::string_view text) {
  const auto n = static_cast<std::size_t>(std::count(text.begin(), text.end(), '\n'));
  return n + (!text.empty() && text.back() != '\n' ? 1 : 0);
}

/// Writes the kept records back in file order; nullopt-like empty result when a record is
/// one the writer documents it cannot hold (std::invalid_argument).
bool rewrite(const CarmenLog& log, std::string& out) {
  std::vector<std::pair<std::size_t, std::string>> lines;
  try {
    for (const auto& [name, value] : log.params) out += format_param(name, value) + "\n";
    for (const auto& r : log.odometry) lines.emplace_back(r.line, format_odom(r));
    for (const auto& r : log.truepos) lines.emplace_back(r.line, format_truepos(r));
    for (const auto& s : log.scans) lines.emplace_back(s.line, format_scan(s));
  } catch (const std::invalid_argument&) {
    return false;
  }
  std::stable_sort(lines.begin(), lines.end(),
                   [](const auto& x, const auto& y) { return x.first < y.first; });
  for (const auto& [line, text] : lines) out += text + "\n";
  return true;
}

/// read_carmen on the bytes in a file must agree with parse_carmen on them in memory.
void check_file_matches_memory(std::string_view text, const CarmenLog& memory) {
  try {
    const CarmenLog file = read_carmen(fuzz::write_scratch("fuzz.log", text));
    if (file.report.lines != memory.report.lines ||
        file.report.malformed != memory.report.malformed)
      fuzz::fail("read_carmen(file) and parse_carmen(text) disagree",
                 "lines " + std::to_string(file.report.lines) + " vs " +
                     std::to_string(memory.report.lines) + ", malformed " +
                     std::to_string(file.report.malformed) + " vs " +
                     std::to_string(memory.report.malformed));
    expect_same_log(memory, file, "file vs memory");
  } catch (const IoError&) {
    // Documented for files: a corrupt gzip stream (the input may start with gzip's magic).
    if (text.size() < 2 || text[0] != '\x1f' || text[1] != '\x8b')
      fuzz::fail("IoError reading a plain file");
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string_view text = fuzz::as_text(data, size);
  CarmenLog lenient;
  try {
    lenient = parse_carmen(text, "fuzz.log");
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
  const ParseReport& rep = lenient.report;
  if (rep.lines != count_lines(text))
    fuzz::fail("report.lines",
               std::to_string(rep.lines) + " vs " + std::to_string(count_lines(text)));
  if (rep.malformed_lines.size() != std::min(rep.malformed, std::size_t{1000}))
    fuzz::fail("malformed_lines not capped as documented");
  (void)rep.summary();
  (void)scan_truth(lenient);
  (void)truepos_trajectory(lenient);
  (void)odometry_trajectory(lenient);

  CarmenReadOptions strict_opt;
  strict_opt.strict = true;
  const bool clean = rep.malformed == 0 && rep.backwards == 0;
  try {
    const CarmenLog strict = parse_carmen(text, "fuzz.log", strict_opt);
    if (!clean) fuzz::fail("strict parse accepted a log the lenient parse flagged");
    expect_same_log(lenient, strict, "strict vs lenient");
  } catch (const FormatError&) {
    if (clean) fuzz::fail("strict parse threw on a clean log");
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }

  check_file_matches_memory(text, lenient);

  std::string written;
  try {
    if (!rewrite(lenient, written)) return 0;
    const CarmenLog back = parse_carmen(written, "rewritten.log");
    if (back.report.malformed != 0)
      fuzz::fail("the writer produced a line the reader rejects",
                 back.report.malformed_lines.front().message);
    expect_same_log(lenient, back, "write/read round trip");
  } catch (const std::exception& e) {
    fuzz::undocumented(e);
  }
  return 0;
}
