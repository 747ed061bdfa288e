#include "landmark_annotations.h"

#include <gtest/gtest.h>

#include "scene_loader.h"

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

TEST(LandmarkAnnotations, CentresAreTheCameraProjectionAndWallsOcclude) {
  const Scene s = scene();
  const RayScene rays(s);
  const RobotPose pose{0.0, 0.0, 30.0};
  const auto a = annotateLandmarks(s, rays, s.rig, pose);
  ASSERT_EQ(a.size(), 3u);
  const OmniCamera camera = s.rig.camera();
  const auto expected = camera.rasterFromCamera(cameraFromWorld(s.rig, pose) * Vec3(2, 0, 0.3));
  ASSERT_TRUE(a[0].centre && expected);
  EXPECT_NEAR((*a[0].centre - *expected).norm(), 0.0, 1e-12);
  EXPECT_TRUE(a[0].visible());
  EXPECT_DOUBLE_EQ(a[0].visibleFraction, 1.0);
  EXPECT_NEAR(a[0].rangeM, 2.0, 1e-12);
  EXPECT_NEAR(a[0].bearingDeg, -30.0, 1e-9);  // the robot faces 30°: the landmark at 0° is 30° to its right
  ASSERT_TRUE(a[0].bbox);
  EXPECT_LT((*a[0].bbox)[0], a[0].centre->x());
  EXPECT_GT((*a[0].bbox)[2], a[0].centre->x());
  EXPECT_LT((*a[0].bbox)[1], a[0].centre->y());
  EXPECT_GT((*a[0].bbox)[3], a[0].centre->y());

  EXPECT_TRUE(a[1].inView());
  EXPECT_TRUE(a[1].occluded);
  EXPECT_FALSE(a[1].visible());
  EXPECT_DOUBLE_EQ(a[1].visibleFraction, 0.0);
  EXPECT_NEAR(std::abs(a[1].bearingDeg), 150.0, 1e-9);

  // Straight up, beyond the mirror's rim: not imaged at all.
  EXPECT_FALSE(a[2].inView());
  EXPECT_FALSE(a[2].bbox);
}

}  // namespace
}  // namespace omnicam
