#pragma once
// Helpers for the `pgmcl perturb` tests: synthetic corrected logs and reading the outputs.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "pgmcl/common/se2.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/io/tum.hpp"

namespace pgmcl::perturb_test {

using cli_test::read_text;
using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

/// A zig-zag path of `n` poses made of identical increments (rot1, trans, rot2), so the
/// noise model's variances are the same for every step.
inline std::vector<Pose2> zigzag(int n, double rot1, double trans, double rot2) {
  std::vector<Pose2> p{{2.0, 2.0, 0.3}};
  for (int k = 1; k < n; ++k) {
    const Pose2& q = p.back();
    const double h = q.theta + rot1;
    p.push_back({q.x + trans * std::cos(h), q.y + trans * std::sin(h), wrap_angle(h + rot2)});
  }
  return p;
}

/// in.log: the room log of `poses` (one FLASER per pose, stamps 1.0 + 0.5 k).
inline void write_log(const cli_test::TempDir& dir, const std::vector<Pose2>& poses,
                      int beams = 5) {
  io::write_carmen(dir.file("in.log"), cli_test::room_log(cli_test::Room{}, poses, beams));
}

/// `pgmcl perturb --log in.log <options> --out raw.log --truth-out truth.tum` in `dir`.
inline RunResult run_perturb(const TempDir& dir, const std::string& options) {
  return run_pgmcl("perturb --log in.log " + options + " --out raw.log --truth-out truth.tum", dir);
}

struct Output {
  io::CarmenLog raw;
  io::Trajectory truth;
};

/// raw.log and truth.tum as the readers see them.
inline Output read_output(const cli_test::TempDir& dir) {
  return {io::read_carmen(dir.file("raw.log")), io::read_tum(dir.file("truth.tum"))};
}

/// The odometry increments of the output, from its ODOM records.
inline std::vector<Pose2> odometry_increments(const Output& o) {
  std::vector<Pose2> inc;
  for (std::size_t i = 1; i < o.raw.odometry.size(); ++i) {
    inc.push_back(o.raw.odometry[i - 1].pose.between(o.raw.odometry[i].pose));
  }
  return inc;
}

inline constexpr double kDeg = 3.14159265358979323846 / 180.0;

/// A command line that must be refused.
struct UsageCase {
  std::string args;     ///< appended to the command
  std::string message;  ///< expected in the "pgmcl: error: ..." line
};

/// Runs `command + c.args` in `dir` for each case: exit code 2, c.message on stderr, and
/// none of `never_written` (file names in `dir`) created.
inline void expect_usage_errors(const TempDir& dir, const std::string& command,
                                const std::vector<UsageCase>& cases,
                                const std::vector<std::string>& never_written) {
  for (const UsageCase& c : cases) {
    SCOPED_TRACE(c.args);
    const RunResult r = run_pgmcl(command + c.args, dir);
    EXPECT_EQ(r.code, 2);
    EXPECT_NE(r.err.find("pgmcl: error: "), std::string::npos) << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    for (const std::string& f : never_written) {
      EXPECT_FALSE(std::filesystem::exists(dir.file(f))) << f;
    }
  }
}

}  // namespace pgmcl::perturb_test
