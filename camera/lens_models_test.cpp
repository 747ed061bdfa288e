// The lens models against independent implementations: Kannala–Brandt against OpenCV's
// cv::fisheye::projectPoints; the double sphere against its geometric definition (two spheres and
// a pinhole, written here step by step); EUCM against the unified (Mei) model it extends (an
// ellipsoid is a sphere after scaling x and y by √β); the f-θ lenses and the panorama against
// their closed forms at known angles; and every model's unprojection against its projection.
#include "lens_models.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <random>

#include "central_fit.h"

namespace omnicam {
namespace {

// Random unit directions within `maxTheta` of the optical axis (+Z).
std::vector<Vec3> directionsWithin(double maxTheta, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<Vec3> out;
  while (static_cast<int>(out.size()) < count) {
    const double theta = maxTheta * std::sqrt(unit(rng)), phi = 2.0 * kPi * unit(rng);
    out.emplace_back(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), std::cos(theta));
  }
  return out;
}

const KannalaBrandt kKannalaBrandt{380.0, 381.5, 639.3, 479.8, {0.05, -0.012, 0.003, -0.0004}, 1.4};
const DoubleSphere kDoubleSphere{313.2, 313.9, 638.1, 512.7, -0.21, 0.59};
const ExtendedUnified kExtendedUnified{463.1, 462.4, 640.2, 511.9, 0.63, 1.07};

TEST(LensModels, KannalaBrandtIsOpenCvsFisheye) {
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  for (const Vec3& d : directionsWithin(1.4, 5000, 3)) {
    const Vec3 p = 2.5 * d;
    points.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*lensProject(kKannalaBrandt, p));
  }
  const cv::Matx33d K(kKannalaBrandt.fx, 0, kKannalaBrandt.cx, 0, kKannalaBrandt.fy, kKannalaBrandt.cy, 0, 0, 1);
  const cv::Vec4d D(kKannalaBrandt.k[0], kKannalaBrandt.k[1], kKannalaBrandt.k[2], kKannalaBrandt.k[3]);
  std::vector<cv::Point2d> theirs;
  cv::fisheye::projectPoints(points, theirs, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, D);
  double worst = 0.0;
  for (size_t i = 0; i < ours.size(); ++i) worst = std::max(worst, (ours[i] - Vec2(theirs[i].x, theirs[i].y)).norm());
  EXPECT_LE(worst, 0.01);
  EXPECT_LE(worst, 1e-9) << "in fact to rounding";
}

// The double sphere as Usenko et al. draw it: onto the unit sphere, the centre moved by ξ along
// the axis, onto the second unit sphere, then a pinhole α/(1 − α) behind that sphere's centre
// whose focal length is scaled by 1/(1 − α).
Vec2 doubleSphereByGeometry(const DoubleSphere& m, const Vec3& p) {
  const Vec3 first = p.normalized();
  const Vec3 second = (first + Vec3(0.0, 0.0, m.xi)).normalized();
  const double behind = m.alpha / (1.0 - m.alpha);
  const double x = second.x() / (second.z() + behind) / (1.0 - m.alpha), y = second.y() / (second.z() + behind) / (1.0 - m.alpha);
  return Vec2(m.fx * x + m.cx, m.fy * y + m.cy);
}

TEST(LensModels, DoubleSphereIsItsGeometricDefinition) {
  double worst = 0.0;
  int count = 0;
  for (const Vec3& d : directionsWithin(1.9, 5000, 5)) {
    const auto ours = lensProject(kDoubleSphere, 3.0 * d);
    if (!ours) continue;
    worst = std::max(worst, (*ours - doubleSphereByGeometry(kDoubleSphere, d)).norm());
    ++count;
  }
  EXPECT_GT(count, 4000);
  EXPECT_LE(worst, 1e-9);
  // With ξ = 0 the double sphere is the extended unified model with β = 1.
  DoubleSphere ds = kDoubleSphere;
  ds.xi = 0.0;
  const ExtendedUnified eucm{ds.fx, ds.fy, ds.cx, ds.cy, ds.alpha, 1.0};
  for (const Vec3& d : directionsWithin(1.5, 500, 6)) EXPECT_LE((*lensProject(ds, d) - *lensProject(eucm, d)).norm(), 1e-9);
}

// EUCM(α, β, f) at (x, y, z) is the unified model (ξ = α/(1 − α), γ = f/(√β (1 − α))) at
// (√β x, √β y, z): camera/central_fit.h's Mei projection, pixel centres moved back by ½.
TEST(LensModels, ExtendedUnifiedIsTheUnifiedModelOfAStretchedPoint) {
  const ExtendedUnified& m = kExtendedUnified;
  MeiIntrinsics mei;
  mei.xi = m.alpha / (1.0 - m.alpha);
  mei.gammaX = m.fx / (std::sqrt(m.beta) * (1.0 - m.alpha));
  mei.gammaY = m.fy / (std::sqrt(m.beta) * (1.0 - m.alpha));
  mei.cx = m.cx, mei.cy = m.cy;
  double worst = 0.0;
  int count = 0;
  for (const Vec3& d : directionsWithin(1.8, 5000, 7)) {
    const auto ours = lensProject(m, 1.7 * d);
    if (!ours) continue;
    const auto theirs = mei.raster(Vec3(std::sqrt(m.beta) * d.x(), std::sqrt(m.beta) * d.y(), d.z()));
    ASSERT_TRUE(theirs.has_value());
    worst = std::max(worst, (*ours - (*theirs - Vec2(0.5, 0.5))).norm());
    ++count;
  }
  EXPECT_GT(count, 4000);
  EXPECT_LE(worst, 1e-9);
}

TEST(LensModels, FThetaLensesAndThePanoramaAtKnownAngles) {
  const double f = 300.0;
  const Vec3 at30(std::sin(kPi / 6), 0.0, std::cos(kPi / 6)), at60down(0.0, std::sin(kPi / 3), std::cos(kPi / 3));
  const FThetaLens equidistant{FThetaLens::Kind::Equidistant, f, {}, 400.0, 300.0, kPi * 0.6};
  EXPECT_NEAR((*lensProject(equidistant, at30) - Vec2(400.0 + f * kPi / 6, 300.0)).norm(), 0.0, 1e-9);
  const FThetaLens equisolid{FThetaLens::Kind::Equisolid, f, {}, 400.0, 300.0, kPi * 0.6};
  EXPECT_NEAR((*lensProject(equisolid, at60down) - Vec2(400.0, 300.0 + f)).norm(), 0.0, 1e-9);  // 2f·sin 30°
  // A polynomial θ(r) = r/f is the equidistant lens; with a cubic term θ(r) is the point's angle.
  FThetaLens polynomial{FThetaLens::Kind::Polynomial, 0.0, {0.0, 1.0 / f, 0.0, 0.0, 0.0}, 400.0, 300.0, kPi * 0.6};
  EXPECT_NEAR((*lensProject(polynomial, at30) - *lensProject(equidistant, at30)).norm(), 0.0, 1e-9);
  polynomial.k = {0.0, 1.0 / f, 0.0, 2e-9, 0.0};
  const Vec2 p = *lensProject(polynomial, at30);
  const double r = (p - Vec2(400.0, 300.0)).norm();
  EXPECT_NEAR(r / f + 2e-9 * r * r * r, kPi / 6, 1e-12);
  EXPECT_FALSE(lensProject(equidistant, Vec3(0.0, 0.0, -1.0)).has_value()) << "beyond its field of view";
  // The panorama: forward at the image centre, +X a quarter of the width to the right, up at
  // the top edge.
  const Equirectangular pano{2048, 1024};
  EXPECT_NEAR((*lensProject(pano, Vec3(0, 0, 1)) - Vec2(1023.5, 511.5)).norm(), 0.0, 1e-9);
  EXPECT_NEAR((*lensProject(pano, Vec3(1, 0, 0)) - Vec2(1535.5, 511.5)).norm(), 0.0, 1e-9);
  EXPECT_NEAR(lensProject(pano, Vec3(0, -1, 1e-300))->y(), -0.5, 1e-9);
}

// A lens of 360° sees straight behind on its θ = π circle (every point of it is that direction),
// never at the centre, which is straight ahead.
TEST(LensModels, StraightBehindALensOf360DegreesIsOnItsOuterCircle) {
  const double f = 10.0, cx = 32.0, cy = 32.0;
  const Vec3 behind(0.0, 0.0, -5.0), ahead(0.0, 0.0, 5.0);
  const KannalaBrandt kb{f, f, cx, cy, {0.0, 0.0, 0.0, 0.0}, kPi};
  const FThetaLens equidistant{FThetaLens::Kind::Equidistant, f, {}, cx, cy, kPi};
  const FThetaLens equisolid{FThetaLens::Kind::Equisolid, f, {}, cx, cy, kPi};
  for (const auto& [name, model] : std::vector<std::pair<const char*, LensModel>>{
           {"kannala_brandt", kb}, {"equidistant", equidistant}, {"equisolid", equisolid}}) {
    EXPECT_NEAR((*lensProject(model, ahead) - Vec2(cx, cy)).norm(), 0.0, 1e-12) << name;
    const Vec2 p = *lensProject(model, behind);
    // Beside the axis the limit is the same circle: a point a hair off straight behind.
    const Vec2 nearBehind = *lensProject(model, Vec3(1e-9, 0.0, -5.0));
    EXPECT_NEAR((p - Vec2(cx, cy)).norm(), (nearBehind - Vec2(cx, cy)).norm(), 1e-6) << name;
    EXPECT_GT((p - Vec2(cx, cy)).norm(), 0.9 * f * 2.0) << name;  // f·π for equidistant, 2f for equisolid
    // And its ray points straight behind.
    const Vec3 ray = *lensDirection(model, p);
    EXPECT_LT(ray.normalized().z(), -1.0 + 1e-9) << name;
  }
}

// Every model's unprojection inverts its projection: image points → rays → image points.
TEST(LensModels, UnprojectionRoundTripsToTheSamePixel) {
  const std::vector<std::pair<const char*, LensModel>> models = {
      {"kannala-brandt", kKannalaBrandt},
      {"double sphere", kDoubleSphere},
      {"eucm", kExtendedUnified},
      {"equidistant", FThetaLens{FThetaLens::Kind::Equidistant, 300.0, {}, 640.0, 512.0, kPi * 0.6}},
      {"equisolid", FThetaLens{FThetaLens::Kind::Equisolid, 300.0, {}, 640.0, 512.0, kPi * 0.6}},
      {"polynomial", FThetaLens{FThetaLens::Kind::Polynomial, 0.0, {0.0, 1.0 / 300.0, 0.0, 2e-9, 0.0}, 640.0, 512.0, kPi * 0.6}},
      {"equirectangular", Equirectangular{1280, 1024}}};
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> x(0.0, 1279.0), y(0.0, 1023.0);
  for (const auto& [name, model] : models) {
    double worst = 0.0;
    int imaged = 0;
    for (int i = 0; i < 20000; ++i) {
      const Vec2 pixel(x(rng), y(rng));
      const std::optional<Vec3> d = lensDirection(model, pixel);
      if (!d) continue;
      ASSERT_NEAR(d->norm(), 1.0, 1e-12) << name;
      const std::optional<Vec2> back = lensProject(model, *d);
      ASSERT_TRUE(back.has_value()) << name << " at " << pixel.transpose();
      worst = std::max(worst, (*back - pixel).norm());
      ++imaged;
    }
    EXPECT_GT(imaged, 5000) << name;
    EXPECT_LE(worst, 1e-9) << name;
  }
}

}  // namespace
}  // namespace omnicam
