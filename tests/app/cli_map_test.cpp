// `pgmcl map` on a synthetic square-room log: walls occupied within one cell, interior free.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "cli_test_util.hpp"
#include "pgmcl/io/carmen_writer.hpp"
#include "pgmcl/map_io/map_io.hpp"

namespace pgmcl {
namespace {

using cli_test::run_pgmcl;
using cli_test::RunResult;
using cli_test::TempDir;

double distance_to_walls(const cli_test::Room& r, double x, double y) {
  const bool inside_x = x >= r.x0 && x <= r.x1, inside_y = y >= r.y0 && y <= r.y1;
  double d = 1e9;
  if (inside_y) d = std::min({d, std::abs(x - r.x0), std::abs(x - r.x1)});
  if (inside_x) d = std::min({d, std::abs(y - r.y0), std::abs(y - r.y1)});
  for (const double cx : {r.x0, r.x1})
    for (const double cy : {r.y0, r.y1}) d = std::min(d, std::hypot(x - cx, y - cy));
  return d;
}

struct RoomMapStats {
  int occupied = 0, occupied_off_wall = 0, interior = 0, interior_free = 0;
  int behind_wall_known = 0, beyond_clear_range_known = 0;
};

// Walls: every occupied cell within one cell of a wall. Interior: free. Behind the walls:
// unknown, except where "no return" beams cleared (at most clear_range from a sensor).
RoomMapStats room_map_stats(const maps::OccupancyGrid& g, const cli_test::Room& room,
                            const std::vector<Pose2>& poses, double clear_range) {
  RoomMapStats s;
  for (int row = 0; row < g.height(); ++row) {
    for (int col = 0; col < g.width(); ++col) {
      double x = 0, y = 0;
      g.cell_center_global(col, row, x, y);
      const double d = distance_to_walls(room, x, y);
      const bool inside = x > room.x0 && x < room.x1 && y > room.y0 && y < room.y1;
      const auto v = g.at(col, row);
      if (v == maps::kOccupied) {
        ++s.occupied;
        s.occupied_off_wall += d > 0.05;
      }
      if (inside && d > 0.1) {
        ++s.interior;
        s.interior_free += v == maps::kFree;
      }
      if (!inside && d > 0.1) {
        s.behind_wall_known += v != maps::kUnknown;
        double nearest = 1e9;
        for (const Pose2& p : poses) nearest = std::min(nearest, std::hypot(x - p.x, y - p.y));
        if (nearest > clear_range + 0.05) s.beyond_clear_range_known += v != maps::kUnknown;
      }
    }
  }
  return s;
}

TEST(CliMap, SquareRoomWallsOccupiedInteriorFree) {
  TempDir dir("cli_map_room");
  const cli_test::Room room;
  const auto poses = cli_test::room_loop(30);
  io::write_carmen(dir.file("room.log"), cli_test::room_log(room, poses, 180));
  const RunResult r =
      run_pgmcl("map --log room.log --resolution 0.05 --max-range 81.9 --out out/room.yaml", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("30 scans"), std::string::npos) << r.out;

  const maps::OccupancyGrid g = maps::load_map(dir.file("out/room.yaml"));
  EXPECT_DOUBLE_EQ(g.resolution(), 0.05);
  const RoomMapStats s = room_map_stats(g, room, poses, 5.0);
  EXPECT_EQ(s.occupied_off_wall, 0);
  EXPECT_EQ(s.interior_free, s.interior);
  EXPECT_EQ(s.behind_wall_known, 0);
  // The walls' perimeter is ~20.5 m: about 410 cells of 5 cm, at least one per wall cell.
  EXPECT_GT(s.occupied, 380);
  EXPECT_LT(s.occupied, 900);
  // Map bounds: data plus the 1 m default margin.
  EXPECT_NEAR(g.origin().x, room.x0 - 1.0, 0.06);
  EXPECT_NEAR(g.origin().y, room.y0 - 1.0, 0.06);
}

TEST(CliMap, NoReturnReadingsClearOnlyUpToTheCap) {
  TempDir dir("cli_map_noreturn");
  const cli_test::Room room;
  const auto poses = cli_test::room_loop(30);
  // Every 7th beam reads 81.9 m, the log's largest reading, which the reader takes as the
  // scanner maximum ("no return", like glass or a black wall): it must mark nothing
  // occupied and clear free space only up to --clear-range.
  io::write_carmen(dir.file("room.log"), cli_test::room_log(room, poses, 180, 7, 81.9));
  const RunResult r = run_pgmcl("map --log room.log --clear-range 3 --out room.yaml", dir);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("no-return range 81.90 m"), std::string::npos) << r.out;
  const maps::OccupancyGrid g = maps::load_map(dir.file("room.yaml"));
  const RoomMapStats s = room_map_stats(g, room, poses, 3.0);
  EXPECT_EQ(s.occupied_off_wall, 0);
  EXPECT_EQ(s.interior_free, s.interior);
  EXPECT_EQ(s.beyond_clear_range_known, 0);
  EXPECT_GT(s.occupied, 380);
}

TEST(CliMap, BadInputsNameFileLineAndField) {
  TempDir dir("cli_map_errors");
  cli_test::write_text(dir.file("bad.log"),
                       "FLASER 3 1.0 1.0 1.0 0 0 0 0 0 0 1.0 host 1.0\n"
                       "FLASER 3 1.0 oops 1.0 0 0 0 0 0 0 2.0 host 2.0\n"
                       "FLASER 3 1.0 1.0 2.0 0 0 0 0 0 0 3.0 host 3.0\n"
                       "FLASER 3 1.0 1.0\n");
  RunResult r = run_pgmcl("map --log bad.log --out m.yaml --strict", dir);
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("pgmcl: error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.log:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("range"), std::string::npos) << r.err;
  EXPECT_EQ(r.err.find("terminate"), std::string::npos);

  // Without --strict the lines are dropped with a warning naming each, and the map is built.
  r = run_pgmcl("map --log bad.log --out m.yaml", dir);
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.err.find("pgmcl: warning: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("dropped 2 malformed line(s)"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.log:2"), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bad.log:4"), std::string::npos) << r.err;

  r = run_pgmcl("map --log bad.log --out m.yaml --resolution -1", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--resolution"), std::string::npos) << r.err;

  r = run_pgmcl("map --log missing.log --out m.yaml", dir);
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("missing.log"), std::string::npos) << r.err;

  cli_test::write_text(dir.file("empty.log"), "PARAM robot_frontlaser_offset 0.0 nohost 0\n");
  r = run_pgmcl("map --log empty.log --out m.yaml", dir);
  EXPECT_NE(r.code, 0);
  EXPECT_NE(r.err.find("empty.log: no laser scans"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace pgmcl
