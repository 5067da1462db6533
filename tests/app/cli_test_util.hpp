#pragma once
// Helpers for the tests that run the built `pgmcl` binary on small synthetic inputs.

#include <sys/wait.h>

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <numbers>
#include <string>
#include <vector>

#include "pgmcl/common/se2.hpp"
#include "pgmcl/io/carmen.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "room.hpp"
#include "temp_files.hpp"

namespace pgmcl::cli_test {

using testkit::read_text;
using testkit::TempDir;
using testkit::write_text;

struct RunResult {
  int code = -1;
  std::string out;
  std::string err;
};

/// Runs `pgmcl <args>` (args are passed to the shell as written) in `dir`.
inline RunResult run_pgmcl(const std::string& args, const TempDir& dir) {
  const std::string out = dir.file("stdout.txt"), err = dir.file("stderr.txt");
  const std::string cmd = "cd '" + dir.path().string() + "' && '" PGMCL_BINARY_DIR "/pgmcl' " +
                          args + " > '" + out + "' 2> '" + err + "'";
  const int status = std::system(cmd.c_str());
  RunResult r;
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = read_text(out);
  r.err = read_text(err);
  return r;
}

using Room = testkit::Room;

/// A corrected-style CARMEN log: one FLASER per pose (pose in x y theta and odom_*), SICK
/// layout with `beams` beams, ranges from `room`; every `no_return_every`-th beam (if > 0)
/// reads `no_return` metres ("no return").
inline io::CarmenLog room_log(const Room& room, const std::vector<Pose2>& poses, int beams = 180,
                              int no_return_every = 0, double no_return = 81.9) {
  io::CarmenLog log;
  const io::BeamLayout layout = io::sick_beam_layout(static_cast<std::size_t>(beams));
  for (std::size_t k = 0; k < poses.size(); ++k) {
    io::CarmenScan s;
    s.message = io::LaserMessage::kFlaser;
    s.stamp = 1.0 + 0.5 * static_cast<double>(k);
    s.scan.angle_min = layout.angle_min;
    s.scan.angle_increment = layout.angle_increment;
    for (int i = 0; i < beams; ++i) {
      const double a = poses[k].theta + layout.angle_min + i * layout.angle_increment;
      const bool lost = no_return_every > 0 && i % no_return_every == 0;
      s.scan.ranges.push_back(
          static_cast<float>(lost ? no_return : room.range(poses[k].x, poses[k].y, a)));
    }
    s.laser_pose = poses[k];
    s.odom_pose = poses[k];
    s.logger_stamp = s.stamp;
    log.scans.push_back(std::move(s));
  }
  return log;
}

/// Poses on an ellipse inside the default room with a turning heading.
inline std::vector<Pose2> room_loop(int n) {
  std::vector<Pose2> p;
  for (int k = 0; k < n; ++k) {
    const double phi = 2.0 * std::numbers::pi * k / n;
    p.push_back({3.4 + 1.6 * std::cos(phi), 2.6 + 1.2 * std::sin(phi), wrap_angle(phi + 1.6)});
  }
  return p;
}

/// The common start of the end-to-end tests: writes corrected.log (the exact log of
/// room_loop(`poses`) in the default room, 180 beams) to `dir` and maps it with `pgmcl map`
/// into `map_path`. Returns the map command's result.
inline RunResult map_room(const TempDir& dir, int poses, const std::string& map_path) {
  io::write_carmen(dir.file("corrected.log"), room_log(Room{}, room_loop(poses), 180));
  return run_pgmcl("map --log corrected.log --max-range 81.9 --out " + map_path, dir);
}

/// The localisation case of the end-to-end tests in `dir`: room.yaml (mapped from the exact
/// log of map_room(dir, 60)), raw.log (noisy odometry, seed 4) and truth.tum.
inline void prepare_localize_case(const TempDir& dir) {
  ASSERT_EQ(map_room(dir, 60, "room.yaml").code, 0);
  ASSERT_EQ(run_pgmcl("perturb --log corrected.log --odom-noise 0.01,0.001,0.01,0.001 --seed 4 "
                      "--out raw.log --truth-out truth.tum",
                      dir)
                .code,
            0);
}

}  // namespace pgmcl::cli_test
