// Hostile scans, odometry and time for the Localizer: scans no pose can explain (all
// max-range, all NaN, taken from inside a wall, boxed in by unmapped clutter), 100 m
// odometry jumps, repeated and backwards timestamps, and beam counts that disagree with
// the configured sensor. Nothing may turn NaN, every update must say why it did little, and
// the filter must get back on track (augmented MCL injecting where the scans still count).

#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <iostream>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>
#include <vector>

#include "pgmcl/common/enum_names.hpp"
#include "pgmcl/mcl/localizer.hpp"
#include "stress_drive.hpp"
#include "stress_world.hpp"

namespace pgmcl::stress {
namespace {

constexpr double kDeg = std::numbers::pi / 180.0;
constexpr float kNaNf = std::numeric_limits<float>::quiet_NaN();

// An 8 m x 6 m room at 5 cm and one lap through its free space in 12 cm steps.
struct Lap {
  Room room = make_room(8.0, 6.0, 0.05);
  std::vector<Pose2> truth =
      waypoint_path({{1.0, 2.8}, {7.7, 2.8}, {7.7, 5.5}, {1.0, 5.5}, {1.0, 2.8}}, 0.12, 0.15);
  std::vector<Pose2> odom = noisy_odometry(truth, MotionNoise{}, 23);
  Scanner scanner{room.grid, 0.01};

  void truncate(std::size_t n) {
    truth.resize(std::min(n, truth.size()));
    odom.resize(truth.size());
  }
};

enum class Hostile { kMaxRange, kNaN, kInsideWall, kBoxedIn };

constexpr std::array<EnumName<Hostile>, 4> kHostileNames{{
    {Hostile::kMaxRange, "all_max_range"},
    {Hostile::kNaN, "all_nan"},
    {Hostile::kInsideWall, "inside_a_wall"},
    {Hostile::kBoxedIn, "boxed_in"},
}};

const char* name(Hostile h) {
  return name_of(h, kHostileNames);
}

class EveryBeamImpossible : public ::testing::TestWithParam<Hostile> {};

// Steps [20, 45) get the hostile scan; before and after, normal ones.
TEST_P(EveryBeamImpossible, NothingNaNTheUpdateSaysWhyAndTheFilterRecovers) {
  const Hostile kind = GetParam();
  Lap lap;
  Localizer loc(lap.room.grid, LocalizerConfig{});
  loc.set_pose(lap.truth[0], diag_cov(0.05, 2 * kDeg));
  constexpr std::size_t kBegin = 20, kEnd = 45;
  lap.truncate(kEnd + 50);
  // A pose inside the 5 cm thick bottom wall: every ray starts in a blocking cell.
  const LaserScan wall_scan = [&] {
    Rng rng(1);
    return Scanner(lap.room.grid).scan({4.0, 0.225, 0.0}, rng);  // noise-free: exactly 0
  }();
  std::size_t injected = 0, hostile_measured = 0;
  std::vector<UpdateResult> hostile;
  std::vector<bool> converged;  // per step, from the step before the hook's
  const RunErrors e = drive(loc, lap.scanner, lap.room.grid, lap.truth, lap.odom, 9, kEnd + 40,
                            on_scan([&](std::size_t k, LaserScan& scan) {
                              converged.resize(k);
                              if (k > 0) converged[k - 1] = loc.last_result().converged;
                              if (k > kBegin && k <= kEnd)
                                hostile.push_back(loc.last_result());  // step k - 1
                              if (k < kBegin || k >= kEnd) return;
                              switch (kind) {
                                case Hostile::kMaxRange:
                                  std::fill(scan.ranges.begin(), scan.ranges.end(),
                                            static_cast<float>(scan.range_max));
                                  break;
                                case Hostile::kNaN:
                                  std::fill(scan.ranges.begin(), scan.ranges.end(), kNaNf);
                                  break;
                                case Hostile::kInsideWall:
                                  scan.ranges = wall_scan.ranges;
                                  break;
                                case Hostile::kBoxedIn:
                                  std::fill(scan.ranges.begin(), scan.ranges.end(), 0.15f);
                                  break;
                              }
                            }));
  EXPECT_TRUE(e.all_finite);
  ASSERT_EQ(hostile.size(), kEnd - kBegin);
  for (const UpdateResult& r : hostile) {
    EXPECT_EQ(r.beams_total, 1081u);
    injected += r.injected;
    hostile_measured += r.measured() ? 1 : 0;
    if (kind == Hostile::kBoxedIn) {
      EXPECT_TRUE(r.measured());
      EXPECT_EQ(r.beams_invalid, 0u);
    } else {
      EXPECT_EQ(r.skipped, SkipReason::kNoValidBeams) << to_string(r.skipped);
      EXPECT_EQ(r.beams_invalid, 1081u);
      EXPECT_EQ(r.beams_used, 0u);
      EXPECT_FALSE(r.resampled);
    }
  }
  if (kind == Hostile::kInsideWall) {
    for (const float r : wall_scan.ranges) ASSERT_EQ(r, 0.0f);
  }
  if (kind == Hostile::kBoxedIn) {
    // Valid readings that end in free space from the tracked pose: the update says the scan
    // matched nothing (every used beam read the background)...
    EXPECT_EQ(hostile.front().beams_background, hostile.front().beams_used);
    // ...and augmented MCL injects once w_fast drops below w_slow. (Seen: the cloud then
    // settles *inside* a piece of furniture, where obstacles do surround the robot at 0.15 m:
    // the likelihood field never penalises a particle in an occupied cell.)
    EXPECT_GT(injected, 0u) << "augmented MCL must inject when the scans stop matching";
  } else {
    EXPECT_EQ(hostile_measured, 0u);
    EXPECT_EQ(injected, 0u) << "no measurement, no evidence of being lost";
  }
  std::cout << "  " << name(kind) << ": injected " << injected << " during the hostile phase"
            << ", error at its end " << e.xy[kEnd - 1] << " m, final " << e.xy.back()
            << " m, RMSE after recovery " << e.rmse_xy << " m\n";
  if (kind == Hostile::kBoxedIn) {
    // After the impossible phase the filter sits in a piece of furniture and comes back on
    // the truth or, as often (2 of 6 seeds either way, before and after the free-space
    // checks), on a place of this near-symmetric room that fits almost as well. What it
    // must not do is claim to be localised there while the sweep finds a better place.
    std::size_t run = 0, longest = 0;
    for (std::size_t k = kEnd; k < converged.size(); ++k) {
      run = converged[k] && e.xy[k] > 1.0 ? run + 1 : 0;
      longest = std::max(longest, run);
    }
    EXPECT_LE(longest, 3u) << "reported converged while more than 1 m off";
    return;
  }
  EXPECT_LT(e.rmse_xy, 0.08) << "back on track 40 steps after the hostile phase";
  EXPECT_LT(e.xy.back(), 0.1);
}

INSTANTIATE_TEST_SUITE_P(Stress, EveryBeamImpossible,
                         ::testing::Values(Hostile::kMaxRange, Hostile::kNaN, Hostile::kInsideWall,
                                           Hostile::kBoxedIn),
                         [](const auto& info) { return std::string(name(info.param)); });

// Odometry that jumps 100 m (a wheel-encoder glitch or an odometry frame reset) while the
// robot does not move: once and staying shifted, or as a one-reading spike. The particles
// are thrown off the map, where every beam reads the background; nothing may turn NaN and
// the filter must find the robot again: after a shift by redrawing particles (augmented
// MCL's injection or a scan-matching hypothesis), after a spike the odometry itself
// jumps back.
TEST(StressTimeAndMotion, OdometryJumpsOf100m) {
  for (const bool spike : {false, true}) {
    SCOPED_TRACE(spike ? "one-reading spike" : "permanent shift");
    Lap lap;
    lap.truncate(130);
    constexpr std::size_t kJump = 30;
    const Pose2 jump{100.0, 0.0, 0.0};
    for (std::size_t k = kJump; k < lap.odom.size(); ++k) {
      if (!spike || k == kJump) lap.odom[k] = jump.compose(lap.odom[k]);
    }
    Localizer loc(lap.room.grid, LocalizerConfig{});
    loc.set_pose(lap.truth[0], diag_cov(0.05, 2 * kDeg));
    std::vector<UpdateResult> after;
    const RunErrors e = drive(loc, lap.scanner, lap.room.grid, lap.truth, lap.odom, 4, 100,
                              on_scan([&](std::size_t k, LaserScan&) {
                                if (k > kJump && k <= kJump + 40)
                                  after.push_back(loc.last_result());
                              }));
    EXPECT_TRUE(e.all_finite);
    const UpdateResult& at = after.front();
    EXPECT_TRUE(at.motion_applied);
    EXPECT_TRUE(at.measured());
    EXPECT_GT(e.xy[kJump], 10.0) << "the jump was applied";
    std::size_t injected = 0, seeded = 0;
    for (const UpdateResult& r : after) {
      injected += r.injected;
      seeded += r.seeded;
    }
    if (!spike) {
      EXPECT_GT(injected + seeded, 0u);
    }
    std::cout << "  " << (spike ? "spike" : "shift") << ": error after the jump " << e.xy[kJump]
              << " m, background beams " << at.beams_background << "/" << at.beams_used
              << ", injected " << injected << " and seeded " << seeded
              << " in 40 steps, final error " << e.xy.back() << " m, RMSE over the last 30 steps "
              << e.rmse_xy << " m\n";
    EXPECT_LT(e.rmse_xy, 0.1);
    EXPECT_LT(e.xy.back(), 0.1);
  }
}

// Stamps that repeat (two scans per stamp) are not "backwards" and change nothing.
TEST(StressTimeAndMotion, RepeatedTimestampsTrackNormally) {
  Lap lap;
  lap.truncate(90);
  Localizer loc(lap.room.grid, LocalizerConfig{});
  loc.set_pose(lap.truth[0], diag_cov(0.05, 2 * kDeg));
  const RunErrors e =
      drive(loc, lap.scanner, lap.room.grid, lap.truth, lap.odom, 6, 5,
            with_stamps([](std::size_t k) { return 0.2 * static_cast<double>(k / 2); }));
  EXPECT_TRUE(e.all_finite);
  EXPECT_EQ(e.rejected, 0u);
  EXPECT_GT(e.measured, lap.truth.size() * 3 / 4);
  EXPECT_LT(e.rmse_xy, 0.05);
}

// Stamps that go backwards. kThrow, with every 7th stamp 50 ms before the previous one
// (out-of-order messages): that update throws std::invalid_argument and leaves the particles
// untouched; the odometry chain continues, so the filter tracks on the other scans.
// kReset, with one jump 10 s back (a replayed log looping around): the update reports
// kTimeWentBackwards, leaves the particles untouched, and the next update restarts the
// odometry chain; the motion across the reset is lost (two steps here) and the scans must
// pull the filter back. (kReset is not meant for jitter: with every 7th stamp backwards it
// loses 2 of every 7 motion steps and the filter drifts off, RMSE ~1.5 m in this room.)
TEST(StressTimeAndMotion, TimestampsGoingBackwards) {
  for (const TimeBackwardsPolicy policy :
       {TimeBackwardsPolicy::kThrow, TimeBackwardsPolicy::kReset}) {
    const bool reset = policy == TimeBackwardsPolicy::kReset;
    SCOPED_TRACE(reset ? "kReset" : "kThrow");
    const auto backwards_at = [reset](std::size_t k) { return reset ? k == 40 : k % 7 == 6; };
    const auto stamp = [&](std::size_t k) {
      const double t = 0.1 * static_cast<double>(k);
      if (reset) return k >= 40 ? t - 10.0 : t;
      return backwards_at(k) ? t - 0.15 : t;
    };
    Lap lap;
    lap.truncate(90);
    LocalizerConfig cfg;
    cfg.time_backwards = policy;
    Localizer loc(lap.room.grid, cfg);
    loc.set_pose(lap.truth[0], diag_cov(0.05, 2 * kDeg));
    std::size_t backwards = 0, untouched = 0, expected = 0;
    std::vector<float> x_before;
    const RunErrors e =
        drive(loc, lap.scanner, lap.room.grid, lap.truth, lap.odom, 8, 5,
              with_stamps(stamp, [&](std::size_t k, LaserScan&) {
                if (k > 0 && backwards_at(k - 1)) {
                  ++expected;
                  backwards += loc.last_result().skipped == SkipReason::kTimeWentBackwards;
                  const auto x = loc.particles().x;
                  untouched += std::equal(x.begin(), x.end(), x_before.begin(), x_before.end());
                }
                x_before.assign(loc.particles().x.begin(), loc.particles().x.end());
              }));
    EXPECT_TRUE(e.all_finite);
    EXPECT_EQ(e.rejected, reset ? 0u : expected);
    EXPECT_EQ(backwards, reset ? expected : 0u);
    EXPECT_EQ(untouched, expected) << "a backwards step never moves a particle";
    std::cout << "  " << (reset ? "kReset" : "kThrow") << ": " << expected
              << " backwards stamps, RMSE " << e.rmse_xy << " m, max " << e.max_xy << " m\n";
    EXPECT_LT(e.rmse_xy, 0.06);
    EXPECT_LT(e.xy.back(), 0.06);
  }
}

// Regression (fixed in 361069c): odometry garbage that is finite but absurd (1e30 m, as from
// a corrupted log) threw the particles to coordinates beyond int range in cells; the hot
// loop's floor_to_cell then cast them to int (UB, caught by UBSan in the Debug build).
// Wanted: every beam reads the background (off the map), nothing NaN, and recovery once the
// odometry is sane again.
TEST(StressTimeAndMotion, OdometryGarbageOf1e30m) {
  Lap lap;
  lap.truncate(110);
  constexpr std::size_t kGlitch = 30;
  lap.odom[kGlitch] = Pose2{1e30, -1e30, 0.0}.compose(lap.odom[kGlitch]);
  Localizer loc(lap.room.grid, LocalizerConfig{});
  loc.set_pose(lap.truth[0], diag_cov(0.05, 2 * kDeg));
  std::vector<UpdateResult> after;
  const RunErrors e = drive(loc, lap.scanner, lap.room.grid, lap.truth, lap.odom, 4, 90,
                            on_scan([&](std::size_t k, LaserScan&) {
                              if (k > kGlitch && k <= kGlitch + 40) {
                                after.push_back(loc.last_result());
                              }
                            }));
  EXPECT_TRUE(e.all_finite);
  EXPECT_TRUE(after.front().measured());
  EXPECT_EQ(after.front().beams_background, after.front().beams_used);
  std::size_t injected = 0;
  for (const UpdateResult& r : after) injected += r.injected;
  EXPECT_GT(injected, 0u);
  std::cout << "  error after the glitch " << e.xy[kGlitch] << " m, final " << e.xy.back()
            << " m\n";
  EXPECT_LT(e.rmse_xy, 0.1);
}

// A scan whose beam count disagrees with the configured sensor (expected_beams = 1081) is a
// clear std::invalid_argument naming both counts, with the filter state untouched; with
// expected_beams = 0 any count is scored (none: kNoValidBeams).
TEST(StressTimeAndMotion, BeamCountDisagreeingWithTheConfiguredSensor) {
  const Room room = make_room(8.0, 6.0, 0.05);
  const Scanner scanner(room.grid);
  Rng rng(2);
  const Pose2 truth{3.0, 3.0, 0.5};
  const LaserScan good = scanner.scan(truth, rng);
  const auto with_beams = [&](std::size_t n) {
    LaserScan s = good;
    s.ranges.assign(n, 2.0f);
    if (n > 1) s.angle_increment = (good.size() - 1) * good.angle_increment / (n - 1);
    return s;
  };
  LocalizerConfig cfg;
  cfg.likelihood.expected_beams = 1081;
  Localizer loc(room.grid, cfg);
  loc.set_pose(truth, diag_cov(0.05, 2 * kDeg));
  ASSERT_TRUE(loc.update({}, good, 0.0).measured());
  const std::vector<float> x0(loc.particles().x.begin(), loc.particles().x.end());
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{1080}, std::size_t{1082},
                              std::size_t{100000}}) {
    try {
      (void)loc.update({1.0, 0.0, 0.0}, with_beams(n), 1.0);
      ADD_FAILURE() << n << " beams accepted";
    } catch (const std::invalid_argument& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(std::to_string(n) + " readings"), std::string::npos) << what;
      EXPECT_NE(what.find("1081"), std::string::npos) << what;
    }
    EXPECT_TRUE(
        std::equal(x0.begin(), x0.end(), loc.particles().x.begin(), loc.particles().x.end()));
  }
  cfg.likelihood.expected_beams = 0;
  Localizer any(room.grid, cfg);
  any.set_pose(truth, diag_cov(0.05, 2 * kDeg));
  double stamp = 0.0;
  for (const std::size_t n : {std::size_t{0}, std::size_t{1}, std::size_t{100000}}) {
    any.force_update();
    const UpdateResult r = any.update({}, with_beams(n), stamp += 1.0);
    EXPECT_EQ(r.beams_total, n);
    EXPECT_EQ(r.measured(), n > 0) << n;
    EXPECT_EQ(r.skipped, n > 0 ? SkipReason::kNone : SkipReason::kNoValidBeams) << n;
    EXPECT_TRUE(result_finite(r));
  }
}

}  // namespace
}  // namespace pgmcl::stress
