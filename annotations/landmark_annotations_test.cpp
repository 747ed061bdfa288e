#include "landmark_annotations.h"

#include <gtest/gtest.h>

#include <cmath>

#include "make_camera.h"
#include "scene_loader.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

// Two landmarks 2 m from the robot: one in the open at +X, one at −X behind a wall.
Scene scene() {
  return loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "box", "name": "wall", "material": "m", "center": [-1, 0, 0.5], "size": [0.1, 2, 1]}],
    "landmarks": [
      {"name": "open", "position": [2, 0, 0.3], "diameter": 0.1, "height": 0.1, "colour_class": "cyan"},
      {"name": "hidden", "position": [-2, 0, 0.3], "diameter": 0.1, "height": 0.1, "colour_class": "magenta"},
      {"name": "overhead", "position": [0, 0.05, 5], "diameter": 0.1, "height": 0.1, "colour_class": "yellow"}]})",
                           "landmarks.json");
}

// The unified (Mei) projection written out from docs/conventions.md §1, independent of
// OmniCamera: ξ from k, γ from the framing, the robot frame from the pose, F' `height` above the
// floor; a direction at incidence θ from straight down lands γ sinθ / (ξ + cosθ) from the centre,
// u along the robot's +x, v along its +y.
Vec2 closedFormRaster(const RigSpec& rig, const RobotPose& pose, const Vec3& world) {
  const double eps = std::sqrt(rig.mirrorRig().hyperboloid().k / (rig.mirrorRig().hyperboloid().k - 2.0));
  const double xi = 2.0 * eps / (1.0 + eps * eps);
  const double framing = (90.0 + rig.mirrorRig().hyperboloid().framingElevationDeg) * kPi / 180.0;
  const double gamma = 0.5 * rig.mirrorRig().imageSize * (xi + std::cos(framing)) / std::sin(framing);
  const double yaw = pose.yawDeg * kPi / 180.0;
  const double dx = world.x() - pose.x, dy = world.y() - pose.y, dz = world.z() - rig.height;
  const double x = std::cos(yaw) * dx + std::sin(yaw) * dy, y = -std::sin(yaw) * dx + std::cos(yaw) * dy;
  const double theta = std::acos(-dz / std::sqrt(x * x + y * y + dz * dz));
  const double r = gamma * std::sin(theta) / (xi + std::cos(theta));
  const double phi = std::atan2(y, x);
  return {0.5 * rig.mirrorRig().imageSize + r * std::cos(phi), 0.5 * rig.mirrorRig().imageSize + r * std::sin(phi)};
}

TEST(LandmarkAnnotations, CentresAreTheCameraProjectionAndWallsOcclude) {
  const Scene s = scene();
  const RayScene rays(s);
  const RobotPose pose{0.0, 0.0, 30.0};
  const auto a = annotateLandmarks(s, rays, s.rig, pose);
  ASSERT_EQ(a.size(), 3u);
  ASSERT_TRUE(a[0].centre);
  EXPECT_NEAR((*a[0].centre - closedFormRaster(s.rig, pose, Vec3(2, 0, 0.3))).norm(), 0.0, 1e-9);
  EXPECT_TRUE(a[0].visible());
  EXPECT_DOUBLE_EQ(a[0].visibleFraction, 1.0);
  EXPECT_NEAR(a[0].rangeM, 2.0, 1e-12);
  EXPECT_NEAR(a[0].bearingDeg, -30.0, 1e-9);  // the robot faces 30°: the landmark at 0° is 30° to its right
  // The box bounds the cylinder's top and bottom circles (radius 0.05 m at z = 0.25, 0.35 m):
  // here from 720 points per circle; the 32 per circle of annotateLandmarks fall short by at most
  // r (1 − cos(π/32)) = 0.012 px for this 4.8 px wide band (measured ≤ 0.0033 px).
  ASSERT_TRUE(a[0].bbox);
  Eigen::AlignedBox2d outline;
  for (double z : {0.25, 0.35})
    for (int k = 0; k < 720; ++k)
      outline.extend(closedFormRaster(s.rig, pose, Vec3(2 + 0.05 * std::cos(k * kPi / 360), 0.05 * std::sin(k * kPi / 360), z)));
  EXPECT_GT(outline.sizes().minCoeff(), 1.0);
  EXPECT_NEAR((*a[0].bbox)[0], outline.min().x(), 0.015);
  EXPECT_NEAR((*a[0].bbox)[1], outline.min().y(), 0.015);
  EXPECT_NEAR((*a[0].bbox)[2], outline.max().x(), 0.015);
  EXPECT_NEAR((*a[0].bbox)[3], outline.max().y(), 0.015);

  ASSERT_TRUE(a[1].inView());
  EXPECT_NEAR((*a[1].centre - closedFormRaster(s.rig, pose, Vec3(-2, 0, 0.3))).norm(), 0.0, 1e-9);
  EXPECT_TRUE(a[1].occluded);
  EXPECT_FALSE(a[1].visible());
  EXPECT_DOUBLE_EQ(a[1].visibleFraction, 0.0);
  EXPECT_NEAR(std::abs(a[1].bearingDeg), 150.0, 1e-9);

  // Straight up, beyond the mirror's rim: not imaged at all.
  EXPECT_FALSE(a[2].inView());
  EXPECT_FALSE(a[2].bbox);
}

TEST(LandmarkAnnotations, UnderARollingShutterEachLandmarkIsWhereItsOwnLineSeesIt) {
  // Driving at 1 m/s while turning at 90°/s, read top to bottom at 1 ms a line: the "open"
  // landmark's centre is at the closed-form projection from the pose of its own line's time, and
  // its line is the one that time belongs to.
  const Scene s = scene();
  const RayScene rays(s);
  RigSpec rig = s.rig;
  rig.shutter = {0.002, RollingShutter{1000.0, Readout::TopToBottom}, 0};
  const RobotPose start{0.0, 0.0, 10.0};
  const BodyVelocity driving{1.0, 0.0, 90.0};
  const auto moving = annotateLandmarks(s, rays, rig, CameraPlacement(start, driving));
  ASSERT_TRUE(moving[0].centre.has_value());
  const int row = static_cast<int>(std::floor(moving[0].centre->y()));
  const RobotPose then = poseAfter(start, driving, row * 1e-3 + 0.001);
  const Vec2 expected = closedFormRaster(rig, then, s.landmarks[0].position);
  EXPECT_NEAR(moving[0].centre->x(), expected.x(), 1e-6);
  EXPECT_NEAR(moving[0].centre->y(), expected.y(), 1e-6);
  EXPECT_NEAR(moving[0].bearingDeg, -then.yawDeg + std::atan2(-then.y, 2.0 - then.x) * 180.0 / kPi, 1e-9);
  // Far from where the start pose sees it: the motion is there.
  const Vec2 still = closedFormRaster(rig, start, s.landmarks[0].position);
  EXPECT_GT((*moving[0].centre - still).norm(), 5.0);
  EXPECT_TRUE(moving[1].occluded);  // still behind the wall
}

// Near the mirror's rim the side facing the camera may lie beyond it while the centre is imaged:
// that side is not seen, but nothing hides it, so the landmark is visible, not occluded. A floor
// and one band, its centre 1° below the rim (45° up) seen from F' 0.4 m up, 1 m away.
TEST(LandmarkAnnotations, ALandmarkWhoseFacingSideIsBeyondTheRimIsNotOccluded) {
  const Scene s = loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "quad", "name": "floor", "material": "m", "origin": [-9, -9, 0], "edge_u": [18, 0, 0], "edge_v": [0, 18, 0]}],
    "landmarks": [{"name": "near_rim", "position": [1, 0, 1.3825], "diameter": 0.1, "height": 0.1, "colour_class": "cyan"}]})",
                                    "rim.json");
  const RayScene rays(s);
  const RobotPose pose{0.0, 0.0, 0.0};
  const double rimPx = 0.5 * s.rig.mirrorRig().imageSize;
  const Vec2 middle(rimPx, rimPx);
  // The premise, from the closed form: the centre inside the rim's circle, the facing point (5 cm
  // nearer) outside it.
  ASSERT_LT((closedFormRaster(s.rig, pose, Vec3(1.0, 0, 1.3825)) - middle).norm(), rimPx);
  ASSERT_GT((closedFormRaster(s.rig, pose, Vec3(0.95, 0, 1.3825)) - middle).norm(), rimPx);
  const auto a = annotateLandmarks(s, rays, s.rig, pose);
  ASSERT_TRUE(a[0].inView());
  EXPECT_FALSE(a[0].occluded);
  EXPECT_TRUE(a[0].visible());
  EXPECT_GT(a[0].visibleFraction, 0.0);  // its far-side points are seen
  EXPECT_LT(a[0].visibleFraction, 1.0);  // and the facing ones beyond the rim are not
}

// A tilted rig's F' stands off its foot (h sin 10° = 7 cm here); range and bearing are the foot's,
// as the detector's inversion (landmark_geometry.h) and the EKF measure them.
TEST(LandmarkAnnotations, RangeAndBearingAreFromTheFootOfATiltedRig) {
  const Scene s = loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "rig": {"tilt_deg": [10, 0]},
    "objects": [{"type": "quad", "name": "floor", "material": "m", "origin": [-9, -9, 0], "edge_u": [18, 0, 0], "edge_v": [0, 18, 0]}],
    "landmarks": [{"name": "left", "position": [0, 2, 0.3], "diameter": 0.1, "height": 0.1, "colour_class": "cyan"},
                  {"name": "behind", "position": [-1.75, -0.25, 0.3], "diameter": 0.1, "height": 0.1, "colour_class": "cyan"}]})",
                                    "tilted.json");
  const RayScene rays(s);
  const RobotPose pose{0.5, -0.25, 0.0};
  const Vec3 viewpoint = CameraPlacement(pose).worldFromViewpoint(s.rig).translation();
  ASSERT_GT((viewpoint.head<2>() - Vec2(0.5, -0.25)).norm(), 0.06);
  const auto a = annotateLandmarks(s, rays, s.rig, pose);
  EXPECT_NEAR(a[0].rangeM, std::hypot(-0.5, 2.25), 1e-12);
  EXPECT_NEAR(a[0].bearingDeg, degrees(std::atan2(2.25, -0.5)), 1e-9);
  EXPECT_NEAR(a[1].rangeM, 2.25, 1e-12);
  EXPECT_NEAR(a[1].bearingDeg, 180.0, 1e-9);  // straight behind: +180, never −180
}

// A lens camera projects beyond its image rectangle (Camera::project is not clipped): a landmark
// whose centre lands off the image is not in view, and its box is its outline's clipped to the
// image, none when the outline lies wholly off it. An equidistant fisheye of 200° on a 64 × 48
// image whose circle (50 px) overhangs the rectangle, with landmarks all around at 2 m.
TEST(LandmarkAnnotations, ALensCamerasLandmarksOffTheImageAreNotInViewAndBoxesStayOnIt) {
  std::string landmarks;
  for (int k = 0; k < 72; ++k) {
    const double a = radians(5.0 * k);
    landmarks += std::string(k ? ", " : "") + R"({"name": "l)" + std::to_string(k) + R"(", "position": [)" +
                 std::to_string(2.0 * std::cos(a)) + ", " + std::to_string(2.0 * std::sin(a)) +
                 R"(, 0.3], "diameter": 0.4, "height": 0.2, "colour_class": "cyan"})";
  }
  const Scene s = loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"m": {}},
    "objects": [{"type": "quad", "name": "floor", "material": "m", "origin": [-9, -9, 0], "edge_u": [18, 0, 0], "edge_v": [0, 18, 0]}],
    "landmarks": [)" + landmarks + "]}",
                                    "ring.json");
  const RayScene rays(s);
  const RigSpec rig = test::lensRig(test::equidistant(50.0 / radians(100.0), 200.0, 64, 48), 64, 48);
  const auto camera = makeCamera(rig);
  const RobotPose pose{0.0, 0.0, 0.0};
  const Rigid viewpointFromWorld = CameraPlacement(pose).worldFromViewpoint(rig).inverse();
  const auto annotations = annotateLandmarks(s, rays, rig, pose);
  int offImage = 0, straddling = 0, onImage = 0;
  for (const LandmarkAnnotation& a : annotations) {
    const auto raster = camera->project(viewpointFromWorld * a.landmark->position);
    const bool inside = raster && raster->x() >= 0 && raster->x() < 64 && raster->y() >= 0 && raster->y() < 48;
    EXPECT_EQ(a.inView(), inside) << a.landmark->name;
    if (inside) {
      ++onImage;
      EXPECT_EQ(*a.centre, *raster) << a.landmark->name;
    } else if (raster) {
      ++offImage;
      EXPECT_FALSE(a.visible()) << a.landmark->name;
      straddling += a.bbox.has_value();
    }
    if (a.bbox) {
      const auto& [uMin, vMin, uMax, vMax] = *a.bbox;
      EXPECT_TRUE(0 <= uMin && uMin < uMax && uMax <= 64 && 0 <= vMin && vMin < vMax && vMax <= 48)
          << a.landmark->name << ": [" << uMin << ", " << vMin << ", " << uMax << ", " << vMax << "]";
    }
  }
  // Every case is exercised: seen, projected off the image, and reaching into it from there.
  EXPECT_GT(onImage, 10);
  EXPECT_GT(offImage - straddling, 2);
  EXPECT_GT(straddling, 0);
}

}  // namespace
}  // namespace omnicam
