// Projecting a point and inverting its pixel at the point's known height gives back its range
// and bearing (closed form: the horizontal distance and angle from F').
#include "landmark_geometry.h"
#include "placement.h"

#include <gtest/gtest.h>

#include <cmath>

namespace omnicam {
namespace {

TEST(LandmarkGeometry, InvertingTheProjectionAtTheKnownHeightRecoversRangeAndBearing) {
  RigSpec rig;
  const RobotPose pose{0.3, -0.4, 35.0};
  const OmniCamera camera = rig.camera();
  for (const Vec3& point : {Vec3(1.35, -1.95, 0.35), Vec3(-1.35, 1.95, 0.25), Vec3(2.0, 0.5, 0.0), Vec3(0.0, 0.4, 0.1)}) {
    const auto raster = camera.rasterFromCamera(CameraPlacement(pose).worldFromCamera(rig).inverse() * point);
    ASSERT_TRUE(raster);
    const auto rb = rangeBearingFromRaster(rig, *raster, point.z());
    ASSERT_TRUE(rb);
    const double dx = point.x() - pose.x, dy = point.y() - pose.y;
    EXPECT_NEAR(rb->x(), std::hypot(dx, dy), 1e-9);
    EXPECT_NEAR(wrapAngle(rb->y() - (std::atan2(dy, dx) - radians(pose.yawDeg))), 0.0, 1e-9);
  }
  // A point at the viewpoint's own height lies on the horizon: no finite range.
  EXPECT_FALSE(rangeBearingFromRaster(rig, {180.0 + camera.horizonRadius(), 180.0}, rig.height));
  // Above F' (seen above the horizon), a point cannot be on a ray that goes down.
  EXPECT_FALSE(rangeBearingFromRaster(rig, {190.0, 180.0}, 1.0));
}

}  // namespace
}  // namespace omnicam
