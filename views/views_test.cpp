#include "views.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "central_camera.h"
#include "errors.h"
#include "physical_camera.h"
#include "placement.h"
#include "rig.h"

namespace omnicam {
namespace {

const OmniCamera& camera() {
  static const OmniCamera cam = RigSpec{}.camera();
  return cam;
}

TEST(Views, BirdsEyeThesisVariantFollowsEquations33To35) {
  ViewSpec spec;
  spec.variant = ViewVariant::Thesis;
  const ViewMap map = buildViewMap(spec, camera());
  ASSERT_EQ(map.width, 400);
  const double h = 73.7437, zw = 40.0;  // docs/conventions.md §1's h for the defaults; the thesis' z_w
  for (int j = 3; j < 400; j += 37)
    for (int i = 5; i < 400; i += 41) {
      const double xw = i + 0.5 - 200.0, yw = 200.0 - (j + 0.5);  // map: right = forward, up = left
      const double theta = std::acos(zw / std::sqrt(xw * xw + yw * yw + zw * zw));
      const double phi = std::atan2(yw, xw);
      const double rho = h / (1.0 + std::cos(theta));
      const size_t k = static_cast<size_t>(j) * 400 + i;
      EXPECT_NEAR(map.sourceX[k], 180.0 + rho * std::sin(theta) * std::cos(phi), 2e-3);
      EXPECT_NEAR(map.sourceY[k], 180.0 + rho * std::sin(theta) * std::sin(phi), 2e-3);
    }
}

TEST(Views, ExactBirdsEyeAgreesWithTheCameraProjection) {
  const ViewMap map = buildViewMap(ViewSpec{}, camera());
  for (int j = 0; j < 400; j += 23)
    for (int i = 0; i < 400; i += 19) {
      // The ground point of this map pixel, projected by the camera model (another code path).
      const Vec3 viewpointDir(i + 0.5 - 200.0, 200.0 - (j + 0.5), -40.0);
      const auto raster = camera().rasterFromCamera(unifiedCameraFromViewpoint().linear() * viewpointDir);
      const size_t k = static_cast<size_t>(j) * 400 + i;
      if (!raster) {
        EXPECT_TRUE(std::isnan(map.sourceX[k]));
        continue;
      }
      EXPECT_NEAR(map.sourceX[k], raster->x(), 2e-3);
      EXPECT_NEAR(map.sourceY[k], raster->y(), 2e-3);
    }
}

TEST(Views, PanoramaColumnsAreRadialAndRowsFollowTheVariant) {
  for (ViewVariant variant : {ViewVariant::Thesis, ViewVariant::Exact}) {
    ViewSpec spec;
    spec.kind = ViewKind::Panorama;
    spec.variant = variant;
    const ViewMap map = buildViewMap(spec, camera());
    ASSERT_EQ(map.width, 1080);
    ASSERT_EQ(map.height, 300);
    for (int i = 0; i < 1080; i += 97) {
      const double phi = kPi - 2.0 * kPi * (i + 0.5) / 1080.0;  // independent: Eqs. 3.6–3.7's angle
      for (int j = 0; j < 300; j += 31) {
        const size_t k = static_cast<size_t>(j) * 1080 + i;
        const double dx = map.sourceX[k] - 180.0, dy = map.sourceY[k] - 180.0;
        const double r = std::hypot(dx, dy);
        EXPECT_NEAR(dx, r * std::cos(phi), 2e-3);
        EXPECT_NEAR(dy, r * std::sin(phi), 2e-3);
        const double row = (j + 0.5) / 300.0;
        const double expected = variant == ViewVariant::Thesis ? 180.0 * (1.0 - row)  // r_omn · x_pan/X_pan
                                                               : camera().radiusOfTheta(radians(135.0) * (1.0 - row));
        EXPECT_NEAR(r, expected, 2e-3);
      }
    }
  }
}

TEST(Views, PerspectiveViewIsAPinholeAtTheViewpoint) {
  // A pinhole at F' looking toward (yaw, pitch), square pixels, horizontal field of view fov:
  // pixel (u, v) sees forward + (u − W/2)/f · right − (v − H/2)/f · up, f = (W/2) / tan(fov/2).
  // That direction lands where the unified model, written out here from k, c and the framing
  // (docs/conventions.md §1), puts it. A swapped axis, a sign or a wrong focal length shows.
  const RigSpec rig;
  const double eps = std::sqrt(rig.mirrorRig().hyperboloid().k / (rig.mirrorRig().hyperboloid().k - 2.0)), xi = 2.0 * eps / (1.0 + eps * eps);
  const double framing = radians(90.0 + rig.mirrorRig().hyperboloid().framingElevationDeg), rim = radians(90.0 + rig.mirrorRig().hyperboloid().rimElevationDeg);
  const double gamma = 0.5 * rig.mirrorRig().imageSize * (xi + std::cos(framing)) / std::sin(framing);
  int imaged = 0, beyond = 0;
  for (const auto& [yawDeg, pitchDeg] : {std::pair{60.0, -25.0}, std::pair{-120.0, 20.0}}) {
    ViewSpec spec;
    spec.kind = ViewKind::Perspective;
    spec.yawDeg = yawDeg, spec.pitchDeg = pitchDeg, spec.fovDeg = 80.0;
    const ViewMap map = buildViewMap(spec, camera());
    ASSERT_EQ(map.width, 400);
    ASSERT_EQ(map.height, 300);
    const double yaw = radians(yawDeg), pitch = radians(pitchDeg);
    const Vec3 forward(std::cos(pitch) * std::cos(yaw), std::cos(pitch) * std::sin(yaw), std::sin(pitch));
    const Vec3 right(std::sin(yaw), -std::cos(yaw), 0.0);
    const Vec3 up = right.cross(forward);
    const double f = 200.0 / std::tan(radians(spec.fovDeg) / 2.0);
    for (int j = 0; j < 300; j += 13)
      for (int i = 0; i < 400; i += 17) {
        const Vec3 d = forward + (i + 0.5 - 200.0) / f * right - (j + 0.5 - 150.0) / f * up;  // robot frame
        const double theta = std::acos(-d.z() / d.norm()), phi = std::atan2(d.y(), d.x());
        const size_t k = static_cast<size_t>(j) * 400 + i;
        if (theta > rim) {  // above the rim (45° up): black
          EXPECT_TRUE(std::isnan(map.sourceX[k])) << yawDeg << ": " << i << "," << j;
          ++beyond;
          continue;
        }
        const double r = gamma * std::sin(theta) / (xi + std::cos(theta));
        EXPECT_NEAR(map.sourceX[k], 180.0 + r * std::cos(phi), 2e-3) << yawDeg << ": " << i << "," << j;
        EXPECT_NEAR(map.sourceY[k], 180.0 + r * std::sin(phi), 2e-3) << yawDeg << ": " << i << "," << j;
        ++imaged;
      }
  }
  EXPECT_GT(imaged, 500);
  EXPECT_GT(beyond, 10);  // looking up 20°, the top rows reach 52° above the horizon
}

TEST(Views, ApplyingAMapSamplesBilinearlyAtPixelCentres) {
  // Source image whose red channel is its own u coordinate: a bilinear lookup reproduces it.
  ImageRGBA omni(360, 360);
  for (int j = 0; j < 360; ++j)
    for (int i = 0; i < 360; ++i) {
      float* p = omni.at(i, j);
      p[0] = i + 0.5f, p[1] = j + 0.5f, p[2] = 0.0f, p[3] = 1.0f;
    }
  ViewSpec spec;
  spec.kind = ViewKind::Perspective;
  spec.pitchDeg = -40.0;
  const ViewMap map = buildViewMap(spec, camera());
  const ImageRGBA view = applyViewMap(map, omni);
  int checked = 0;
  for (size_t k = 0; k < map.sourceX.size(); k += 101) {
    if (std::isnan(map.sourceX[k]) || map.sourceX[k] < 1 || map.sourceX[k] > 359 || map.sourceY[k] < 1 || map.sourceY[k] > 359) continue;
    EXPECT_NEAR(view.pixels[k * 4], map.sourceX[k], 1e-3);
    EXPECT_NEAR(view.pixels[k * 4 + 1], map.sourceY[k], 1e-3);
    ++checked;
  }
  EXPECT_GT(checked, 100);
  // A reused output (holding a larger view of ones) is wholly overwritten, black included.
  ViewSpec upward = spec;
  upward.pitchDeg = 40.0;  // partly above the rim: black pixels
  const ViewMap upMap = buildViewMap(upward, camera());
  ImageRGBA reused(1080, 300);
  std::fill(reused.pixels.begin(), reused.pixels.end(), 1.0f);
  applyViewMap(upMap, omni, reused);
  const ImageRGBA fresh = applyViewMap(upMap, omni);
  ASSERT_EQ(reused.pixels.size(), fresh.pixels.size());
  EXPECT_EQ(reused.width, fresh.width);
  EXPECT_EQ(reused.pixels, fresh.pixels);
  EXPECT_NE(std::count(fresh.pixels.begin(), fresh.pixels.end(), 0.0f), 0);
  EXPECT_THROW(parseViewKind("fisheye"), InputError);
  EXPECT_THROW(parseViewVariant("approx"), InputError);
}

// A rig framed inside its mirror disc (the horizon on the image border) images no direction
// between the horizon and the rim: a view's pixels that look there are black, with alpha 0, and
// not the image's edge pixels stretched outward.
TEST(Views, SourcesOffTheImageAreBlackNotTheEdgeStretched) {
  RigSpec rig;
  rig.mirrorRig().hyperboloid().framingElevationDeg = 0.0;
  const OmniCamera cropped = rig.camera();
  ImageRGBA omni(cropped.width(), cropped.height());
  std::fill(omni.pixels.begin(), omni.pixels.end(), 1.0f);  // white and opaque to its border
  ViewSpec spec;
  spec.kind = ViewKind::Panorama;
  spec.width = 360;
  spec.height = 100;
  const ViewMap map = buildViewMap(spec, cropped);
  const ImageRGBA view = applyViewMap(map, omni);
  // Rows are linear in the angle from straight down, from the rim (45° above the horizon) at the
  // top edge to straight down: the horizon, on the image's border beside the centre column,
  // lies a third of the way down ((90° + 45° − 90°) / 135°).
  const double rowOfHorizon = 100.0 * 45.0 / 135.0;
  const int centre = 180;  // looking forward: +u, towards the border's midpoint
  for (int j = 0; j < 100; ++j) {
    const float alpha = view.at(centre, j)[3];
    if (j + 1 < rowOfHorizon) {
      EXPECT_EQ(alpha, 0.0f) << "row " << j << " looks above the horizon, off the image";
      EXPECT_TRUE(std::isnan(map.sourceX[static_cast<size_t>(j) * 360 + centre]));
    } else if (j > rowOfHorizon + 1) {
      EXPECT_EQ(alpha, 1.0f) << "row " << j;
    }
  }
  for (size_t k = 0; k < map.sourceX.size(); ++k)
    if (!std::isnan(map.sourceX[k])) {
      ASSERT_GE(map.sourceX[k], 0.0f);
      ASSERT_LE(map.sourceX[k], static_cast<float>(cropped.width()));
      ASSERT_GE(map.sourceY[k], 0.0f);
      ASSERT_LE(map.sourceY[k], static_cast<float>(cropped.height()));
    }
}

// At the image's last texel centres (and within the half pixel beyond) the lookup is that texel
// alone: it leaked 0.1 % of its neighbour, the top-left tap kept 1.001 texels inside. Between
// centres it is the exact blend, at the first texel too.
TEST(Views, TheOutermostTexelsAreTakenAlone) {
  ImageRGBA omni(5, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 5; ++i) {
      float* p = omni.at(i, j);
      p[0] = static_cast<float>(i), p[1] = static_cast<float>(j), p[2] = static_cast<float>(10 * j + i), p[3] = 1.0f;
    }
  ViewMap map;
  map.width = 6, map.height = 1;
  map.sourceX = {4.5f, 5.0f, 4.0f, 0.5f, 0.0f, 2.25f};
  map.sourceY = {3.5f, 4.0f, 3.5f, 0.5f, 0.0f, 1.75f};
  finishViewMap(map, omni.width, omni.height);
  const ImageRGBA view = applyViewMap(map, omni);
  const float expected[6][3] = {{4, 3, 34}, {4, 3, 34}, {3.5f, 3, 33.5f}, {0, 0, 0}, {0, 0, 0}, {1.75f, 1.25f, 14.25f}};
  for (int k = 0; k < 6; ++k)
    for (int c = 0; c < 3; ++c) EXPECT_NEAR(view.at(k, 0)[c], expected[k][c], 1e-4f) << "pixel " << k << " channel " << c;
}

// The map's source position at a continuous view position (u, v): bilinear between the four
// pixel centres around it (the map is smooth; its curvature over a pixel is far below 0.01 px).
Vec2 sourceAt(const ViewMap& map, double u, double v) {
  const double x = u - 0.5, y = v - 0.5;
  const int i = static_cast<int>(std::floor(x)), j = static_cast<int>(std::floor(y));
  const double fx = x - i, fy = y - j;
  auto at = [&](int a, int b) {
    const size_t k = static_cast<size_t>(b) * map.width + static_cast<size_t>(a);
    return Vec2(map.sourceX[k], map.sourceY[k]);
  };
  return (1 - fy) * ((1 - fx) * at(i, j) + fx * at(i + 1, j)) + fy * ((1 - fx) * at(i, j + 1) + fx * at(i + 1, j + 1));
}

// The geometry a view's sidecar states, checked through the omni camera: a point the stated
// pinhole (or floor scale) puts at a view position is the point the view map samples there, for
// a level rig and a tilted one (the view's directions are the robot's, from F' where the tilt
// puts it: rig.h's tilt, robotFromViewpoint = Rx(roll)·Ry(pitch)·T(0, 0, height), rebuilt here
// and checked against placement.h's). Views built as if the tilted rig were level miss by
// centimetres of floor.
TEST(Views, TheSidecarsGeometryIsTheViews) {
  const double height = RigSpec{}.height;
  const CentralCamera central{RigSpec{}};
  for (const Vec2& tiltDeg : {Vec2(0.0, 0.0), Vec2(4.0, -7.0)}) {
    Rigid robotFromViewpoint = Rigid::Identity();
    robotFromViewpoint.rotate(Eigen::AngleAxisd(radians(tiltDeg.x()), Vec3::UnitX()));
    robotFromViewpoint.rotate(Eigen::AngleAxisd(radians(tiltDeg.y()), Vec3::UnitY()));
    robotFromViewpoint.translate(Vec3(0, 0, height));
    RigSpec tilted;
    tilted.tiltDeg = {tiltDeg.x(), tiltDeg.y()};
    ASSERT_TRUE(omnicam::robotFromViewpoint(tilted).matrix().isApprox(robotFromViewpoint.matrix(), 1e-12));
    auto omniRaster = [&](const Vec3& robotPoint) {  // where the omni camera images a robot-frame point
      return camera().rasterFromCamera(unifiedCameraFromViewpoint().linear() * (robotFromViewpoint.inverse() * robotPoint));
    };
    ViewSpec perspective;
    perspective.kind = ViewKind::Perspective;
    perspective.yawDeg = 30.0, perspective.pitchDeg = -35.0, perspective.fovDeg = 80.0;
    perspective.width = 320, perspective.height = 200;
    const ViewMap pmap = buildViewMap(perspective, central, robotFromViewpoint);
    const nlohmann::json p = viewToJson(perspective, pmap, central, robotFromViewpoint);
    const nlohmann::json& k = p.at("intrinsics");
    EXPECT_EQ(k.at("model"), "pinhole");
    Eigen::Matrix4d cameraFromRobot;
    for (int r = 0; r < 4; ++r)
      for (int c = 0; c < 4; ++c) cameraFromRobot(r, c) = p.at("camera_from_robot").at(r).at(c).get<double>();
    for (const Vec3& robotPoint : {Vec3(1.0, 0.6, 0.0), Vec3(0.8, 0.3, 0.1), Vec3(1.2, 1.0, 0.05), Vec3(0.7, 0.5, 0.0)}) {
      const Eigen::Vector4d c = cameraFromRobot * robotPoint.homogeneous();
      ASSERT_GT(c.z(), 0.0);
      // OpenCV's pixel (integer centres) + 0.5: omnicam's continuous raster.
      const double u = k.at("fx").get<double>() * c.x() / c.z() + k.at("cx").get<double>() + 0.5;
      const double v = k.at("fy").get<double>() * c.y() / c.z() + k.at("cy").get<double>() + 0.5;
      ASSERT_TRUE(u > 1 && v > 1 && u < perspective.width - 1 && v < perspective.height - 1) << u << " " << v;
      const auto expected = omniRaster(robotPoint);
      ASSERT_TRUE(expected);
      EXPECT_LT((sourceAt(pmap, u, v) - *expected).norm(), 0.01) << robotPoint.transpose() << " tilt " << tiltDeg.transpose();
    }
    // Bird's-eye: a floor point (x, y) lies (x, y) − F' / ground_metres_per_pixel from the centre
    // (F' above it), forward to the right and left upward.
    ViewSpec birdsEye;
    const ViewMap bmap = buildViewMap(birdsEye, central, robotFromViewpoint);
    const nlohmann::json b = viewToJson(birdsEye, bmap, central, robotFromViewpoint);
    const Vec3 viewpoint = robotFromViewpoint.translation();
    const double mpp = b.at("ground_metres_per_pixel").get<double>();
    EXPECT_DOUBLE_EQ(mpp, viewpoint.z() / birdsEye.groundDistance);
    EXPECT_EQ(b.at("viewpoint_m"), nlohmann::json({viewpoint.x(), viewpoint.y(), viewpoint.z()}));
    for (const Vec2& floor : {Vec2(1.0, 0.0), Vec2(0.5, -0.7), Vec2(-1.2, 0.4)}) {
      const double u = 0.5 * bmap.width + (floor.x() - viewpoint.x()) / mpp, v = 0.5 * bmap.height - (floor.y() - viewpoint.y()) / mpp;
      const auto expected = omniRaster(Vec3(floor.x(), floor.y(), 0.0));
      ASSERT_TRUE(expected);
      EXPECT_LT((sourceAt(bmap, u, v) - *expected).norm(), 0.01) << floor.transpose() << " tilt " << tiltDeg.transpose();
    }
    // Panorama: the robot's azimuth φ along the width (forward in the middle, turning right to the
    // right), its incidence θ from straight down linear in the rows from the rim's θ to 0.
    ViewSpec panorama;
    panorama.kind = ViewKind::Panorama;
    const ViewMap qmap = buildViewMap(panorama, central, robotFromViewpoint);
    EXPECT_DOUBLE_EQ(viewToJson(panorama, qmap, central, robotFromViewpoint).at("top_incidence_deg").get<double>(),
                     degrees(camera().rimTheta()));
    for (const Vec2& phiTheta : {Vec2(0.3, 1.2), Vec2(-2.0, 0.8), Vec2(2.5, 1.6)}) {
      const double phi = phiTheta.x(), theta = phiTheta.y();
      const double u = (kPi - phi) / (2.0 * kPi) * qmap.width, v = (1.0 - theta / camera().rimTheta()) * qmap.height;
      const Vec3 direction(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
      const auto expected = omniRaster(viewpoint + 5.0 * direction);
      ASSERT_TRUE(expected);
      EXPECT_LT((sourceAt(qmap, u, v) - *expected).norm(), 0.02) << phiTheta.transpose() << " tilt " << tiltDeg.transpose();
    }
    if (tiltDeg != Vec2::Zero()) {
      // The thesis' equations are a level rig's.
      ViewSpec thesis = birdsEye;
      thesis.variant = ViewVariant::Thesis;
      EXPECT_THROW(buildViewMap(thesis, central, robotFromViewpoint), InputError);
      continue;
    }
    ViewSpec thesis = birdsEye;
    thesis.variant = ViewVariant::Thesis;
    EXPECT_FALSE(viewToJson(thesis, buildViewMap(thesis, camera()), central, robotFromViewpoint).contains("ground_metres_per_pixel"));
  }
}

// A view's sidecar keeps what the view shows (rig, pose, scene) and moves what describes only
// the omni image (its intrinsics and frame) under "source".
TEST(Views, AViewsSidecarMovesTheOmniImagesModelUnderSource) {
  const nlohmann::json omni = {{"rig", {{"height", 0.4}}}, {"pose", {{"x", 1.0}}}, {"intrinsics", {{"model", "mei_unified"}}},
                               {"camera_from_world", {{1, 0, 0, 0}}}};
  const nlohmann::json view = viewSidecar(omni, {{"kind", "panorama"}}, "a.png");
  EXPECT_EQ(view.at("rig"), omni.at("rig"));
  EXPECT_EQ(view.at("pose"), omni.at("pose"));
  EXPECT_FALSE(view.contains("intrinsics"));
  EXPECT_FALSE(view.contains("camera_from_world"));
  EXPECT_EQ(view.at("source").at("intrinsics"), omni.at("intrinsics"));
  EXPECT_EQ(view.at("source").at("camera_from_world"), omni.at("camera_from_world"));
  EXPECT_EQ(view.at("view").at("kind"), "panorama");
  EXPECT_EQ(view.at("source_image"), "a.png");
}

// Through the camera interface the ideal rig's views are the closed form's, bit for bit.
TEST(Views, TheCentralCameraGivesTheClosedFormsViews) {
  for (ViewKind kind : {ViewKind::BirdsEye, ViewKind::Panorama, ViewKind::Perspective}) {
    ViewSpec spec;
    spec.kind = kind;
    const ViewMap a = buildViewMap(spec, camera()), b = buildViewMap(spec, CentralCamera(RigSpec{}), robotFromViewpoint(RigSpec{}));
    for (size_t k = 0; k < a.sourceX.size(); ++k) {
      ASSERT_TRUE((std::isnan(a.sourceX[k]) && std::isnan(b.sourceX[k])) || a.sourceX[k] == b.sourceX[k]);
      ASSERT_TRUE((std::isnan(a.sourceY[k]) && std::isnan(b.sourceY[k])) || a.sourceY[k] == b.sourceY[k]);
    }
  }
}

// A physical rig's views: every view pixel's source is the pixel whose true ray looks along the
// view's direction (to within the parallax of a point 1 km away: the ray leaves its mirror point,
// centimetres from the viewpoint).
TEST(Views, APhysicalRigsViewsLookAlongTheirDirections) {
  for (const Vec2& tiltDeg : {Vec2(0.0, 0.0), Vec2(4.0, -3.0)}) {
    RigSpec rig;
    rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
    rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
    rig.tiltDeg = {tiltDeg.x(), tiltDeg.y()};
    // The view directions are the robot's; the rays the viewpoint frame's, which the tilt turns:
    // Rx(roll)·Ry(pitch), rebuilt here.
    const Eigen::Matrix3d viewpointFromRobot =
        (Eigen::AngleAxisd(radians(tiltDeg.x()), Vec3::UnitX()) * Eigen::AngleAxisd(radians(tiltDeg.y()), Vec3::UnitY()))
            .toRotationMatrix()
            .transpose();
    const PhysicalCamera physical(rig);
    ViewSpec thesis;
    thesis.variant = ViewVariant::Thesis;
    EXPECT_THROW(buildViewMap(thesis, physical, robotFromViewpoint(rig)), InputError);
    // The widest angle from its own straight down the camera sees, over the same 128 × 128 grid
    // views.h scans: the panorama's top row, tilted or not.
    double widest = 0.0;
    for (int b = 0; b < 128; ++b)
      for (int a = 0; a < 128; ++a)
        if (const auto r = physical.generateRay({Vec2((a + 0.5) * rig.mirrorRig().imageSize / 128.0, (b + 0.5) * rig.mirrorRig().imageSize / 128.0)}))
          widest = std::max(widest, std::acos(std::clamp(-r->direction.z(), -1.0, 1.0)));
    for (ViewKind kind : {ViewKind::BirdsEye, ViewKind::Panorama, ViewKind::Perspective}) {
      ViewSpec spec;
      spec.kind = kind;
      spec.width = 120;
      spec.height = 90;
      const ViewMap map = buildViewMap(spec, physical, robotFromViewpoint(rig));
      if (kind == ViewKind::Panorama) {
        EXPECT_DOUBLE_EQ(map.topIncidence, widest);
        EXPECT_DOUBLE_EQ(viewToJson(spec, map, physical, robotFromViewpoint(rig)).at("top_incidence_deg").get<double>(), degrees(widest));
      }
      int sourced = 0;
      double worst = 0.0;
      for (int j = 0; j < map.height; ++j)
        for (int i = 0; i < map.width; ++i) {
          const size_t k = static_cast<size_t>(j) * map.width + i;
          if (std::isnan(map.sourceX[k])) continue;
          ++sourced;
          const auto ray = physical.generateRay({Vec2(map.sourceX[k], map.sourceY[k])});
          ASSERT_TRUE(ray);
          // The view's direction, rebuilt here from the definitions in views.h.
          const double u = i + 0.5, v = j + 0.5;
          Vec3 d = Vec3::Zero();
          if (kind == ViewKind::BirdsEye) {
            d = Vec3(u - 0.5 * map.width, 0.5 * map.height - v, -spec.groundDistance);
          } else if (kind == ViewKind::Perspective) {
            const double t = std::tan(radians(spec.fovDeg) / 2.0);
            const Vec3 view(1.0, -(2.0 * u / map.width - 1.0) * t, -(2.0 * v / map.height - 1.0) * t * map.height / map.width);
            d = Eigen::AngleAxisd(radians(spec.pitchDeg), -Vec3::UnitY()) * view;  // yaw 0
          } else {
            // Rows linear in the angle from straight down, from the widest the camera sees (top)
            // to straight down (bottom); columns: azimuth π at the left edge.
            const double phi = kPi - 2.0 * kPi * u / map.width, theta = widest * (1.0 - v / map.height);
            d = Vec3(std::sin(theta) * std::cos(phi), std::sin(theta) * std::sin(phi), -std::cos(theta));
          }
          d = viewpointFromRobot * d;
          EXPECT_GT(ray->direction.dot(d), 0.0);
          worst = std::max(worst, ray->direction.cross(d.normalized()).norm());
        }
      EXPECT_GT(sourced, map.width * map.height / 4) << viewKindName(kind);
      EXPECT_LE(worst, 1e-4) << viewKindName(kind) << " tilt " << tiltDeg.transpose();
    }
  }
}

}  // namespace
}  // namespace omnicam
