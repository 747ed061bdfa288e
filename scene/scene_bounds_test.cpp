// The floor-plan extent of each shape against closed forms.
#include "scene_bounds.h"

#include <gtest/gtest.h>

#include <cmath>

namespace omnicam {
namespace {

FloorRect extentOf(Shape shape) {
  Scene scene;
  scene.objects.push_back({"o", 0, std::move(shape), ""});
  const std::optional<FloorRect> r = sceneFloorExtent(scene);
  if (!r) throw std::runtime_error("no extent");
  return *r;
}

void expectRect(const FloorRect& r, double xMin, double yMin, double xMax, double yMax) {
  EXPECT_NEAR(r.xMin, xMin, 1e-12);
  EXPECT_NEAR(r.yMin, yMin, 1e-12);
  EXPECT_NEAR(r.xMax, xMax, 1e-12);
  EXPECT_NEAR(r.yMax, yMax, 1e-12);
}

TEST(SceneFloorExtent, EachShapeByItsClosedForm) {
  // A 2 × 1 box turned 30°: half extents |cos|·1 + |sin|·0.5 and |sin|·1 + |cos|·0.5.
  const double c = std::cos(M_PI / 6), s = std::sin(M_PI / 6);
  expectRect(extentOf(Box{{1, 2, 0.5}, {2, 1, 1}, 30.0}), 1 - (c + 0.5 * s), 2 - (s + 0.5 * c), 1 + (c + 0.5 * s), 2 + (s + 0.5 * c));
  expectRect(extentOf(Box{{1, 2, 0.5}, {2, 1, 1}, -30.0}), 1 - (c + 0.5 * s), 2 - (s + 0.5 * c), 1 + (c + 0.5 * s), 2 + (s + 0.5 * c));
  // An upright cylinder: its circle; one lying along x: its length, and its radius across.
  expectRect(extentOf(Cylinder{{3, 0, 0}, {3, 0, 2}, 0.5, true}), 2.5, -0.5, 3.5, 0.5);
  expectRect(extentOf(Cylinder{{0, 0, 1}, {4, 0, 1}, 0.5, true}), 0, -0.5, 4, 0.5);
  expectRect(extentOf(Sphere{{-1, -1, 3}, 2}), -3, -3, 1, 1);
  expectRect(extentOf(Quad{{0, 0, 0}, {2, 1, 0}, {-1, 3, 5}}), -1, 0, 2, 4);
  // A disc tilted 60° about y (normal (sin 60°, 0, cos 60°)): r·cos 60° along x, r along y.
  expectRect(extentOf(Disc{{0, 0, 1}, {std::sin(M_PI / 3), 0, std::cos(M_PI / 3)}, 2, 0}), -1, -2, 1, 2);
  expectRect(extentOf(Mesh{{{0, 0, 0}, {5, -2, 1}, {1, 7, 0}}, {{0, 1, 2}}, {}}), 0, -2, 5, 7);
}

TEST(SceneFloorExtent, TheSceneHoldsEveryObjectAndAnEmptySceneHasNone) {
  Scene scene;
  EXPECT_FALSE(sceneFloorExtent(scene));
  scene.objects.push_back({"a", 0, Sphere{{0, 0, 0}, 1}, ""});
  scene.objects.push_back({"b", 0, Sphere{{10, 5, 0}, 1}, ""});
  const FloorRect r = *sceneFloorExtent(scene);
  expectRect(r, -1, -1, 11, 6);
  EXPECT_TRUE(r.contains(5, 2));
  EXPECT_FALSE(r.contains(12, 2));
}

}  // namespace
}  // namespace omnicam
