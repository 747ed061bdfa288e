#include "analytic_shapes.h"

#include <gtest/gtest.h>

#include <cmath>

namespace omnicam {
namespace {

TEST(AnalyticShapes, SphereFromInsideHitsAtTheRadius) {
  const Sphere s{{1, 2, 3}, 2.0};
  const auto hit = intersect(s, Vec3(1, 2, 3), Vec3(0, 0, -3), 0.0, INFINITY);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->t * 3.0, 2.0, 1e-12);
  EXPECT_NEAR(hit->normal.z(), -1.0, 1e-12);
  EXPECT_NEAR(hit->uv.y(), 0.0, 1e-12);  // bottom pole
}

TEST(AnalyticShapes, CylinderSideAndCaps) {
  const Cylinder c{{0, 0, 0}, {0, 0, 2}, 0.5, true};
  auto side = intersect(c, Vec3(3, 0, 1), Vec3(-1, 0, 0), 0.0, INFINITY);
  ASSERT_TRUE(side);
  EXPECT_NEAR(side->t, 2.5, 1e-12);
  EXPECT_NEAR(side->normal.x(), 1.0, 1e-12);
  EXPECT_NEAR(side->uv.x(), 0.0, 1e-12);  // u = 0 faces +X
  EXPECT_NEAR(side->uv.y(), 0.5, 1e-12);
  auto cap = intersect(c, Vec3(0.1, 0, 5), Vec3(0, 0, -1), 0.0, INFINITY);
  ASSERT_TRUE(cap);
  EXPECT_NEAR(cap->t, 3.0, 1e-12);
  EXPECT_NEAR(cap->normal.z(), 1.0, 1e-12);
  const Cylinder open{{0, 0, 0}, {0, 0, 2}, 0.5, false};
  auto through = intersect(open, Vec3(0.1, 0, 5), Vec3(0, 0, -1), 0.0, INFINITY);
  EXPECT_FALSE(through);  // straight down the open tube
  auto inside = intersect(open, Vec3(0, 0, 1), Vec3(0, 1, 0), 0.0, INFINITY);
  ASSERT_TRUE(inside);
  EXPECT_NEAR(inside->t, 0.5, 1e-12);
  EXPECT_FALSE(intersect(c, Vec3(3, 0, 3), Vec3(-1, 0, 0), 0.0, INFINITY));  // above it
}

TEST(AnalyticShapes, DiscWithHoleIsAnAnnulus) {
  const Disc d{{0, 0, 0}, {0, 0, 1}, 1.0, 0.5};
  EXPECT_FALSE(intersect(d, Vec3(0.2, 0, 1), Vec3(0, 0, -1), 0.0, INFINITY));
  EXPECT_TRUE(intersect(d, Vec3(0.7, 0, 1), Vec3(0, 0, -1), 0.0, INFINITY));
  EXPECT_FALSE(intersect(d, Vec3(1.2, 0, 1), Vec3(0, 0, -1), 0.0, INFINITY));
  EXPECT_FALSE(intersect(d, Vec3(0.7, 0, 1), Vec3(0, 0, -1), 0.0, 0.5));  // beyond tFar
}

}  // namespace
}  // namespace omnicam
