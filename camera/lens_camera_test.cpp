// The lens cameras (issue #37) behind the camera interface: rays and projections invert each
// other everywhere the camera images; the lens is where its rotation puts it; the image scales;
// OpenCV's own projections (cv::fisheye, cv::projectPoints) of the same camera on the robot.
#include "lens_camera.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>

#include "make_camera.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

using test::fTheta;
using test::lensRig;

// One of each model, off-centre and turned, as a researcher would configure them.
std::vector<RigSpec> everyModel() {
  FThetaLens polynomial = fTheta(FThetaLens::Kind::Polynomial, 0.0, 190.0, 101.0, 73.5);
  polynomial.k = {0.0, 0.0125, 1.5e-5, -4e-8, 0.0};
  return {lensRig(KannalaBrandt{95.0, 96.0, 161.0, 118.0, {0.02, -0.005, 0.001, -0.0002}, radians(100.0)}, 320, 240, {2.0, 10.0, 20.0}),
          lensRig(DoubleSphere{120.0, 121.0, 160.5, 119.0, -0.2, 0.6}, 320, 240, {0.0, -30.0, 0.0}),
          lensRig(ExtendedUnified{150.0, 149.0, 158.0, 121.0, 0.6, 1.1}, 320, 240, {0.0, 0.0, 45.0}),
          lensRig(fTheta(FThetaLens::Kind::Equidistant, 40.0, 200.0, 104.5, 70.0), 200, 150, {10.0, 40.0, 30.0}),
          lensRig(fTheta(FThetaLens::Kind::Equisolid, 55.0, 180.0, 79.5, 79.5), 160, 160),
          lensRig(polynomial, 200, 150, {0.0, 30.0, 0.0}),
          lensRig(Equirectangular{256, 128, radians(-120.0), radians(60.0), radians(-60.0), radians(20.0)}, 256, 128, {5.0, 10.0, -40.0}),
          lensRig(PinholeRadTan{300.0, 302.0, 161.0, 118.0, {-0.2, 0.05, 0.001, -0.002, 0.01}}, 320, 240, {0.0, 15.0, 0.0})};
}

TEST(LensCamera, RaysAndProjectionsInvertEachOtherWhereverTheCameraImages) {
  for (const RigSpec& rig : everyModel()) {
    const std::shared_ptr<const Camera> camera = makeCamera(rig);
    ASSERT_NE(dynamic_cast<const LensCamera*>(camera.get()), nullptr);
    EXPECT_EQ(camera->model(), lensModelName(rig.lensCamera().model));
    EXPECT_EQ(camera->width(), rig.lensCamera().width);
    EXPECT_EQ(camera->height(), rig.lensCamera().height);
    int imaged = 0;
    double worst = 0.0;
    for (double y = 0.25; y < camera->height(); y += 1.5)
      for (double x = 0.25; x < camera->width(); x += 1.5) {
        const Vec2 raster(x, y);
        const auto ray = camera->generateRay({raster});
        ASSERT_EQ(ray.has_value(), camera->images(raster)) << camera->model() << " " << x << "," << y;
        if (!ray) continue;
        ++imaged;
        EXPECT_EQ(ray->origin, Vec3::Zero());
        EXPECT_NEAR(ray->direction.norm(), 1.0, 1e-14);
        const auto back = camera->project(2.7 * ray->direction);
        ASSERT_TRUE(back) << camera->model() << " " << x << "," << y;
        worst = std::max(worst, (*back - raster).norm());
      }
    EXPECT_LE(worst, 1e-9) << camera->model();
    EXPECT_GT(imaged, camera->width() * camera->height() / 2.25 / 4) << camera->model();
  }
}

// A lens looks along robot +x with its image's right along −y (robot right) and down along −z;
// pitch −90° looks straight up, yaw 90° to the left.
TEST(LensCamera, TheLensLooksWhereItsRotationSays) {
  const PinholeRadTan pinhole{100.0, 100.0, 49.5, 39.5, {}};
  const auto centreRay = [&](std::array<double, 3> rotation) {
    return LensCamera(lensRig(pinhole, 100, 80, rotation)).generateRay({Vec2(50.0, 40.0)})->direction;
  };
  EXPECT_LT((centreRay({0.0, 0.0, 0.0}) - Vec3::UnitX()).norm(), 1e-15);
  EXPECT_LT((centreRay({0.0, -90.0, 0.0}) - Vec3::UnitZ()).norm(), 1e-15);
  EXPECT_LT((centreRay({0.0, 90.0, 0.0}) + Vec3::UnitZ()).norm(), 1e-15);
  EXPECT_LT((centreRay({0.0, 0.0, 90.0}) - Vec3::UnitY()).norm(), 1e-15);
  EXPECT_LT((centreRay({35.0, 0.0, 0.0}) - Vec3::UnitX()).norm(), 1e-15);  // roll turns the image about its axis
  const LensCamera level(lensRig(pinhole, 100, 80));
  const Vec3 right = level.generateRay({Vec2(60.0, 40.0)})->direction, down = level.generateRay({Vec2(50.0, 50.0)})->direction;
  EXPECT_NEAR(right.y(), -0.1 / std::sqrt(1.01), 1e-15);
  EXPECT_NEAR(down.z(), -0.1 / std::sqrt(1.01), 1e-15);
  // The camera frame of the frame chain (poses.tum, sidecars): OpenCV's axes of the lens.
  const RigSpec turned = lensRig(pinhole, 100, 80, {0.0, -90.0, 0.0});
  const Rigid cameraFromView = cameraFromViewpoint(turned);
  EXPECT_LT((cameraFromView * Vec3(0.0, 0.0, 2.0) - Vec3(0.0, 0.0, 2.0)).norm(), 1e-15);  // up is its optical axis
  EXPECT_LT((cameraFromView * Vec3(0.0, -1.0, 0.0) - Vec3(1.0, 0.0, 0.0)).norm(), 1e-15);  // robot right is image right
}

// The same camera at another size: a direction's raster point scales with the image (omnicam's
// raster runs over [0, W] × [0, H], so it scales exactly).
TEST(LensCamera, AResizedLensImagesTheSameDirectionsAtScaledPoints) {
  for (const RigSpec& rig : everyModel()) {
    const RigSpec large = rig.resized(2 * rig.lensCamera().width);
    ASSERT_EQ(large.lensCamera().height, 2 * rig.lensCamera().height);
    const LensCamera small(rig), big(large);
    for (double y = 3.3; y < small.height(); y += 7.0)
      for (double x = 2.1; x < small.width(); x += 7.0) {
        const auto ray = small.generateRay({Vec2(x, y)});
        if (!ray) continue;
        const auto there = big.project(ray->direction);
        ASSERT_TRUE(there) << small.model();
        EXPECT_LT((*there - 2.0 * Vec2(x, y)).norm(), 1e-9) << small.model();
      }
  }
}

// cv::fisheye::projectPoints reproduces the Kannala–Brandt camera on the robot (its lens turned,
// OpenCV's pixel centres at integers: ours minus ½) to 0.01 px — in fact to 1e-9.
TEST(LensCamera, OpenCvFisheyeProjectsLikeTheKannalaBrandtCamera) {
  const KannalaBrandt kb{95.0, 96.0, 161.0, 118.0, {0.02, -0.005, 0.001, -0.0002}, radians(89.0)};
  const RigSpec rig = lensRig(kb, 320, 240, {2.0, 10.0, 20.0});
  const LensCamera camera(rig);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  for (double y = 0.5; y < 240; y += 9.0)
    for (double x = 0.5; x < 320; x += 9.0) {
      const auto ray = camera.generateRay({Vec2(x, y)});
      if (!ray) continue;
      const Vec3 p = cameraFromViewpoint(rig) * Vec3(1.7 * ray->direction);  // in the lens' (OpenCV's) frame
      points.emplace_back(p.x(), p.y(), p.z());
      ours.emplace_back(x, y);
    }
  ASSERT_GT(points.size(), 500u);
  std::vector<cv::Point2d> projected;
  const cv::Matx33d k(kb.fx, 0.0, kb.cx, 0.0, kb.fy, kb.cy, 0.0, 0.0, 1.0);
  cv::fisheye::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k,
                             cv::Vec4d(kb.k[0], kb.k[1], kb.k[2], kb.k[3]));
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  EXPECT_LE(worst, 0.01);
  EXPECT_LE(worst, 1e-8);
}

// cv::projectPoints reproduces the distorted pinhole (k1, k2, p1, p2, k3) on the robot.
TEST(LensCamera, OpenCvProjectPointsProjectsLikeTheDistortedPinhole) {
  const PinholeRadTan p{300.0, 302.0, 161.0, 118.0, {-0.2, 0.05, 0.001, -0.002, 0.01}};
  const RigSpec rig = lensRig(p, 320, 240, {0.0, 15.0, 0.0});
  const LensCamera camera(rig);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  for (double y = 0.5; y < 240; y += 7.0)
    for (double x = 0.5; x < 320; x += 7.0) {
      const auto ray = camera.generateRay({Vec2(x, y)});
      ASSERT_TRUE(ray);
      const Vec3 q = cameraFromViewpoint(rig) * Vec3(2.0 * ray->direction);
      points.emplace_back(q.x(), q.y(), q.z());
      ours.emplace_back(x, y);
    }
  std::vector<cv::Point2d> projected;
  const cv::Matx33d k(p.fx, 0.0, p.cx, 0.0, p.fy, p.cy, 0.0, 0.0, 1.0);
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k,
                    std::vector<double>{p.distortion.k1, p.distortion.k2, p.distortion.p1, p.distortion.p2, p.distortion.k3},
                    projected);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  EXPECT_LE(worst, 1e-8);
}

// Rig equality (the one definition every cache uses) sees the lens.
TEST(LensCamera, RigEqualitySeesEveryLensField) {
  const RigSpec a = everyModel().front();
  RigSpec b = a;
  EXPECT_TRUE(a == b);
  std::get<KannalaBrandt>(b.lensCamera().model).k[3] += 1e-12;
  EXPECT_FALSE(a == b);
  b = a;
  b.lensCamera().rotationDeg[1] += 1e-9;
  EXPECT_FALSE(a == b);
  EXPECT_FALSE(*makeCamera(a) == *makeCamera(b));
}

}  // namespace
}  // namespace omnicam
