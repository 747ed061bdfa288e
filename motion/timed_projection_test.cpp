#include "timed_projection.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>

#include "make_camera.h"
#include "placement.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

constexpr BodyVelocity kDriving{1.0, 0.0, 90.0};
const RobotPose kStart{0.3, -0.2, 15.0};

RigSpec rigWith(const Shutter& shutter) {
  RigSpec rig = RigSpec{}.resized(96);
  rig.shutter = shutter;
  return rig;
}

// The line of a raster point: the pixel it lies in, or for a point off the image the nearest.
int lineAt(const Shutter& shutter, const Vec2& raster, int size) {
  const auto pixel = [size](double v) { return v < 0.0 ? 0 : v >= size ? size - 1 : static_cast<int>(v); };
  return lineOf(shutter, pixel(raster.x()), pixel(raster.y()), size, size);
}

std::optional<Vec2> projectFrom(const Camera& camera, const RobotPose& pose, const Vec3& p) {
  return camera.project(CameraPlacement(pose).worldFromViewpoint(camera.rig()).inverse() * p);
}

// Points on the floor and on walls around the robot, up to 3 m away.
std::vector<Vec3> pointsAround() {
  std::mt19937_64 random(7);
  std::uniform_real_distribution<double> angle(0.0, 2.0 * kPi), range(0.5, 3.0), height(0.0, 0.6);
  std::vector<Vec3> points;
  for (int k = 0; k < 400; ++k) {
    const double a = angle(random), r = range(random);
    points.emplace_back(kStart.x + r * std::cos(a), kStart.y + r * std::sin(a), height(random));
  }
  return points;
}

TEST(TimedProjection, AGlobalShutterImagesEveryPointAtMidExposure) {
  const auto camera = makeCamera(rigWith({0.04, std::nullopt, 0}));
  const RobotPose middle = poseAfter(kStart, kDriving, 0.02);
  for (const Vec3& p : pointsAround()) {
    const auto timed = projectAtReadout(*camera, CameraPlacement(kStart, kDriving), p);
    const auto direct = projectFrom(*camera, middle, p);
    ASSERT_EQ(timed.has_value(), direct.has_value());
    if (!timed) continue;
    EXPECT_EQ(timed->raster, *direct);
    EXPECT_EQ(timed->seconds, 0.02);
  }
}

// Brute force over every line: the lines whose own time images the point on themselves. Where
// exactly one does, projectAtReadout finds it; where several do (a robot turning so fast that its
// readout sees the point twice), it takes one of them.
void expectTheLinesWhoseTimeSeesEachPointThere(const BodyVelocity& velocity, int minUnique) {
  for (Readout readout : {Readout::TopToBottom, Readout::LeftToRight, Readout::BottomToTop}) {
    const Shutter shutter{0.004, RollingShutter{300.0, readout}, 0};
    const auto camera = makeCamera(rigWith(shutter));
    int unique = 0, agreed = 0, several = 0;
    for (const Vec3& p : pointsAround()) {
      std::vector<int> consistent;
      for (int line = 0; line < 96; ++line) {
        const auto raster = projectFrom(*camera, poseAfter(kStart, velocity, lineStart(shutter, line) + 0.002), p);
        if (raster && lineAt(shutter, *raster, 96) == line) consistent.push_back(line);
      }
      const auto timed = projectAtReadout(*camera, CameraPlacement(kStart, velocity), p);
      if (consistent.size() > 1 && timed) {
        ++several;
        const int line = lineAt(shutter, timed->raster, 96);
        EXPECT_NE(std::find(consistent.begin(), consistent.end(), line), consistent.end()) << readoutName(readout);
      }
      if (consistent.size() != 1) continue;
      ++unique;
      ASSERT_TRUE(timed.has_value());
      const int line = consistent.front();
      agreed += lineAt(shutter, timed->raster, 96) == line;
      EXPECT_DOUBLE_EQ(timed->seconds, lineStart(shutter, line) + 0.002);
      EXPECT_EQ(timed->raster, *projectFrom(*camera, poseAfter(kStart, velocity, timed->seconds), p));
    }
    EXPECT_GT(unique, minUnique) << readoutName(readout);  // the case is exercised
    EXPECT_EQ(agreed, unique) << readoutName(readout) << " (" << several << " points seen on several lines)";
  }
}

TEST(TimedProjection, ARollingShutterImagesEachPointOnTheLineWhoseTimeSeesItThere) {
  expectTheLinesWhoseTimeSeesEachPointThere(kDriving, 100);
}

// 9000 °/s: the robot turns 259° within the 28.8 ms readout, and the iteration cycles for most
// points (it took the cycle's nearest miss, up to 19 px from where the point is drawn).
TEST(TimedProjection, ARobotTurningFurtherThanHalfATurnWithinTheReadoutStillImagesEachPointWhereItsLineSeesIt) {
  expectTheLinesWhoseTimeSeesEachPointThere({1.0, 0.0, 9000.0}, 20);
}

TEST(TimedProjection, AStillRobotIsProjectedAsTheStaticCameraProjects) {
  const auto camera = makeCamera(rigWith({0.01, RollingShutter{300.0, Readout::TopToBottom}, 0}));
  for (const Vec3& p : pointsAround()) {
    const auto timed = projectAtReadout(*camera, CameraPlacement(kStart, BodyVelocity{}), p);
    const auto direct = projectFrom(*camera, kStart, p);
    ASSERT_EQ(timed.has_value(), direct.has_value());
    if (timed) {
      EXPECT_EQ(timed->raster, *direct);
    }
  }
}

// A pinhole images a point almost in its image plane ~1e11 px off the image (project is not
// clipped): such a point is timed by the nearest line, the last column read left to right — not
// by whatever a cast of 1e11 to int gives.
TEST(TimedProjection, APointProjectedFarOffTheImageIsTimedByTheNearestLine) {
  PinholeRadTan pinhole;
  pinhole.fx = pinhole.fy = 100.0, pinhole.cx = pinhole.cy = 31.5;
  RigSpec rig = test::lensRig(pinhole, 64, 64);
  rig.shutter = {0.001, RollingShutter{300.0, Readout::LeftToRight}, 0};
  const auto camera = makeCamera(rig);
  // In the viewpoint frame: the optical axis and the image's right, from the camera's own rays.
  const Vec3 axis = camera->generateRay({Vec2(32.0, 32.0)})->direction.normalized();
  const Vec3 towardRight = camera->generateRay({Vec2(63.0, 32.0)})->direction.normalized();
  const Vec3 right = (towardRight - towardRight.dot(axis) * axis).normalized();
  const CameraPlacement still(kStart, BodyVelocity{});
  const Vec3 world = still.worldFromViewpoint(rig) * (right + 1e-9 * axis);
  const auto timed = projectAtReadout(*camera, still, world);
  ASSERT_TRUE(timed.has_value());
  EXPECT_GT(timed->raster.x(), 1e9);
  EXPECT_DOUBLE_EQ(timed->seconds, lineStart(rig.shutter, 63) + 0.0005);
}

}  // namespace
}  // namespace omnicam
