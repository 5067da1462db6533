// ThreadPolicy: the team or one thread, from recorded costs; no clock involved.
#include "pgmcl/mcl/thread_policy.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cstdint>
#include <vector>

namespace pgmcl {
namespace {

/// Runs `n` updates whose cost per unit of work is `team_cost` with the team and
/// `serial_cost` with one thread; returns the counts next() chose.
std::vector<int> drive(ThreadPolicy& p, int n, double team_cost, double serial_cost) {
  std::vector<int> used;
  for (int i = 0; i < n; ++i) {
    const int t = p.next();
    used.push_back(t);
    p.record(t, (t == 1 ? serial_cost : team_cost) * 1000.0, 1000.0);
  }
  return used;
}

int count(const std::vector<int>& v, int x) {
  int c = 0;
  for (int y : v) c += y == x;
  return c;
}

TEST(ThreadPolicy, SerialRequestIsAlwaysSerial) {
  ThreadPolicy p(1);
  EXPECT_EQ(count(drive(p, 200, 0.5, 1.0), 1), 200);
}

TEST(ThreadPolicy, KeepsTheTeamWhenItIsFasterAndTriesSeriallyRarely) {
  ThreadPolicy p(2);
  const std::vector<int> used = drive(p, 640, 0.6, 1.0);
  EXPECT_EQ(used[0], 2);
  EXPECT_EQ(used[1], 2);
  EXPECT_EQ(used[2], 1);  // the first try, after the warm-up
  EXPECT_EQ(p.preferred(), 2);
  // One try per kProbeEvery updates (plus the first).
  EXPECT_LE(count(used, 1), 640 / static_cast<int>(ThreadPolicy::kProbeEvery) + 1);
}

TEST(ThreadPolicy, FollowsTheLoadBothWays) {
  ThreadPolicy p(2);
  (void)drive(p, 100, 0.6, 1.0);
  ASSERT_EQ(p.preferred(), 2);
  // A busy core: the team now costs twice the serial time; within a few updates the
  // mean of the team's samples passes the serial one.
  const std::vector<int> busy = drive(p, 200, 2.0, 1.05);
  EXPECT_EQ(p.preferred(), 1);
  int team_after_switch = 0;
  for (std::size_t i = 10; i < busy.size(); ++i) team_after_switch += busy[i] == 2;
  EXPECT_LE(team_after_switch, 2);  // tries after 64, then 128 updates
  for (int i = 0; i < 2; ++i) EXPECT_EQ(busy[static_cast<std::size_t>(i)], 2);
  // The load goes: the next try, at most kMaxProbeEvery updates on, wins, is repeated at
  // once, and the team is back.
  const std::vector<int> quiet =
      drive(p, static_cast<int>(ThreadPolicy::kMaxProbeEvery) + 20, 0.6, 1.0);
  EXPECT_EQ(p.preferred(), 2);
  int first_try = -1;
  for (std::size_t i = 0; i < quiet.size(); ++i)
    if (quiet[i] == 2) {
      first_try = static_cast<int>(i);
      break;
    }
  ASSERT_GE(first_try, 0);
  // From the first winning try on, the team is used on every update but the tries of one
  // thread, which lose (after 64 updates, then 128, ...).
  for (std::size_t i = static_cast<std::size_t>(first_try);
       i < std::min(quiet.size(), static_cast<std::size_t>(first_try) + 60); ++i)
    EXPECT_EQ(quiet[i], 2) << "update " << i;
  EXPECT_LE(count(std::vector<int>(quiet.begin() + first_try, quiet.end()), 1), 3);
}

TEST(ThreadPolicy, TriesThatKeepLosingComeLater) {
  ThreadPolicy p(2);
  const std::vector<int> used = drive(p, 2000, 2.0, 1.0);  // a busy core throughout
  EXPECT_EQ(p.preferred(), 1);
  std::vector<int> tries;  // updates that ran the team after the first switch
  for (std::size_t i = 10; i < used.size(); ++i)
    if (used[i] == 2) tries.push_back(static_cast<int>(i));
  // 64, 128, 256, then every 512 updates: 6 tries instead of 31 at a fixed 64.
  ASSERT_EQ(tries.size(), 6u);
  for (std::size_t k = 1; k < tries.size(); ++k) {
    const int gap = tries[k] - tries[k - 1];
    EXPECT_EQ(gap, static_cast<int>(std::min<std::uint64_t>(ThreadPolicy::kProbeEvery << k,
                                                            ThreadPolicy::kMaxProbeEvery)));
  }
}

TEST(ThreadPolicy, AHiccupCostsOnlyAFewSerialUpdates) {
  ThreadPolicy p(2);
  (void)drive(p, 100, 0.6, 1.0);
  // One team update hit by a hiccup costs 5x: the mean of five sees it and one thread
  // runs until the tries, which win, have pushed it out of the window.
  p.record(2, 5000.0, 1000.0);
  p.record(2, 0.0, 1000.0);  // not a measurement: ignored
  p.record(2, 1.0, 0.0);
  const std::vector<int> after = drive(p, 200, 0.6, 1.0);
  EXPECT_EQ(p.preferred(), 2);
  EXPECT_LE(count(after, 1), static_cast<int>(ThreadPolicy::kProbeEvery) + 5);
}

bool taken() noexcept {
  return true;
}
bool free_cores() noexcept {
  return false;
}

TEST(ThreadPolicy, BesideBusyCoresTheTeamIsNeitherStartedNorTried) {
  // The run queue says the other cores are taken: not one update runs on the team, where
  // each would wait out another process's time slice.
  ThreadPolicy p(2, &taken);
  const std::vector<int> used = drive(p, 2000, 2.0, 1.0);
  EXPECT_EQ(count(used, 2), 0);
  EXPECT_EQ(p.preferred(), 1);
}

TEST(ThreadPolicy, FreeCoresLeaveTheTriesAsTheyWere) {
  ThreadPolicy probed(2, &free_cores), blind(2);
  EXPECT_EQ(drive(probed, 1000, 0.6, 1.0), drive(blind, 1000, 0.6, 1.0));
  EXPECT_EQ(drive(probed, 1000, 2.0, 1.0), drive(blind, 1000, 2.0, 1.0));
}

TEST(ThreadPolicy, TheRunQueueTakesTheCoresWhenItHoldsAsManyAsThereAre) {
  // /proc/loadavg's fourth field: runnable entities (the caller included) / all of them.
  EXPECT_TRUE(run_queue_full("2.10 1.80 1.20 2/345 6789\n", 2));
  EXPECT_TRUE(run_queue_full("2.10 1.80 1.20 5/345 6789\n", 4));
  EXPECT_FALSE(run_queue_full("0.50 0.40 0.30 1/345 6789\n", 2));
  EXPECT_FALSE(run_queue_full("2.10 1.80 1.20 3/345 6789\n", 4));
  EXPECT_FALSE(run_queue_full("2.10 1.80 1.20 7/345 6789\n", 1));  // no team to spare
  EXPECT_FALSE(run_queue_full("", 2));                             // unreadable: no claim
  EXPECT_FALSE(run_queue_full("garbage", 2));
}

}  // namespace
}  // namespace pgmcl
