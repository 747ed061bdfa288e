#include "vibration.h"

#include <gtest/gtest.h>

#include <cmath>

#include "errors.h"
#include "make_camera.h"
#include "scene_loader.h"
#include "placement.h"

namespace omnicam {
namespace {

TEST(RigTilt, TiltsTheRigAboutTheRobotsOriginOnTheFloor) {
  RigSpec rig;
  rig.height = 0.5;
  const double a = 7.0, b = -4.0;
  rig.tiltDeg = {a, 0.0};  // roll about x: the top of the rig leans towards −y
  Vec3 f = robotFromViewpoint(rig).translation();
  EXPECT_NEAR(f.x(), 0.0, 1e-15);
  EXPECT_NEAR(f.y(), -0.5 * std::sin(radians(a)), 1e-15);
  EXPECT_NEAR(f.z(), 0.5 * std::cos(radians(a)), 1e-15);
  rig.tiltDeg = {0.0, b};  // pitch about y: the top leans towards +x for a positive pitch
  f = robotFromViewpoint(rig).translation();
  EXPECT_NEAR(f.x(), 0.5 * std::sin(radians(b)), 1e-15);
  EXPECT_NEAR(f.z(), 0.5 * std::cos(radians(b)), 1e-15);
  // Roll then pitch: the viewpoint's z axis is Rx(a)·Ry(b)·ẑ.
  rig.tiltDeg = {a, b};
  const Vec3 axis = robotFromViewpoint(rig).linear() * Vec3::UnitZ();
  const double ra = radians(a), rb = radians(b);
  EXPECT_NEAR(axis.x(), std::sin(rb), 1e-15);
  EXPECT_NEAR(axis.y(), -std::sin(ra) * std::cos(rb), 1e-15);
  EXPECT_NEAR(axis.z(), std::cos(ra) * std::cos(rb), 1e-15);
}

TEST(RigTilt, APointOnTheTiltedAxisIsSeenAtTheImageCentre) {
  RigSpec rig;
  rig.tiltDeg = {3.0, -2.0};
  const RobotPose pose{1.0, -0.5, 40.0};
  // By hand: the rig's axis in the world is Rz(yaw)·Rx(roll)·Ry(pitch)·ẑ, and F' sits h along it
  // from the robot's origin on the floor.
  const double roll = radians(3.0), pitch = radians(-2.0), yaw = radians(40.0);
  const Vec3 local(std::sin(pitch), -std::sin(roll) * std::cos(pitch), std::cos(roll) * std::cos(pitch));
  const Vec3 axis(std::cos(yaw) * local.x() - std::sin(yaw) * local.y(), std::sin(yaw) * local.x() + std::cos(yaw) * local.y(),
                  local.z());
  const Vec3 viewpoint = Vec3(pose.x, pose.y, 0.0) + rig.height * axis;
  const auto camera = makeCamera(rig);
  // Straight down the tilted axis, 0.3 m below F': the image centre.
  const auto centre = camera->project(CameraPlacement(pose).worldFromViewpoint(rig).inverse() * (viewpoint - 0.3 * axis));
  ASSERT_TRUE(centre);
  EXPECT_NEAR(centre->x(), 0.5 * rig.mirrorRig().imageSize, 1e-9);
  EXPECT_NEAR(centre->y(), 0.5 * rig.mirrorRig().imageSize, 1e-9);
  // The level rig sees the same point off centre.
  RigSpec level = rig;
  level.tiltDeg = {0.0, 0.0};
  const auto seenLevel = camera->project(CameraPlacement(pose).worldFromViewpoint(level).inverse() * (viewpoint - 0.3 * axis));
  ASSERT_TRUE(seenLevel);
  EXPECT_GT((*seenLevel - *centre).norm(), 0.5);
}

TEST(RigTilt, TheSceneFormatReadsAndBoundsIt) {
  const auto rigOf = [](const std::string& rig) {
    return rigFromJson(nlohmann::json::parse(rig), "scene.json", "rig");
  };
  EXPECT_EQ(rigOf(R"({"tilt_deg": [1.5, -2]})").tiltDeg, (std::array<double, 2>{1.5, -2.0}));
  EXPECT_EQ(rigOf(R"({})").tiltDeg, (std::array<double, 2>{0.0, 0.0}));
  EXPECT_THROW(rigOf(R"({"tilt_deg": [31, 0]})"), InputError);
  EXPECT_THROW(rigOf(R"({"tilt_deg": [1]})"), InputError);
}

Vibration shaking() {
  Vibration v;
  v.seed = 42;
  v.cameraOffsetMm = {0.5, 0.25, 1.0};
  v.cameraRotationDeg = {0.2, 0.1, 0.4};
  v.rigTiltDeg = {1.0, 2.0};
  return v;
}

TEST(Vibration, WithoutAmplitudesTheRigStaysAsItIs) {
  RigSpec rig;
  rig.mirrorRig().mount.offsetMm = {1.0, 2.0, 3.0};
  Vibration still;
  still.seed = 9;
  EXPECT_EQ(vibratedRig(rig, still, 17, 1), rig);
}

TEST(Vibration, EachFrameAndCameraDrawsItsOwnPerturbationWithinTheAmplitudes) {
  RigSpec rig;
  rig.mirrorRig().mount.offsetMm = {1.0, 0.0, -2.0};
  rig.tiltDeg = {0.5, 0.0};
  const Vibration v = shaking();
  // The same (seed, frame, camera) gives the same rig, in any order; others differ.
  EXPECT_EQ(vibratedRig(rig, v, 5, 1), vibratedRig(rig, v, 5, 1));
  EXPECT_NE(vibratedRig(rig, v, 5, 1), vibratedRig(rig, v, 6, 1));
  EXPECT_NE(vibratedRig(rig, v, 5, 1), vibratedRig(rig, v, 5, 0));
  Vibration reseeded = v;
  reseeded.seed = 43;
  EXPECT_NE(vibratedRig(rig, v, 5, 1), vibratedRig(rig, reseeded, 5, 1));
  // Uniform within ± amplitude: over 20000 frames the mean is 0 and the variance a²/3 (each to
  // well within 5 standard errors), and the extremes come close to ± a.
  const int frames = 20000;
  double sum = 0.0, sumSquares = 0.0, lowest = 0.0, highest = 0.0;
  for (int f = 0; f < frames; ++f) {
    const RigSpec r = vibratedRig(rig, v, static_cast<uint64_t>(f), 0);
    EXPECT_EQ(r.mirrorRig().mount.distortion, rig.mirrorRig().mount.distortion);
    EXPECT_EQ(r.height, rig.height);
    for (int k = 0; k < 3; ++k) {
      EXPECT_LE(std::abs(r.mirrorRig().mount.offsetMm[k] - rig.mirrorRig().mount.offsetMm[k]), v.cameraOffsetMm[k]);
      EXPECT_LE(std::abs(r.mirrorRig().mount.rotationDeg[k] - rig.mirrorRig().mount.rotationDeg[k]), v.cameraRotationDeg[k]);
    }
    const double d = r.tiltDeg[1] - rig.tiltDeg[1];  // amplitude 2°
    EXPECT_LE(std::abs(r.tiltDeg[0] - rig.tiltDeg[0]), v.rigTiltDeg[0]);
    sum += d;
    sumSquares += d * d;
    lowest = std::min(lowest, d);
    highest = std::max(highest, d);
  }
  const double a = v.rigTiltDeg[1], mean = sum / frames, variance = sumSquares / frames - mean * mean;
  const double sdOfMean = a / std::sqrt(3.0 * frames);
  EXPECT_LT(std::abs(mean), 5.0 * sdOfMean);
  EXPECT_NEAR(variance, a * a / 3.0, 5.0 * a * a * std::sqrt(4.0 / 45.0 / frames));
  EXPECT_LT(lowest, -0.999 * a);
  EXPECT_GT(highest, 0.999 * a);
}

}  // namespace
}  // namespace omnicam
