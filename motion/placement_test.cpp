// The frame chain (placement.h) against closed forms and against the chain composed by hand from
// independent rotations: mounts turn and move with the robot, a robot's tilt rocks every camera
// about the robot's origin (a rig's own tilt only its own), and a frozen instant is that instant.
#include "placement.h"

#include <gtest/gtest.h>

#include <cmath>

#include "geometry.h"

namespace omnicam {
namespace {

RigSpec rigAt(double height) {
  RigSpec rig;
  rig.height = height;
  return rig;
}

void expectNear(const Vec3& got, const Vec3& want, double tolerance = 1e-12) {
  EXPECT_NEAR(got.x(), want.x(), tolerance);
  EXPECT_NEAR(got.y(), want.y(), tolerance);
  EXPECT_NEAR(got.z(), want.z(), tolerance);
}

TEST(CameraPlacement, AMountTurnsWithTheRobot) {
  const CameraPlacement p({1.0, 2.0, 90.0}, {}, {0.2, 0.1, 30.0});
  const RobotPose foot = p.footAt(0.0);
  EXPECT_NEAR(foot.x, 1.0 - 0.1, 1e-12);  // robot +X is world +Y, robot +Y is world −X
  EXPECT_NEAR(foot.y, 2.0 + 0.2, 1e-12);
  EXPECT_DOUBLE_EQ(foot.yawDeg, 120.0);
  // F' stands the rig's height above the foot, its axes the foot's.
  const Rigid worldFromView = p.worldFromViewpoint(rigAt(0.4));
  expectNear(worldFromView.translation(), Vec3(0.9, 2.2, 0.4));
  expectNear(worldFromView.linear() * Vec3::UnitX(), Vec3(std::cos(radians(120.0)), std::sin(radians(120.0)), 0.0));
}

TEST(CameraPlacement, AMountedCameraDrivesTheArcOfItsMountPoint) {
  // Turning on the spot at 90°/s, a camera 0.2 m ahead facing left circles the robot's centre.
  const CameraPlacement spinning({0.0, 0.0, 0.0}, {0.0, 0.0, 90.0}, {0.2, 0.0, 90.0});
  for (double t : {0.0, 0.25, 0.5, 1.3}) {
    const RobotPose foot = spinning.footAt(t);
    const double a = radians(90.0 * t);
    EXPECT_NEAR(foot.x, 0.2 * std::cos(a), 1e-12) << t;
    EXPECT_NEAR(foot.y, 0.2 * std::sin(a), 1e-12) << t;
    EXPECT_NEAR(foot.yawDeg, 90.0 + 90.0 * t, 1e-12) << t;
  }
  // In general: the robot's pose at t (motion.h), with the mount applied to it by hand.
  const RobotPose robot{1.0, -2.0, 25.0};
  const BodyVelocity v{0.8, -0.3, 120.0};
  const RobotMount mount{0.15, -0.3, -40.0};
  const CameraPlacement mounted(robot, v, mount);
  for (double t : {0.01, 0.1, 0.7}) {
    const RobotPose r = poseAfter(robot, v, t);
    const double yaw = radians(r.yawDeg);
    EXPECT_NEAR(mounted.footAt(t).x, r.x + std::cos(yaw) * mount.x - std::sin(yaw) * mount.y, 1e-12) << t;
    EXPECT_NEAR(mounted.footAt(t).y, r.y + std::sin(yaw) * mount.x + std::cos(yaw) * mount.y, 1e-12) << t;
    EXPECT_NEAR(mounted.footAt(t).yawDeg, r.yawDeg + mount.yawDeg, 1e-9) << t;
  }
}

TEST(CameraPlacement, ARobotsTiltRocksACameraAboutTheRobotsOriginNotItsOwnFoot) {
  // Pitched by θ about the robot's y axis, a camera standing d ahead with F' at height h moves to
  // (d cos θ + h sin θ, 0, −d sin θ + h cos θ); the same tilt on the rig alone turns it about its
  // own foot: (d + h sin θ, 0, h cos θ).
  const double d = 0.25, h = 0.4, theta = 3.0;
  const double c = std::cos(radians(theta)), s = std::sin(radians(theta));
  const CameraPlacement rocking({0.0, 0.0, 0.0}, {}, {d, 0.0, 0.0}, {0.0, theta});
  expectNear(rocking.worldFromViewpoint(rigAt(h)).translation(), Vec3(d * c + h * s, 0.0, -d * s + h * c));
  RigSpec tiltedRig = rigAt(h);
  tiltedRig.tiltDeg = {0.0, theta};
  expectNear(CameraPlacement({0.0, 0.0, 0.0}, {}, {d, 0.0, 0.0}).worldFromViewpoint(tiltedRig).translation(),
             Vec3(d + h * s, 0.0, h * c));
  // Both cameras of a robot tilt alike: their viewpoints keep their distance and their axes agree.
  const CameraPlacement front({1.0, 2.0, 30.0}, {}, {0.1, 0.0, 0.0}, {2.0, -1.0});
  const CameraPlacement rear({1.0, 2.0, 30.0}, {}, {-0.1, 0.0, 180.0}, {2.0, -1.0});
  const Rigid a = front.worldFromViewpoint(rigAt(h)), b = rear.worldFromViewpoint(rigAt(h));
  EXPECT_NEAR((a.translation() - b.translation()).norm(), 0.2, 1e-12);
  EXPECT_NEAR((a.linear() * Vec3::UnitZ() - b.linear() * Vec3::UnitZ()).norm(), 0.0, 1e-12);
}

TEST(CameraPlacement, TheChainIsTheProductOfItsLinks) {
  // world ← robot(t) ← robot tilt ← mount ← rig tilt ← viewpoint, each link built here from its
  // own rotation and translation.
  const RobotPose robot{-0.7, 1.1, 200.0};
  const BodyVelocity v{0.5, 0.2, -60.0};
  const RobotMount mount{0.12, -0.05, 75.0};
  const RobotTilt robotTilt{1.5, -2.5};
  RigSpec rig = rigAt(0.35);
  rig.tiltDeg = {-0.75, 1.25};
  const CameraPlacement placement(robot, v, mount, robotTilt);
  const auto about = [](double deg, const Vec3& axis) { return Eigen::AngleAxisd(radians(deg), axis).toRotationMatrix(); };
  for (double t : {0.0, 0.03, 0.4}) {
    const RobotPose r = poseAfter(robot, v, t);
    Rigid worldFromRobot = Rigid::Identity();
    worldFromRobot.linear() = about(r.yawDeg, Vec3::UnitZ());
    worldFromRobot.translation() = Vec3(r.x, r.y, 0.0);
    Rigid tilt = Rigid::Identity();
    tilt.linear() = about(robotTilt[0], Vec3::UnitX()) * about(robotTilt[1], Vec3::UnitY());
    Rigid robotFromMount = Rigid::Identity();
    robotFromMount.linear() = about(mount.yawDeg, Vec3::UnitZ());
    robotFromMount.translation() = Vec3(mount.x, mount.y, 0.0);
    Rigid mountFromViewpoint = Rigid::Identity();
    mountFromViewpoint.linear() = about(rig.tiltDeg[0], Vec3::UnitX()) * about(rig.tiltDeg[1], Vec3::UnitY());
    mountFromViewpoint.translation() = mountFromViewpoint.linear() * Vec3(0.0, 0.0, rig.height);
    const Rigid want = worldFromRobot * tilt * robotFromMount * mountFromViewpoint;
    const Rigid got = placement.worldFromViewpoint(rig, t);
    EXPECT_LT((got.matrix() - want.matrix()).cwiseAbs().maxCoeff(), 1e-12) << t;
    // The unified model's axes: X = x, Y = −y, Z = −z of the viewpoint frame.
    const Rigid camera = placement.worldFromCamera(rig, t);
    expectNear(camera.linear().col(1), -got.linear().col(1));
    expectNear(camera.linear().col(2), -got.linear().col(2));
  }
}

TEST(CameraPlacement, AFrozenInstantIsExactlyThatInstant) {
  const CameraPlacement moving({0.3, -0.2, 15.0}, {1.0, 0.1, 90.0}, {0.1, 0.05, 20.0}, {1.0, 0.5});
  const RigSpec rig = rigAt(0.4);
  for (double t : {0.0, 0.004, 0.02}) {
    const CameraPlacement frozen = moving.frozenAt(t);
    EXPECT_TRUE(frozen.still());
    EXPECT_EQ(frozen.worldFromViewpoint(rig).matrix(), moving.worldFromViewpoint(rig, t).matrix()) << t;
    EXPECT_EQ(frozen.worldFromViewpoint(rig, 0.5).matrix(), moving.worldFromViewpoint(rig, t).matrix()) << t;
  }
}

TEST(CameraPlacement, AFrameMovesOnlyWhenTheRobotDrivesWhileAShutterIsOpen) {
  RigSpec rig = rigAt(0.4);
  EXPECT_FALSE(moving(CameraPlacement({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}), rig));  // an instant
  rig.shutter.exposureS = 0.01;
  EXPECT_TRUE(moving(CameraPlacement({0.0, 0.0, 0.0}, {1.0, 0.0, 0.0}), rig));
  EXPECT_FALSE(moving(CameraPlacement({0.0, 0.0, 0.0}), rig));
}

}  // namespace
}  // namespace omnicam
