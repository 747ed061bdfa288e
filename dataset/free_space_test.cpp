// The free-space polygon against closed-form areas (a box and a wall grown by the circumscribed
// disc polygon), the clearance of every triangle corner and sampled point checked by the
// independent brute-force distance of FloorObstacles, and uniform sampling by area.
#include "free_space.h"
#include "floor_obstacles.h"

#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "pose_sampler.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

// The floor, one 1 m × 0.6 m box, a 2 m wall (a vertical quad: its footprint is a segment), a
// pole (a cylinder) and a ceiling above the cameras.
Scene obstacleScene() {
  return loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "quad", "material": "m", "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]},
                {"type": "box", "material": "m", "center": [-2, 0, 0.5], "size": [1, 0.6, 1]},
                {"type": "quad", "material": "m", "origin": [1, 2, 0], "edge_u": [2, 0, 0], "edge_v": [0, 0, 1]},
                {"type": "cylinder", "material": "m", "base": [2, -2, 0], "top": [2, -2, 1], "radius": 0.1},
                {"type": "box", "material": "m", "center": [0, 0, 3], "size": [10, 10, 0.1]}]})",
                           "obstacles.json");
}

constexpr double kTop = 0.4;  // the viewpoint's height: the ceiling is not an obstacle
const double kSides = FreeSpace::kDiscSides;
// Area the circumscribed disc polygon of inradius r adds around a convex footprint of perimeter
// P whose edges are all axis-aligned (their normals point at the polygon's vertices, where its
// support is r / cos(π/n)), plus the polygon's own area n r² tan(π/n).
double grownArea(double footprintArea, double perimeter, double r) {
  return footprintArea + perimeter * r / std::cos(M_PI / kSides) + kSides * r * r * std::tan(M_PI / kSides);
}

TEST(FreeSpace, AnEmptyRegionIsAllFree) {
  const FreeSpace free(obstacleScene(), kTop, {-1.0, 0.0, -1.0, 1.0}, 0.3);
  EXPECT_DOUBLE_EQ(free.area(), 2.0);
  EXPECT_EQ(free.componentCount(), 1);
}

TEST(FreeSpace, ABoxIsCutOutGrownByTheClearance) {
  const double clearance = 0.25, r = clearance + FloorObstacles::kChordTolerance;
  const FreeSpace free(obstacleScene(), kTop, {-4.0, -0.5, -2.0, 2.0}, clearance);
  EXPECT_NEAR(free.area(), 3.5 * 4.0 - grownArea(0.6, 3.2, r), 1e-9);
  EXPECT_EQ(free.componentCount(), 1);  // a hole in one piece
}

TEST(FreeSpace, AWallsSegmentFootprintIsCutOutToo) {
  const double clearance = 0.2, r = clearance + FloorObstacles::kChordTolerance;
  const FreeSpace free(obstacleScene(), kTop, {0.0, 4.0, 1.0, 3.0}, clearance);
  EXPECT_NEAR(free.area(), 4.0 * 2.0 - grownArea(0.0, 4.0, r), 1e-9);
}

TEST(FreeSpace, ARegionSplitByAnObstacleHasTwoComponents) {
  // The box spans y ∈ [-0.3, 0.3]; a region 0.2 m wider on each side, at 0.25 m clearance, is
  // cut in two (the grown box reaches 0.551 m).
  const FreeSpace free(obstacleScene(), kTop, {-2.2, -1.8, -1.0, 1.0}, 0.25);
  EXPECT_EQ(free.componentCount(), 2);
  const FreeSpace filled(obstacleScene(), kTop, {-2.2, -1.8, -0.5, 0.5}, 0.25);
  EXPECT_TRUE(filled.empty());
  EXPECT_EQ(filled.area(), 0.0);
}

TEST(FreeSpace, EveryCornerAndSampleKeepsTheClearance) {
  const Scene scene = obstacleScene();
  const double clearance = 0.3;
  const FreeSpace free(scene, kTop, {-4.0, 4.0, -4.0, 4.0}, clearance);
  const FloorObstacles obstacles(scene, kTop);
  ASSERT_EQ(obstacles.obstacleCount(), 3u);
  double nearest = 10.0;
  for (const auto& t : free.triangles())
    for (const Vec2& corner : t) nearest = std::min(nearest, obstacles.distance(corner, 10.0));
  EXPECT_GE(nearest, clearance);
  // The circumscribed polygon overshoots by at most r (1 / cos(π/n) − 1) ≈ 0.5 % of r.
  EXPECT_LE(nearest, (clearance + FloorObstacles::kChordTolerance) / std::cos(M_PI / kSides) + 1e-9);
  std::mt19937_64 generator(5);
  std::uniform_real_distribution<double> draw(0.0, 1.0);
  for (int k = 0; k < 5000; ++k) {
    const Vec2 p = free.pointFromDraws(draw(generator), draw(generator), draw(generator));
    ASSERT_GE(obstacles.distance(p, 10.0), clearance) << p.transpose();
    ASSERT_TRUE(p.x() >= -4.0 && p.x() <= 4.0 && p.y() >= -4.0 && p.y() <= 4.0) << p.transpose();
  }
}

TEST(FreeSpace, SamplesAreUniformByArea) {
  // The box sits in the left half of the region: each half receives samples in proportion to
  // its free area (closed form), within 4 standard deviations of the binomial count.
  const double clearance = 0.25, r = clearance + FloorObstacles::kChordTolerance;
  const FreeSpace free(obstacleScene(), kTop, {-3.0, 1.0, -1.5, 1.5}, clearance);
  const double leftArea = 2.0 * 3.0 - grownArea(0.6, 3.2, r), rightArea = 2.0 * 3.0;
  ASSERT_NEAR(free.area(), leftArea + rightArea, 1e-9);
  std::mt19937_64 generator(11);
  std::uniform_real_distribution<double> draw(0.0, 1.0);
  const int n = 20000;
  int left = 0;
  for (int k = 0; k < n; ++k) left += free.pointFromDraws(draw(generator), draw(generator), draw(generator)).x() < -1.0;
  const double p = leftArea / (leftArea + rightArea);
  EXPECT_NEAR(left, n * p, 4.0 * std::sqrt(n * p * (1.0 - p)));
}

}  // namespace
}  // namespace omnicam
