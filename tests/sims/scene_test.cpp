#include "pgmcl/sims/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "pgmcl/common/random.hpp"
#include "scenes.hpp"

namespace pgmcl::sims {
namespace {

constexpr float kPiF = std::numbers::pi_v<float>;

TEST(Obstacles, RayDiscMatchesQuadraticAndNormalIsRadial) {
  float nx = 0, ny = 0;
  const float t = ray_disc(0.0F, 0.0F, 1.0F, 0.0F, 5.0F, 0.3F, 0.5F, nx, ny);
  EXPECT_NEAR(t, 5.0 - std::sqrt(0.25 - 0.09), 1e-5);
  EXPECT_NEAR(nx, -0.8, 1e-5);
  EXPECT_NEAR(ny, -0.6, 1e-5);
  EXPECT_TRUE(std::isinf(ray_disc(0.0F, 0.0F, 1.0F, 0.0F, 5.0F, 0.6F, 0.5F, nx, ny)));
  EXPECT_TRUE(std::isinf(ray_disc(0.0F, 0.0F, -1.0F, 0.0F, 5.0F, 0.0F, 0.5F, nx, ny)));
  EXPECT_EQ(ray_disc(5.1F, 0.0F, 1.0F, 0.0F, 5.0F, 0.0F, 0.5F, nx, ny), 0.0F);
}

TEST(Obstacles, RayBoxAgreesWithRotatedSlabs) {
  // A 2 x 1 box at (4, 1) rotated by 30 degrees, hit along its local -x face normal.
  const float yaw = kPiF / 6, c = std::cos(yaw), s = std::sin(yaw);
  float nx = 0, ny = 0;
  // Start 3 m out along the box's -x axis, aim at the centre: hit the face at 1 m from centre.
  const float ox = 4.0F - 3.0F * c, oy = 1.0F - 3.0F * s;
  const float t = ray_box(ox, oy, c, s, 4.0F, 1.0F, c, s, 1.0F, 0.5F, nx, ny);
  EXPECT_NEAR(t, 2.0F, 1e-5);
  EXPECT_NEAR(nx, -c, 1e-6);
  EXPECT_NEAR(ny, -s, 1e-6);
  // Brute force: march along random rays and compare the first inside point.
  Rng rng(2);
  for (int k = 0; k < 300; ++k) {
    const float a = static_cast<float>(rng.uniform(-3.14, 3.14));
    const float px = static_cast<float>(rng.uniform(0, 8)),
                py = static_cast<float>(rng.uniform(-3, 5));
    const float dx = std::cos(a), dy = std::sin(a);
    const float hit = ray_box(px, py, dx, dy, 4.0F, 1.0F, c, s, 1.0F, 0.5F, nx, ny);
    float march = std::numeric_limits<float>::infinity();
    for (int i = 0; i < 20000; ++i) {
      const float tt = i * 1e-3F, x = px + tt * dx - 4.0F, y = py + tt * dy - 1.0F;
      if (std::abs(c * x + s * y) <= 1.0F && std::abs(-s * x + c * y) <= 0.5F) {
        march = tt;
        break;
      }
    }
    if (std::isinf(march)) {
      EXPECT_TRUE(std::isinf(hit) || hit > 19.9F);
    } else {
      EXPECT_NEAR(hit, march, 1.5e-3);
    }
  }
}

TEST(Obstacles, PathLoopsAtConstantSpeed) {
  ObstaclePath p{{{0, 0}, {2, 0}, {2, 1}}, 0.5, 0.0};
  EXPECT_NEAR(p.position_at(2.0).x, 1.0, 1e-12);
  EXPECT_NEAR(p.position_at(5.0).y, 0.5, 1e-12);  // 2.5 m: up the second leg
  const double loop = 3.0 + std::sqrt(5.0);
  const auto a = p.position_at(1.3), b = p.position_at(1.3 + loop / 0.5);
  EXPECT_NEAR(a.x, b.x, 1e-9);
  EXPECT_NEAR(a.y, b.y, 1e-9);
  ObstaclePath still{{{3, 4}}, 1.0, 0.0};
  EXPECT_DOUBLE_EQ(still.position_at(10).x, 3.0);
  ObstaclePath bad{{}, 1.0, 0.0};
  EXPECT_THROW(bad.validate("discs[0].path"), std::invalid_argument);
}

TEST(SurfaceField, RegionsOverrideLabelsOverrideDefault) {
  maps::OccupancyGrid grid(10, 10, 1.0, {10.0, 0.0, 0.0}, maps::kOccupied);
  SurfaceLayout layout;
  layout.labels.assign(100, SurfaceLayout::kNoLabel);
  layout.labels[grid.index(1, 1)] = 2;  // plastic wicker
  layout.labels[grid.index(5, 5)] = 3;
  layout.regions.push_back({"shiny_black_metal", 14.0, 4.0, 16.0, 6.0});  // global frame
  const SurfaceField f(layout, grid);
  EXPECT_EQ(f.material(f.at(0, 0)).name, "average");
  EXPECT_EQ(f.material(f.at(1, 1)).name, "plastic_wicker");
  EXPECT_EQ(f.material(f.at(5, 5)).name, "shiny_black_metal");
  EXPECT_TRUE(f.material(f.at(4, 4)).specular);
  EXPECT_NEAR(f.material(f.index_of("cardboard_box", "t")).sigma.sigma(0.0), 4.6533e-3, 1e-9);
  layout.regions.push_back({"granite", 0, 0, 1, 1});
  try {
    (void)SurfaceField(layout, grid);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("regions[1].material"), std::string::npos) << e.what();
  }
  layout.regions.pop_back();
  layout.labels.resize(3);
  EXPECT_THROW((void)SurfaceField(layout, grid), std::invalid_argument);
}

TEST(Scene, ObstaclesOccludeTheGridAndAreMappedToTheLocalFrame) {
  const Pose2 origin{1.0, 2.0, 0.5};
  const auto grid = test::square_room(100, 100, 0.05, origin);
  const RayCaster rc(grid);
  const SurfaceField surf(SurfaceLayout{}, grid);
  Scene scene(rc, surf);
  // A disc at global (origin ∘ (2.5, 2.5)), moving nowhere; a beam from local (1, 2.5)
  // along local +x meets it at 1.5 - 0.2 m.
  double gx = 0, gy = 0;
  origin.transform_point(2.5, 2.5, gx, gy);
  DiscObstacle d{0.2, {{{gx, gy}}, 0.0, 0.0}, "fabric"};
  scene.set_obstacles({d}, {}, 3.0);
  const auto hit = scene.cast(1.0F, 2.5F, 1.0F, 0.0F, 30.0F);
  ASSERT_TRUE(hit.hit);
  EXPECT_NEAR(hit.range, 1.3F, 1e-4);
  EXPECT_NEAR(hit.nx, -1.0F, 1e-4);
  EXPECT_EQ(surf.material(hit.material).name, "fabric");
  // Pointing away, the wall (average material) is hit: 4.95 - 1.0 along local -x.
  const auto wall = scene.cast(1.0F, 2.5F, -1.0F, 0.0F, 30.0F);
  EXPECT_NEAR(wall.range, 0.95F, 1e-4);
  EXPECT_NEAR(wall.nx, 1.0F, 1e-6);
  EXPECT_EQ(surf.material(wall.material).name, "average");
  DiscObstacle unknown = d;
  unknown.material = "jelly";
  EXPECT_THROW(scene.set_obstacles({unknown}, {}, 0.0), std::invalid_argument);
}

TEST(Scene, GridNormalsOfThinDiagonalAndThickWalls) {
  maps::OccupancyGrid grid(60, 60, 0.05, {}, maps::kFree);
  for (int k = 5; k < 55; ++k) grid.set(k, k, maps::kOccupied);  // thin 45 deg staircase
  test::fill_cells(grid, 0, 0, 59, 2, maps::kOccupied);          // thick floor
  const RayCaster rc(grid);
  float nx = 0, ny = 0;
  // Hit the staircase from below-right, at various angles: the normal is always (1,-1)/√2.
  for (const float a : {2.0F, 2.4F, 2.8F, 1.7F}) {
    const RayHit h = rc.cast_local(2.0F, 0.5F, a, 10.0F);
    ASSERT_TRUE(h.hit);
    rc.surface_normal(h.col, h.row, h.face, std::cos(a), std::sin(a), nx, ny);
    EXPECT_NEAR(nx, std::sqrt(0.5F), 1e-5) << a;
    EXPECT_NEAR(ny, -std::sqrt(0.5F), 1e-5) << a;
  }
  // The same staircase from the other side.
  const RayHit h2 = rc.cast_local(0.5F, 2.0F, -0.3F, 10.0F);
  rc.surface_normal(h2.col, h2.row, h2.face, std::cos(-0.3F), std::sin(-0.3F), nx, ny);
  EXPECT_NEAR(nx, -std::sqrt(0.5F), 1e-5);
  EXPECT_NEAR(ny, std::sqrt(0.5F), 1e-5);
  // The thick floor seen obliquely: (0, 1).
  const float a = -2.5F;
  const RayHit f = rc.cast_local(1.0F, 0.6F, a, 10.0F);
  rc.surface_normal(f.col, f.row, f.face, std::cos(a), std::sin(a), nx, ny);
  EXPECT_NEAR(nx, 0.0F, 1e-6);
  EXPECT_NEAR(ny, 1.0F, 1e-6);
}

TEST(Scene, CircleNormalsFollowTheRadius) {
  const double res = 0.05, cx = 2.5, cy = 2.5, radius = 1.0;
  maps::OccupancyGrid grid(100, 100, res, {}, maps::kFree);
  test::fill_disc(grid, cx, cy, radius, maps::kOccupied);
  const RayCaster rc(grid);
  double worst = 0.0;
  for (int k = 0; k < 72; ++k) {
    const double phi = k * 2 * std::numbers::pi / 72;
    // Beam aimed at the centre from 1.2 m outside, 20 degrees off.
    const double sx = cx + 2.2 * std::cos(phi), sy = cy + 2.2 * std::sin(phi);
    const float a = static_cast<float>(phi + std::numbers::pi + 0.1);
    const RayHit h = rc.cast_local(static_cast<float>(sx), static_cast<float>(sy), a, 10.0F);
    ASSERT_TRUE(h.hit);
    float nx = 0, ny = 0;
    rc.surface_normal(h.col, h.row, h.face, std::cos(a), std::sin(a), nx, ny);
    const double rx = h.x - cx, ry = h.y - cy, rn = std::hypot(rx, ry);
    worst = std::max(worst, std::acos(std::clamp((nx * rx + ny * ry) / rn, -1.0, 1.0)));
  }
  // A 20-cell-radius staircase: 5x5 surface fits are within ~15 degrees of the radius.
  EXPECT_LT(worst, 15.0 * std::numbers::pi / 180.0);
  std::printf("circle normals: worst %.1f deg\n", worst * 180 / std::numbers::pi);
}

}  // namespace
}  // namespace pgmcl::sims
