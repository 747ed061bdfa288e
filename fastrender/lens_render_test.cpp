// Lens cameras (issue #37) through the fast engine, against closed forms: depth along every pixel
// centre's ray out to the image's edge (habitat-sim #1820 gives the planar depth there instead),
// for a fisheye facing a wall and a panorama above a floor.
#include <gtest/gtest.h>

#include <cmath>

#include "aov_renderer.h"
#include "lens_camera.h"
#include "placement.h"

namespace omnicam {
namespace {

Scene wallAt(double x) {
  Scene s;
  s.materials.push_back({"grey", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  s.objects.push_back({"wall", 0, Quad{{x, -40, -40}, {0, 80, 0}, {0, 0, 80}}, ""});
  return s;
}

// An equidistant fisheye (r = f·θ) looking along robot +x at a wall 1.5 m ahead: the pixel whose
// centre lies r pixels from the principal point sees the wall at 1.5 / cos(r / f) along its ray,
// out to 85° from the axis (11.5 times the planar distance).
TEST(LensRender, FisheyeDepthIsTheRayLengthOutToTheImageEdge) {
  constexpr double kWall = 1.5, kFocal = 60.0, kHalfFovDeg = 85.0;
  const FastRenderer renderer(wallAt(kWall));
  RenderSettings settings;
  FThetaLens lens;
  lens.kind = FThetaLens::Kind::Equidistant;
  lens.f = kFocal;
  lens.cx = 99.5, lens.cy = 89.5;
  lens.maxThetaRad = radians(kHalfFovDeg);
  settings.rig.kind = LensCameraSpec{lens, 200, 180, {0.0, 0.0, 0.0}};
  settings.rig.height = 1.0;
  const AovFrame aov = renderAovs(renderer, RobotPose{}, settings);
  ASSERT_EQ(aov.width, 200);
  ASSERT_EQ(aov.height, 180);
  int checked = 0, beyond80 = 0;
  double worst = 0.0;
  for (int j = 0; j < aov.height; ++j)
    for (int i = 0; i < aov.width; ++i) {
      const double theta = std::hypot(i - lens.cx, j - lens.cy) / kFocal;  // OpenCV's pixel centres: (i, j)
      const float depth = aov.depth[static_cast<size_t>(j) * aov.width + i];
      if (theta > lens.maxThetaRad) {
        EXPECT_EQ(depth, 0.0f) << i << "," << j << ": outside the image circle";
        continue;
      }
      const double expected = kWall / std::cos(theta);
      worst = std::max(worst, std::abs(depth - expected) / expected);
      ++checked;
      beyond80 += theta > radians(80.0);
    }
  EXPECT_LE(worst, 1e-6) << "relative depth error (float32 holds ~6e-8)";
  EXPECT_GT(checked, 20000);
  EXPECT_GT(beyond80, 500) << "the test must reach the image's edge";
}

// An equirectangular panorama 0.4 m above an endless floor: every pixel of row j sees the floor
// at latitude lat_j < 0, height / sin(−lat_j) along its ray, whatever its longitude; above the
// horizon nothing.
TEST(LensRender, PanoramaDepthIsTheRayLengthInEveryColumn) {
  Scene floor;
  floor.materials.push_back({"grey", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  floor.objects.push_back({"floor", 0, Quad{{-500, -500, 0}, {1000, 0, 0}, {0, 1000, 0}}, ""});
  const FastRenderer renderer(floor);
  RenderSettings settings;
  Equirectangular pano;
  pano.width = 256, pano.height = 128;
  settings.rig.kind = LensCameraSpec{pano, 256, 128, {0.0, 0.0, 37.0}};
  settings.rig.height = 0.4;
  const AovFrame aov = renderAovs(renderer, RobotPose{0.3, -0.2, 25.0}, settings);
  int checked = 0;
  double worst = 0.0;
  for (int j = 0; j < aov.height; ++j) {
    const double latitude = kPi / 2 - (j + 0.5) / aov.height * kPi;
    for (int i = 0; i < aov.width; ++i) {
      const float depth = aov.depth[static_cast<size_t>(j) * aov.width + i];
      if (latitude >= 0.0) {
        EXPECT_EQ(depth, 0.0f);
        continue;
      }
      const double expected = 0.4 / std::sin(-latitude);
      if (expected > 400.0) continue;  // the floor's far edge
      worst = std::max(worst, std::abs(depth - expected) / expected);
      ++checked;
    }
  }
  EXPECT_LE(worst, 1e-6);
  EXPECT_GT(checked, 256 * 60);
}

// A pixel's colour, depth and instance are its centre's: a camera turned straight down (pitch
// +90°) sees the floor's point below it at the principal point, at the rig's height.
TEST(LensRender, ATurnedLensLooksWhereItsRotationSays) {
  Scene floor;
  floor.materials.push_back({"grey", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  floor.objects.push_back({"floor", 0, Quad{{-50, -50, 0}, {100, 0, 0}, {0, 100, 0}}, ""});
  const FastRenderer renderer(floor);
  RenderSettings settings;
  PinholeRadTan pinhole{100.0, 100.0, 20.0, 15.0, {}};
  settings.rig.kind = LensCameraSpec{pinhole, 41, 31, {0.0, 90.0, 0.0}};
  settings.rig.height = 0.7;
  const AovFrame aov = renderAovs(renderer, RobotPose{1.0, 2.0, 60.0}, settings);
  EXPECT_FLOAT_EQ(aov.depth[15 * 41 + 20], 0.7f);
  // Image right is robot −y turned down: the pixel 10 to the right of centre sees 0.07 m to the robot's right.
  const LensCamera camera(settings.rig);
  const auto ray = camera.generateRay({Vec2(30.5, 15.5)});
  ASSERT_TRUE(ray);
  const Vec3 robotPoint = ray->direction * (0.7 / -ray->direction.z());
  EXPECT_NEAR(robotPoint.y(), -0.07, 1e-12);
  EXPECT_NEAR(robotPoint.x(), 0.0, 1e-12);
}

}  // namespace
}  // namespace omnicam
