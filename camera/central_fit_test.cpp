// The best-fit central model: our Mei projection is cv::omnidir's; for a rig that is exactly
// central (the aligned pinhole with a lens) the fit recovers the closed-form rescaled D with no
// residual at any distance; a turned pinhole at F stays central (one residual at every
// distance); a moved one is not: its residual differs from the fit's at infinity by a parallax
// that falls as 1/distance.
#include "central_fit.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/ccalib/omnidir.hpp>
#include <random>

#include "physical_camera.h"

namespace omnicam {
namespace {

TEST(CentralFit, MeiProjectionIsOpenCvOmnidirs) {
  MeiIntrinsics k;
  k.xi = 0.93, k.gammaX = 181.5, k.gammaY = -179.25, k.cx = 179.4, k.cy = 181.2;
  k.lens = {-0.11, 0.027, 0.0013, -0.0009, 0.0};
  std::mt19937 rng(41);
  std::uniform_real_distribution<double> coord(-3.0, 3.0);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  while (points.size() < 5000) {
    const Vec3 p(coord(rng), coord(rng), coord(rng));
    const auto raster = k.raster(p);
    if (!raster || p.normalized().z() < -0.5) continue;  // keep to the part of the sphere the model images
    points.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*raster);
  }
  const cv::Matx33d K(k.gammaX, 0.0, k.cx, 0.0, k.gammaY, k.cy, 0.0, 0.0, 1.0);
  const cv::Matx14d D(k.lens.k1, k.lens.k2, k.lens.p1, k.lens.p2);
  std::vector<cv::Point2d> projected;
  cv::omnidir::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, k.xi, D);
  double worst = 0.0;
  for (size_t i = 0; i < ours.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  EXPECT_LE(worst, 1e-9);
}

// The lift back to the sphere against OpenCV's omnidir::undistortPoints (which returns the ray
// as (x/z, y/z): compared where z > 0) and against our own projection (round trip).
TEST(CentralFit, MeiDirectionIsOpenCvsUndistortionAndInvertsTheProjection) {
  MeiIntrinsics k;
  k.xi = 0.93, k.gammaX = 181.5, k.gammaY = -179.25, k.cx = 179.4, k.cy = 181.2;
  k.lens = {-0.05, 0.01, 0.0013, -0.0009, 0.0};
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> pixel(20.0, 340.0);
  std::vector<cv::Point2d> distorted;
  std::vector<Vec3> ours;
  double roundTrip = 0.0;
  while (distorted.size() < 2000) {
    const Vec2 raster(pixel(rng), pixel(rng));
    const auto d = k.direction(raster);
    if (!d) continue;
    ASSERT_NEAR(d->norm(), 1.0, 1e-12);
    const auto back = k.raster(*d);
    ASSERT_TRUE(back.has_value());
    roundTrip = std::max(roundTrip, (*back - raster).norm());
    if (d->z() < 0.2) continue;  // OpenCV's perspective output needs z > 0
    distorted.emplace_back(raster.x() - 0.5, raster.y() - 0.5);
    ours.push_back(*d);
  }
  EXPECT_LE(roundTrip, 1e-9);
  const cv::Matx33d K(k.gammaX, 0.0, k.cx, 0.0, k.gammaY, k.cy, 0.0, 0.0, 1.0);
  const cv::Matx14d D(k.lens.k1, k.lens.k2, k.lens.p1, k.lens.p2);
  std::vector<cv::Point2d> undistorted;
  cv::omnidir::undistortPoints(distorted, undistorted, K, D, cv::Mat(1, 1, CV_64F, cv::Scalar(k.xi)), cv::Matx33d::eye());
  double worst = 0.0;
  for (size_t i = 0; i < ours.size(); ++i) {
    const Vec3 theirs = Vec3(undistorted[i].x, undistorted[i].y, 1.0).normalized();
    worst = std::max(worst, std::acos(std::min(1.0, theirs.dot(ours[i]))));
  }
  // OpenCV inverts the distortion by 20 fixed-point steps: agreement to its precision.
  EXPECT_LE(worst, 1e-6) << "radians";
}

TEST(CentralFit, RecoversTheExactModelOfTheAlignedDistortedRig) {
  RigSpec rig;
  rig.mirrorRig().mount.distortion = {-0.09, 0.02, 0.0011, -0.0007, 0.0};
  rig.mirrorRig().mount.principalPointOffsetPx = {0.9, -1.3};
  const CentralApproximation fit = fitCentralApproximation(PhysicalCamera(rig));
  // Closed form (docs/physical-camera.md): the pinhole's normalised coordinates are Mei's scaled by
  // s = γ/f with v flipped, so D = (k1 s², k2 s⁴, −p1 s, p2 s).
  const OmniCamera ideal = rig.mirrorRig().idealCamera();
  const double s = ideal.gamma() / ideal.physicalFocalLength();
  const LensDistortion& l = rig.mirrorRig().mount.distortion;
  EXPECT_NEAR(fit.intrinsics.lens.k1, l.k1 * s * s, 1e-7);
  EXPECT_NEAR(fit.intrinsics.lens.k2, l.k2 * s * s * s * s, 1e-7);
  EXPECT_NEAR(fit.intrinsics.lens.p1, -l.p1 * s, 1e-8);
  EXPECT_NEAR(fit.intrinsics.lens.p2, l.p2 * s, 1e-8);
  EXPECT_NEAR(fit.intrinsics.xi, ideal.xi(), 1e-8);
  EXPECT_NEAR(fit.intrinsics.gammaX, ideal.gamma(), 1e-6);
  EXPECT_NEAR(fit.intrinsics.gammaY, -ideal.gamma(), 1e-6);
  EXPECT_NEAR(fit.intrinsics.cx, rig.mirrorRig().imageSize / 2.0 + 0.9 - 0.5, 1e-7);
  EXPECT_NEAR(fit.intrinsics.cy, rig.mirrorRig().imageSize / 2.0 - 1.3 - 0.5, 1e-7);
  EXPECT_LE(fit.viewpoint.norm(), 1e-12);       // every ray passes through F'
  EXPECT_LE(fit.rotationVector.norm(), 1e-9);
  ASSERT_EQ(fit.residuals.size(), 5u);
  for (const auto& r : fit.residuals) EXPECT_LE(r.maxPx, 1e-6) << "at " << r.distanceM << " m";
}

// The ray error in closed form: the exact model of the ideal rig turned by α = 1 mrad about its
// viewpoint's z axis errs at each pixel by the angle the turn moves that pixel's ray,
// 2·asin(sin(α/2)·|z × d|); moved 1 cm sideways, by the parallax of a point 0.5 m away seen from
// 1 cm off, at most asin(0.01/0.5) (a ray across the offset).
TEST(CentralFit, TheRayErrorOfATurnedOrMovedExactModelIsItsAngle) {
  RigSpec rig;
  const PhysicalCamera camera(rig);
  const CentralApproximation exact = fitCentralApproximation(camera);
  const double alpha = 1e-3;
  CentralApproximation turned = exact;
  turned.cameraFromViewpoint.linear() = exact.cameraFromViewpoint.linear() * Eigen::AngleAxisd(alpha, Vec3::UnitZ()).toRotationMatrix();
  const std::vector<float> map = centralRayErrorMap(camera, turned, 0.0);
  double worst = 0.0;
  int pixels = 0;
  for (int j = 0; j < camera.height(); ++j)
    for (int i = 0; i < camera.width(); ++i) {
      const float e = map[static_cast<size_t>(j) * camera.width() + i];
      const auto ray = camera.generateRay({Vec2(i + 0.5, j + 0.5)});
      ASSERT_EQ(std::isnan(e), !ray.has_value());
      if (!ray) continue;
      const double expected = 2.0 * std::asin(std::sin(alpha / 2.0) * Vec3::UnitZ().cross(ray->direction).norm());
      worst = std::max(worst, std::abs(e - expected));
      ++pixels;
    }
  EXPECT_GT(pixels, 10000);
  EXPECT_LT(worst, 1e-7) << "radians";
  for (float e : centralRayErrorMap(camera, exact, 0.5)) {
    if (!std::isnan(e)) {
      EXPECT_LT(e, 1e-7);
    }
  }
  CentralApproximation moved = exact;
  moved.viewpoint = Vec3(0.01, 0.0, 0.0);
  moved.cameraFromViewpoint.translation() = -(exact.cameraFromViewpoint.linear() * moved.viewpoint);
  double hi = 0.0;
  for (float e : centralRayErrorMap(camera, moved, 0.5))
    if (!std::isnan(e)) hi = std::max(hi, static_cast<double>(e));
  EXPECT_NEAR(hi, std::asin(0.01 / 0.5), 2e-4);
}

TEST(CentralFit, ATurnedPinholeAtTheFocusStaysCentral) {
  RigSpec rig;
  rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
  const CentralApproximation fit = fitCentralApproximation(PhysicalCamera(rig));
  EXPECT_LE(fit.viewpoint.norm(), 1e-12);  // every ray still passes through F'
  // A tilted image plane is not quite Mei's (its tangential terms absorb most of it) ...
  EXPECT_GT(fit.residuals[0].maxPx, 1e-4);
  EXPECT_LT(fit.residuals[0].maxPx, 0.05);
  // ... but with no parallax the misfit is the same at every distance.
  for (const auto& r : fit.residuals) EXPECT_NEAR(r.rmsPx, fit.residuals[0].rmsPx, 1e-9) << "at " << r.distanceM << " m";
}

TEST(CentralFit, AMovedPinholesParallaxFallsWithDistance) {
  RigSpec rig;  // the demo's misalignment: 2 mm and 1°
  rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
  rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
  const PhysicalCamera camera(rig);
  const CentralApproximation& fit = camera.centralApproximation();
  ASSERT_EQ(fit.residuals.size(), 5u);
  for (const auto& r : fit.residuals)
    std::printf("best-fit central model, %s m: rms %.4f px, max %.4f px\n",
                r.distanceM == 0.0 ? "infinity" : std::to_string(r.distanceM).c_str(), r.rmsPx, r.maxPx);
  // The rays do not meet: the viewpoint is a compromise, away from F' but near it.
  EXPECT_GT(fit.viewpoint.norm(), 1e-5);
  EXPECT_LT(fit.viewpoint.norm(), 5e-3);
  // An off-axis pinhole's image is not Mei's: pixels of misfit even at infinity.
  EXPECT_GT(fit.residuals[0].rmsPx, 0.5);
  // Closer points add parallax: the residual departs from the fit's as about 1/distance.
  const auto parallax = [&](size_t i) { return std::abs(fit.residuals[i].rmsPx - fit.residuals[0].rmsPx); };
  for (size_t i = 2; i < fit.residuals.size(); ++i) EXPECT_LT(parallax(i), parallax(i - 1)) << "at " << fit.residuals[i].distanceM;
  EXPECT_LT(parallax(4), parallax(1) / 10.0);  // 5 m against 0.2 m: 1/25 for a pure 1/d
  EXPECT_GT(parallax(1), 1e-3);
  // The per-pixel map holds every pixel, the grid's among them.
  const std::vector<float> map = centralResidualMap(camera, fit, 1.0);
  ASSERT_EQ(map.size(), static_cast<size_t>(rig.mirrorRig().imageSize * rig.mirrorRig().imageSize));
  float worst = 0.0f;
  int imaged = 0;
  for (float v : map)
    if (!std::isnan(v)) worst = std::max(worst, v), ++imaged;
  EXPECT_GT(imaged, fit.rays);
  EXPECT_GE(worst, fit.residuals[3].maxPx - 1e-4);
  EXPECT_LE(worst, 2.0 * fit.residuals[3].maxPx);
  const nlohmann::json described = camera.describe();
  EXPECT_TRUE(described["non_central"].get<bool>());
  EXPECT_FALSE(described.contains("mei_equivalent"));
  ASSERT_TRUE(described.contains("central_approximation"));
  EXPECT_EQ(described["central_approximation"]["residual_px"].size(), 5u);
  EXPECT_EQ(described["central_approximation"]["residual_px"][1]["distance_m"], 0.2);
}

}  // namespace
}  // namespace omnicam
