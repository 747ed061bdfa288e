// The physical camera: the ideal pinhole reproduces the closed form; a moved, turned, distorted
// one obeys the reflection law at every ray; world → pixel inverts pixel → ray; lens distortion
// matches OpenCV; and the aligned, distorted hyperboloid is Mei's model with rescaled D.
#include "physical_camera.h"

#include <gtest/gtest.h>

#include <cmath>
#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <random>

#include "central_camera.h"
#include "errors.h"
#include "lens_distortion.h"
#include "make_camera.h"
#include "test_rigs.h"

namespace omnicam {
namespace {

using test::misaligned;
using test::shaped;

RigSpec distorted(RigSpec rig) {
  rig.mirrorRig().mount.distortion = {-0.12, 0.03, 0.0015, -0.001, 0.0};
  rig.mirrorRig().mount.principalPointOffsetPx = {1.25, -0.8};
  return rig;
}

TEST(PhysicalCamera, TheIdealPinholeTracesTheClosedFormsRays) {
  const RigSpec rig;
  const PhysicalCamera traced(rig);
  const CentralCamera closed(rig);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  int checked = 0;
  double worstAngle = 0.0, worstOffset = 0.0;
  for (int i = 0; i < 20000; ++i) {
    const Vec2 p(coord(rng), coord(rng));
    const auto a = closed.generateRay({p});
    const auto b = traced.generateRay({p});
    // Away from the rim both image the point or neither does.
    if (std::abs((p - closed.unified().centre()).norm() - closed.unified().rimRadius()) > 1e-6) {
      ASSERT_EQ(a.has_value(), b.has_value()) << p.transpose();
    }
    if (!a || !b) continue;
    ++checked;
    worstAngle = std::max(worstAngle, a->direction.cross(b->direction).norm());  // sine of the angle
    // The reflected ray's line passes through F' (the origin): the single viewpoint.
    worstOffset = std::max(worstOffset, b->origin.cross(b->direction).norm());
  }
  EXPECT_GT(checked, 10000);
  EXPECT_LE(worstAngle, 1e-11);
  EXPECT_LE(worstOffset, 1e-13);  // metres
  EXPECT_TRUE(makeCamera(rig)->central());
  EXPECT_FALSE(makeCamera(rig, true)->central());
}

// A camera on the mirror's axis (turned about it, moved along it, or with lens distortion only)
// sees the vertex along the axis itself: that ray is the closed form's, straight down from F',
// and the point straight below projects onto the image centre (at an odd size, a pixel centre).
TEST(PhysicalCamera, TheRayAlongTheAxisOfAnOnAxisCameraIsTheClosedForms) {
  RigSpec turned, moved, distortedOnly;
  for (RigSpec* rig : {&turned, &moved, &distortedOnly}) rig->mirrorRig().imageSize = 361;
  turned.mirrorRig().mount.rotationDeg = {0.0, 0.0, 5.0};
  moved.mirrorRig().mount.offsetMm = {0.0, 0.0, 3.0};
  distortedOnly.mirrorRig().mount.distortion = {-0.05, 0.0, 0.0, 0.0, 0.0};
  for (const RigSpec* rig : {&turned, &moved, &distortedOnly}) {
    const PhysicalCamera camera(*rig);
    const auto ray = camera.generateRay({Vec2(180.5, 180.5)});
    ASSERT_TRUE(ray);
    EXPECT_NEAR(ray->direction.x(), 0.0, 1e-12);
    EXPECT_NEAR(ray->direction.y(), 0.0, 1e-12);
    EXPECT_NEAR(ray->direction.z(), -1.0, 1e-12);
    const auto below = camera.project(Vec3(0.0, 0.0, -2.0));
    ASSERT_TRUE(below);
    EXPECT_NEAR((*below - Vec2(180.5, 180.5)).norm(), 0.0, 1e-6);
  }
}

TEST(PhysicalCamera, AMovedTurnedDistortedCameraObeysTheReflectionLaw) {
  const RigSpec rig = distorted(misaligned(3.0, 2.0));
  const PhysicalCamera camera(rig);
  const Pinhole& pinhole = camera.pinhole();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  int checked = 0;
  for (int i = 0; i < 5000; ++i) {
    const Vec2 p(coord(rng), coord(rng));
    const auto ray = camera.generateRay({p});
    if (!ray) continue;
    ++checked;
    const Vec3 m = ray->origin;
    EXPECT_NEAR(camera.mirror().implicit(m), 0.0, 1e-9);
    const Vec3 incoming = (m - pinhole.position).normalized();
    const Vec3 n = camera.mirror().normalAt(m);
    // Angle of incidence equals angle of reflection, in the plane of the normal.
    EXPECT_NEAR(incoming.dot(n), -ray->direction.dot(n), 1e-12);
    EXPECT_LE(std::abs(incoming.cross(n).dot(ray->direction)), 1e-12);
    // The incoming ray is the pinhole's ray through that pixel, lens included.
    const auto back = pinhole.raster(m);
    ASSERT_TRUE(back);
    EXPECT_LE((*back - p).norm(), 1e-8);
  }
  EXPECT_GT(checked, 2000);
}

// pixel → ray → point at depth → pixel, over random pixels and depths 0.1 m … 100 m.
void expectRoundTrips(const RigSpec& rig, int count, double bound) {
  const auto camera = makeCamera(rig);
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize), logDepth(std::log(0.1), std::log(100.0));
  double worst = 0.0;
  int done = 0, lost = 0;
  while (done < count) {
    const Vec2 p(coord(rng), coord(rng));
    const auto ray = camera->generateRay({p});
    if (!ray) continue;
    ++done;
    const Vec3 point = ray->origin + std::exp(logDepth(rng)) * ray->direction;
    const auto back = camera->project(point);
    if (!back) {
      ++lost;
      continue;
    }
    worst = std::max(worst, (*back - p).norm());
  }
  std::printf("%s: %d round trips, worst %.3g px, %d not projected\n", camera->model(), count, worst, lost);
  EXPECT_EQ(lost, 0);
  EXPECT_LE(worst, bound);
}

TEST(PhysicalCamera, RoundTripsOfTheIdealRigTraced) {
  const RigSpec rig;
  const PhysicalCamera camera(rig);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  double worst = 0.0;
  for (int done = 0; done < 20000;) {
    const Vec2 p(coord(rng), coord(rng));
    const auto ray = camera.generateRay({p});
    if (!ray) continue;
    ++done;
    const auto back = camera.project(ray->origin + (0.1 + done * 1e-3) * ray->direction);
    ASSERT_TRUE(back);
    worst = std::max(worst, (*back - p).norm());
  }
  EXPECT_LE(worst, 1e-6);
}

TEST(PhysicalCamera, RoundTripsOfAMisalignedHyperboloid) { expectRoundTrips(misaligned(3.0, 2.0), 100000, 1e-6); }

TEST(PhysicalCamera, RoundTripsOfAMisalignedDistortedHyperboloid) {
  expectRoundTrips(distorted(misaligned(2.0, 1.0)), 100000, 1e-6);
}

TEST(PhysicalCamera, RoundTripsOfAnOrthographicParaboloid) { expectRoundTrips(shaped(MirrorShape::Paraboloid, 0.0), 100000, 1e-6); }
TEST(PhysicalCamera, RoundTripsOfAPerspectiveParaboloid) { expectRoundTrips(shaped(MirrorShape::Paraboloid, 0.15), 100000, 1e-6); }
TEST(PhysicalCamera, RoundTripsOfASphere) { expectRoundTrips(shaped(MirrorShape::Sphere, 0.12), 100000, 1e-6); }
TEST(PhysicalCamera, RoundTripsOfACone) { expectRoundTrips(shaped(MirrorShape::Cone, 0.05), 100000, 1e-6); }

// A pinhole on the cone's axis: project is the closed form alone (mirror_surface.h).
TEST(PhysicalCamera, RoundTripsOfAConeFromItsAxis) {
  RigSpec rig = shaped(MirrorShape::Cone, 0.05);
  rig.mirrorRig().mount.offsetMm = {0.0, 0.0, -4.0};
  expectRoundTrips(rig, 100000, 1e-6);
}

// Every shape's rays obey the reflection law at their own mirror point, from the camera as built.
TEST(PhysicalCamera, EveryShapeReflectsFromItsSurface) {
  for (const RigSpec& rig : {shaped(MirrorShape::Paraboloid, 0.0), shaped(MirrorShape::Paraboloid, 0.15),
                             shaped(MirrorShape::Sphere, 0.12), shaped(MirrorShape::Cone, 0.05)}) {
    const PhysicalCamera camera(rig);
    std::mt19937 rng(13);
    std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
    int checked = 0;
    for (int i = 0; i < 3000; ++i) {
      const Vec2 p(coord(rng), coord(rng));
      const auto ray = camera.generateRay({p});
      if (!ray) continue;
      ++checked;
      const Vec3 m = ray->origin;
      ASSERT_NEAR(camera.mirror().implicit(m), 0.0, 1e-9) << mirrorShapeName(rig.mirrorRig().shape);
      const Vec3 incoming = camera.pinhole().rayTo(m).direction;
      const Vec3 n = camera.mirror().normalAt(m);
      EXPECT_NEAR(incoming.dot(n), -ray->direction.dot(n), 1e-12);
      EXPECT_LE(std::abs(incoming.cross(n).dot(ray->direction)), 1e-12);
      EXPECT_LE(m.z(), camera.mirror().rimZ() + 1e-15);
    }
    // The rim touches the image border: the mirror fills most of the inscribed disc.
    EXPECT_GT(checked, 3000 * 0.6) << mirrorShapeName(rig.mirrorRig().shape);
  }
}

// Near the widest rim the scene format allows, the mirror point is ~5 c from the axis: Newton's
// stopping test must still be reachable in floating point there.
TEST(PhysicalCamera, RoundTripsNearAWideRim) {
  RigSpec rig = misaligned(2.0, 1.0);
  rig.mirrorRig().hyperboloid().k = 6.0;
  rig.mirrorRig().hyperboloid().rimElevationDeg = 51.0;  // 4.2 c from F'; at 52° this mirror has no rim
  rig.mirrorRig().hyperboloid().framingElevationDeg = 51.0;
  const double rimDistance = rig.mirrorRig().idealCamera().rimPoint().norm();
  std::printf("rim %.2f c from F'\n", rimDistance / rig.mirrorRig().hyperboloid().c);
  EXPECT_GT(rimDistance, 3.0 * rig.mirrorRig().hyperboloid().c);
  expectRoundTrips(rig, 20000, 1e-6);
}

// --size renders the same camera with other pixels: the principal point's offset scales too.
TEST(PhysicalCamera, ResizingKeepsTheCamerasGeometry) {
  const RigSpec rig = distorted(misaligned(2.0, 1.0));
  const PhysicalCamera small(rig), large(rig.resized(2 * rig.mirrorRig().imageSize));
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  int checked = 0;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p(coord(rng), coord(rng));
    const auto a = small.generateRay({p}), b = large.generateRay({2.0 * p});
    ASSERT_EQ(a.has_value(), b.has_value());
    if (!a) continue;
    ++checked;
    EXPECT_LE((a->origin - b->origin).norm(), 1e-13);
    EXPECT_LE((a->direction - b->direction).norm(), 1e-12);
  }
  EXPECT_GT(checked, 1000);
}

// A lens that folds inside the image: points beyond the fold are not projected onto pixels whose
// ray is another one.
TEST(PhysicalCamera, ProjectRespectsTheLensFold) {
  RigSpec rig;
  rig.mirrorRig().mount.distortion = {-4.0, 0.0, 0.0, 0.0, 0.0};  // folds at r = 1/sqrt(12) ≈ 0.29, inside the corners
  const PhysicalCamera camera(rig);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize), logDepth(std::log(0.1), std::log(100.0));
  int projected = 0;
  for (int i = 0; i < 20000; ++i) {
    // Random scene points around the rig, seen or not.
    const Vec3 p = std::exp(logDepth(rng)) * Vec3(coord(rng) - 180.0, coord(rng) - 180.0, coord(rng) - 250.0).normalized();
    const auto raster = camera.project(p);
    if (!raster) continue;
    ++projected;
    ASSERT_TRUE(camera.images(*raster)) << raster->transpose();
  }
  EXPECT_GT(projected, 1000);
}

TEST(PhysicalCamera, PointsItCannotSeeAreNotProjected) {
  const PhysicalCamera camera(misaligned(2.0, 1.0));
  EXPECT_FALSE(camera.project(Vec3(0.0, 0.0, 5.0)));    // straight above the mirror
  EXPECT_FALSE(camera.project(Vec3(3.0, 0.0, 3.5)));    // above the rim
  EXPECT_TRUE(camera.project(Vec3(3.0, 0.5, -0.4)));    // on the floor ahead
}

TEST(PhysicalCamera, ACameraThatMissesTheMirrorIsRefused) {
  RigSpec rig;
  rig.mirrorRig().mount.offsetMm = {100.0, 0.0, 0.0};
  EXPECT_THROW(PhysicalCamera{rig}, InputError);
  rig.mirrorRig().mount.offsetMm = {0.0, 0.0, 0.0};
  rig.mirrorRig().mount.rotationDeg = {30.0, 0.0, 0.0};
  EXPECT_THROW(PhysicalCamera{rig}, InputError);
}

TEST(PhysicalCamera, APinholeInsideTheMirrorIsRefused) {
  RigSpec rig;
  rig.mirrorRig().mount.offsetMm = {0.0, 0.0, 40.0};
  EXPECT_THROW(PhysicalCamera{rig}, InputError);
}

TEST(LensDistortion, MatchesOpenCvAndInvertsExactly) {
  const LensDistortion lens{-0.21, 0.07, 0.0012, -0.0008, -0.011};
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> coord(-0.45, 0.45);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> normalised;
  for (int i = 0; i < 2000; ++i) {
    const Vec2 p(coord(rng), coord(rng));
    normalised.push_back(p);
    points.emplace_back(p.x(), p.y(), 1.0);
  }
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), cv::Matx33d::eye(), cv::Matx<double, 1, 5>(lens.k1, lens.k2, lens.p1, lens.p2, lens.k3), projected);
  double worstOpenCv = 0.0, worstInverse = 0.0;
  for (size_t i = 0; i < points.size(); ++i) {
    const Vec2 d = distort(lens, normalised[i]);
    worstOpenCv = std::max(worstOpenCv, (d - Vec2(projected[i].x, projected[i].y)).norm());
    const auto back = undistort(lens, d);
    ASSERT_TRUE(back);
    worstInverse = std::max(worstInverse, (*back - normalised[i]).norm());
  }
  EXPECT_LE(worstOpenCv, 1e-14);
  EXPECT_LE(worstInverse, 1e-15);
  // Beyond the fold of a strongly barrel lens (x(1 + k1 x²) peaks at x = 1/√(−3 k1)) nothing is imaged.
  const LensDistortion barrel{-0.5, 0.0, 0.0, 0.0, 0.0};
  EXPECT_FALSE(undistort(barrel, Vec2(0.6, 0.0)));
  EXPECT_TRUE(undistort(barrel, Vec2(0.4, 0.0)));
}

// For the aligned hyperboloid the pinhole's image is the unified model's scaled by s = γ/f, with
// the sign of v flipped (γ_y = −γ): lens distortion on the pinhole's coordinates is Mei's
// distortion with k1·s², k2·s⁴, p1·(−s), p2·s (cv::omnidir has no k3).
TEST(PhysicalCamera, AlignedDistortionIsMeiWithRescaledCoefficients) {
  RigSpec rig;
  rig.mirrorRig().mount.distortion = {-0.09, 0.02, 0.0011, -0.0007, 0.0};
  rig.mirrorRig().mount.principalPointOffsetPx = {0.9, -1.3};
  const auto camera = makeCamera(rig);
  const nlohmann::json intrinsics = camera->describe();
  ASSERT_TRUE(intrinsics.contains("mei_equivalent")) << intrinsics.dump();
  const nlohmann::json& mei = intrinsics["mei_equivalent"];
  const cv::Matx33d K(mei["gamma_x"], 0.0, mei["cx"], 0.0, mei["gamma_y"], mei["cy"], 0.0, 0.0, 1.0);
  const cv::Matx14d D(mei["distortion"][0], mei["distortion"][1], mei["distortion"][2], mei["distortion"][3]);
  const double xi = mei["xi"];
  std::mt19937 rng(29);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  std::vector<cv::Point3d> points;  // OpenCV's camera frame: x forward, y = −robot y, z down
  std::vector<Vec2> ours;
  while (points.size() < 2000) {
    const auto ray = camera->generateRay({Vec2(coord(rng), coord(rng))});
    if (!ray) continue;
    const Vec3 p = ray->origin + 2.0 * ray->direction;
    const auto raster = camera->project(p);
    ASSERT_TRUE(raster);
    ours.push_back(*raster);
    const Vec3 q = unifiedCameraFromViewpoint() * p;
    points.emplace_back(q.x(), q.y(), q.z());
  }
  std::vector<cv::Point2d> projected;
  cv::omnidir::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, xi, D);
  double worst = 0.0;
  for (size_t i = 0; i < ours.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  std::printf("cv::omnidir with rescaled D vs omnicam: worst %.3g px\n", worst);
  EXPECT_LE(worst, 1e-9);  // the issue asks for 0.01 px; the relation is exact
}

// The orthographic paraboloid is the unified model with ξ = 1, γ = h·f (moved sideways: its
// centre moves by −f·offset): cv::omnidir with those numbers reproduces the traced camera's
// project, and the best-fit central model finds the same numbers with no residual.
TEST(PhysicalCamera, TheOrthographicParaboloidIsMeiWithXiOne) {
  RigSpec rig = shaped(MirrorShape::Paraboloid, 0.0);
  rig.mirrorRig().mount.rotationDeg = {0.0, 0.0, 0.0};
  const PhysicalCamera camera(rig);
  const auto mei = camera.meiEquivalent();
  ASSERT_TRUE(mei);
  EXPECT_FALSE(camera.describe()["non_central"].get<bool>());
  const cv::Matx33d K(mei->gammaX, 0.0, mei->cx, 0.0, mei->gammaY, mei->cy, 0.0, 0.0, 1.0);
  std::mt19937 rng(31);
  std::uniform_real_distribution<double> coord(0.0, rig.mirrorRig().imageSize);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  while (points.size() < 2000) {
    const auto ray = camera.generateRay({Vec2(coord(rng), coord(rng))});
    if (!ray) continue;
    const Vec3 p = ray->origin + 3.0 * ray->direction;
    const auto raster = camera.project(p);
    ASSERT_TRUE(raster);
    ours.push_back(*raster);
    const Vec3 q = unifiedCameraFromViewpoint() * p;  // the unified model's frame at the focus
    points.emplace_back(q.x(), q.y(), q.z());
  }
  std::vector<cv::Point2d> projected;
  cv::omnidir::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), K, mei->xi, cv::Matx14d(0, 0, 0, 0));
  double worst = 0.0;
  for (size_t i = 0; i < ours.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  std::printf("orthographic paraboloid: cv::omnidir (xi = 1) vs omnicam: worst %.3g px\n", worst);
  EXPECT_LE(worst, 1e-9);
  const CentralApproximation& fit = camera.centralApproximation();
  // ξ, γ and k1 nearly trade off against each other across the image (the fit lands within
  // 3·10⁻⁵ of ξ = 1 with no residual): the residual is what is determined.
  EXPECT_NEAR(fit.intrinsics.xi, 1.0, 1e-3);
  EXPECT_NEAR(fit.intrinsics.gammaX, mei->gammaX, 1e-3 * mei->gammaX);
  EXPECT_NEAR(fit.intrinsics.cx, mei->cx, 1e-6);
  for (const auto& r : fit.residuals) EXPECT_LE(r.maxPx, 1e-6);
}

TEST(Camera, EqualityIsTheRigsAndTheModels) {
  RigSpec a, b;
  EXPECT_TRUE(*makeCamera(a) == *makeCamera(b));
  EXPECT_FALSE(*makeCamera(a) == *makeCamera(a, true));
  b.mirrorRig().mount.distortion.k3 = 1e-9;
  EXPECT_FALSE(a == b);
  EXPECT_FALSE(*makeCamera(a, true) == *makeCamera(b));
  EXPECT_THROW((void)b.camera(), InputError);  // no central model for it
}

}  // namespace
}  // namespace omnicam
