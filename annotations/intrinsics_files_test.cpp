#include "intrinsics_files.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/core.hpp>
#include <regex>

#include "central_camera.h"
#include "lens_camera.h"
#include "opencv_omnidir.h"
#include "physical_camera.h"
#include "rig.h"
#include "placement.h"

namespace omnicam {
namespace {

// cv::omnidir::projectPoints with K, xi and D read back from `yaml` reproduces the camera's own
// project (OpenCV's pixel centres are integers: ours minus 0.5) for a robot moved and turned in
// the world, to within `tolerance` px.
void expectOpenCvReproducesProject(const Camera& camera, const std::string& yaml, const RobotPose& pose, double tolerance) {
  cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  const OmnidirIntrinsics k = readOmnidirIntrinsics(fs);
  const Rigid cfw = CameraPlacement(pose).worldFromCamera(camera.rig()).inverse();
  const Rigid viewpointFromWorld = unifiedCameraFromViewpoint().inverse() * cfw;
  std::vector<cv::Vec3d> world;
  std::vector<Vec2> ours;
  for (const Vec3& p : {Vec3(3, 1, 0), Vec3(-1, 2, 0.5), Vec3(1.6, -0.2, 0.0), Vec3(0, -3, 0.6), Vec3(2.5, -0.7, 0.39)}) {
    const auto raster = camera.project(viewpointFromWorld * p);
    ASSERT_TRUE(raster);
    world.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*raster);
  }
  cv::Mat rvec, tvec;
  omnidirExtrinsics(cfw, rvec, tvec);
  std::vector<cv::Vec2d> projected;
  cv::omnidir::projectPoints(world, projected, rvec, tvec, k.K, k.xi, k.D);
  for (size_t i = 0; i < world.size(); ++i) {
    EXPECT_NEAR(projected[i][0] + 0.5, ours[i].x(), tolerance);
    EXPECT_NEAR(projected[i][1] + 0.5, ours[i].y(), tolerance);
  }
}

// cv::omnidir::projectPoints with K, xi and D read back from opencv.yaml reproduces omnicam's
// projection (OpenCV's pixel centres are integers: ours minus 0.5), for a robot turned and
// moved in the world — γ_y < 0 included.
TEST(IntrinsicsFiles, OpenCvReadsTheYamlAndReproducesOurProjection) {
  RigSpec rig;
  rig.mirrorRig().imageSize = 300;
  const CentralCamera camera(rig);
  const std::string yaml = openCvIntrinsicsYaml(camera);
  cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_LT(readOmnidirIntrinsics(fs).K.at<double>(1, 1), 0.0);
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 300);
  expectOpenCvReproducesProject(camera, yaml, {1.5, -0.7, 125.0}, 1e-9);
}

TEST(IntrinsicsFiles, KalibrAndCamodocalCarryTheSameNumbers) {
  RigSpec rig;
  const OmniCamera camera = rig.camera();
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  cv::FileStorage mei(camodocalIntrinsicsYaml("front", CentralCamera(rig)), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(mei.isOpened());
  EXPECT_EQ(static_cast<std::string>(mei["model_type"]), "MEI");
  EXPECT_EQ(static_cast<double>(mei["mirror_parameters"]["xi"]), k.xi);
  EXPECT_EQ(static_cast<double>(mei["projection_parameters"]["gamma2"]), k.gamma_y);
  EXPECT_EQ(static_cast<double>(mei["projection_parameters"]["u0"]), k.cx);

  const std::string kalibr = kalibrIntrinsicsYaml("front", CentralCamera(rig));
  std::smatch m;
  ASSERT_TRUE(std::regex_search(kalibr, m, std::regex(R"(intrinsics: \[([^,]+), ([^,]+), ([^,]+), ([^,]+), ([^\]]+)\])")));
  EXPECT_EQ(std::stod(m[1]), k.xi);  // round-trip text: exactly the same doubles
  EXPECT_EQ(std::stod(m[2]), k.gamma_x);
  EXPECT_EQ(std::stod(m[3]), k.gamma_y);
  EXPECT_EQ(std::stod(m[4]), k.cx);
  EXPECT_EQ(std::stod(m[5]), k.cy);
  EXPECT_NE(kalibr.find("camera_model: omni\n"), std::string::npos);
  EXPECT_NE(kalibr.find("resolution: [360, 360]"), std::string::npos);
}

// The aligned pinhole with a lens is exactly Mei's model with rescaled D: cv::omnidir with the
// file's numbers reproduces the physical camera's own projection.
TEST(IntrinsicsFiles, AnAlignedDistortedRigsFileIsExact) {
  RigSpec rig;
  rig.mirrorRig().mount.distortion = {-0.08, 0.015, 0.0009, -0.0012, 0.0};
  rig.mirrorRig().mount.principalPointOffsetPx = {-0.6, 1.1};
  const PhysicalCamera camera(rig);
  const std::string yaml = openCvIntrinsicsYaml(camera);
  cv::FileStorage fs(yaml, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<int>(fs["exact"]), 1);
  expectOpenCvReproducesProject(camera, yaml, {0.4, 1.1, -35.0}, 1e-6);
}

// A non-central rig's files never claim the exact model; OpenCV's carries the fitted frame, with
// which cv::omnidir sees distant points where the camera does, to within the stated residual.
TEST(IntrinsicsFiles, ANonCentralRigsFilesSayApproximate) {
  RigSpec rig;
  rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
  rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
  const PhysicalCamera camera(rig);
  const std::string text = openCvIntrinsicsYaml(camera);
  EXPECT_NE(text.find("APPROXIMATE"), std::string::npos);
  EXPECT_NE(kalibrIntrinsicsYaml("front", camera).find("# APPROXIMATE"), std::string::npos);
  EXPECT_NE(camodocalIntrinsicsYaml("front", camera).find("APPROXIMATE"), std::string::npos);
  cv::FileStorage fs(text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_EQ(static_cast<int>(fs["exact"]), 0);
  const OmnidirIntrinsics k = readOmnidirIntrinsics(fs);
  cv::Mat r, t;
  fs["camera_from_rig_R"] >> r;
  fs["camera_from_rig_t"] >> t;
  ASSERT_EQ(r.rows, 3);
  ASSERT_EQ(t.rows, 3);
  Rigid fittedFromRig = Rigid::Identity();
  for (int row = 0; row < 3; ++row) {
    for (int col = 0; col < 3; ++col) fittedFromRig.linear()(row, col) = r.at<double>(row, col);
    fittedFromRig.translation()[row] = t.at<double>(row);
  }
  const CentralApproximation& fit = camera.centralApproximation();
  const double statedMaxAt5m = fit.residuals.back().maxPx;
  ASSERT_EQ(fit.residuals.back().distanceM, 5.0);
  std::vector<cv::Vec3d> points;
  std::vector<Vec2> ours;
  for (int i = 8; i < rig.mirrorRig().imageSize; i += 16)
    for (int j = 8; j < rig.mirrorRig().imageSize; j += 16) {
      const auto ray = camera.generateRay({Vec2(i + 0.5, j + 0.5)});
      if (!ray) continue;
      const Vec3 rigCamera = unifiedCameraFromViewpoint() * Vec3(ray->origin + 5.0 * ray->direction);
      const Vec3 p = fittedFromRig * rigCamera;
      points.emplace_back(p.x(), p.y(), p.z());
      ours.emplace_back(i + 0.5, j + 0.5);
    }
  ASSERT_GT(points.size(), 300u);
  std::vector<cv::Vec2d> projected;
  cv::omnidir::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k.K, k.xi, k.D);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i)
    worst = std::max(worst, (Vec2(projected[i][0] + 0.5, projected[i][1] + 0.5) - ours[i]).norm());
  // Points 5 m along the ray from its mirror point lie within millimetres of 5 m from the viewpoint.
  EXPECT_LE(worst, 1.5 * statedMaxAt5m + 1e-3);
  EXPECT_GT(worst, 0.0);
}

// A physical rig's intrinsics belong to its best fit's own frame: placed there
// (worldFromModelCamera, what EuRoC's T_BS, Kalibr's T_cn_cnm1 and ROS's tf give), OpenCV's
// projection of world points lands within the fit's stated residuals of the camera's own; placed
// at the rig's camera frame (poses.tum's), as ROS and Kalibr once did, it misses by far more.
TEST(IntrinsicsFiles, APhysicalRigsModelIsPlacedInItsFittedFrame) {
  RigSpec rig;
  rig.mirrorRig().imageSize = 360;
  rig.mirrorRig().mount.offsetMm = {2.0, 0.0, 0.0};
  const PhysicalCamera camera(rig);
  cv::FileStorage fs(openCvIntrinsicsYaml(camera), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  const OmnidirIntrinsics k = readOmnidirIntrinsics(fs);
  const CameraPlacement placement(RobotPose{1.2, -0.4, 35.0});
  const Rigid viewpointFromWorld = placement.worldFromViewpoint(rig).inverse();
  std::vector<cv::Vec3d> world;
  std::vector<Vec2> ours;
  for (int i = 0; i < 48; ++i) {  // points 1–5 m around the robot, on the floor and up to 1 m high
    const double bearing = 2.0 * kPi * i / 48.0, range = 1.0 + (i % 5), height = 0.25 * (i % 5);
    const Vec3 p(1.2 + range * std::cos(bearing), -0.4 + range * std::sin(bearing), height);
    const auto raster = camera.project(viewpointFromWorld * p);
    if (!raster) continue;
    world.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*raster);
  }
  ASSERT_GT(world.size(), 30u);
  const auto rmsPx = [&](const Rigid& worldFromModel) {
    cv::Mat rvec, tvec;
    omnidirExtrinsics(worldFromModel.inverse(), rvec, tvec);
    std::vector<cv::Vec2d> projected;
    cv::omnidir::projectPoints(world, projected, rvec, tvec, k.K, k.xi, k.D);
    double sum = 0.0;
    for (size_t n = 0; n < world.size(); ++n)
      sum += (Vec2(projected[n][0] + 0.5, projected[n][1] + 0.5) - ours[n]).squaredNorm();
    return std::sqrt(sum / world.size());
  };
  const double fitted = rmsPx(worldFromModelCamera(placement, camera));
  const double rigFrame = rmsPx(placement.worldFromCamera(rig));
  double statedMax = 0.0;  // the fit's stated worst residual at 1 m and beyond
  for (const auto& r : camera.centralApproximation().residuals)
    if (r.distanceM == 0.0 || r.distanceM >= 1.0) statedMax = std::max(statedMax, r.maxPx);
  std::printf("physical rig, 2 mm off axis: OpenCV vs exact projection rms %.3f px in the fitted frame, %.3f px in "
              "the rig's camera frame (fit's stated max %.3f px)\n", fitted, rigFrame, statedMax);
  EXPECT_LE(fitted, statedMax);
  EXPECT_GT(rigFrame, 5.0 * fitted);  // measured 4.38 px against 0.62
}

// Kalibr's reader wants floats ("146.0", not "146") and the calibration bag's topic.
TEST(IntrinsicsFiles, TheMirrorsKalibrFileWritesFloatsAndTheBagsTopic) {
  RigSpec rig;
  rig.mirrorRig().imageSize = 300;  // cx = 149.5, γ integer-free; the principal point below is an integer
  rig.mirrorRig().mount.principalPointOffsetPx = {0.5, -0.5};
  const PhysicalCamera camera(rig);
  const std::string kalibr = kalibrIntrinsicsYaml("front", camera);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(kalibr, m, std::regex(R"(intrinsics: \[([^\]]+)\])")));
  const std::string numbers = m[1];
  for (const std::string& number : {std::string("150.0"), std::string("149.0")})
    EXPECT_NE(numbers.find(number), std::string::npos) << numbers;
  EXPECT_TRUE(std::regex_search(kalibr, std::regex(R"(distortion_coeffs: \[-?0\.0, -?0\.0, -?0\.0, -?0\.0\])"))) << kalibr;
  EXPECT_NE(kalibr.find("rostopic: /front/image_raw\n"), std::string::npos);
}

RigSpec lensRig(const LensModel& model, int width, int height) {
  RigSpec rig;
  rig.kind = LensCameraSpec{model, width, height, {0.0, 10.0, 20.0}};
  return rig;
}

// The points a lens camera sees, 2 m along its rays, in its own (OpenCV) frame, with their pixels.
void seenPoints(const LensCamera& camera, std::vector<cv::Point3d>& points, std::vector<Vec2>& pixels, double minZ) {
  for (double y = 0.5; y < camera.height(); y += 6.0)
    for (double x = 0.5; x < camera.width(); x += 6.0) {
      const auto ray = camera.generateRay({Vec2(x, y)});
      if (!ray) continue;
      const Vec3 p = cameraFromViewpoint(camera.rig()) * Vec3(2.0 * ray->direction);
      if (p.z() <= minZ) continue;
      points.emplace_back(p.x(), p.y(), p.z());
      pixels.emplace_back(x, y);
    }
}

// opencv.yaml of a Kannala–Brandt lens, read back by cv::FileStorage, makes cv::fisheye project
// as the camera does; camodocal's file carries the same numbers under its names.
TEST(IntrinsicsFiles, AKannalaBrandtLensReadsBackIntoCvFisheye) {
  const KannalaBrandt kb{95.0, 96.0, 161.0, 118.0, {0.02, -0.005, 0.001, -0.0002}, radians(100.0)};
  const LensCamera camera(lensRig(kb, 320, 240));
  const std::vector<IntrinsicsFile> files = intrinsicsFiles("side", camera);
  ASSERT_EQ(files.size(), 3u);
  cv::FileStorage fs(files[0].text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  EXPECT_EQ(static_cast<std::string>(fs["camera_model"]), "fisheye");
  cv::Mat k, d;
  fs["K"] >> k;
  fs["D"] >> d;
  ASSERT_EQ(d.total(), 4u);
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  seenPoints(camera, points, ours, 1e-3);  // OpenCV images z > 0 only
  ASSERT_GT(points.size(), 500u);
  std::vector<cv::Point2d> projected;
  cv::fisheye::projectPoints(points, projected, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, d);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i) worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  EXPECT_LE(worst, 1e-8);
  cv::FileStorage camodocal(files[2].text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  EXPECT_EQ(static_cast<std::string>(camodocal["model_type"]), "KANNALA_BRANDT");
  const cv::FileNode p = camodocal["projection_parameters"];
  EXPECT_EQ(static_cast<double>(p["k2"]), kb.k[0]);
  EXPECT_EQ(static_cast<double>(p["k5"]), kb.k[3]);
  EXPECT_EQ(static_cast<double>(p["mu"]), kb.fx);
  EXPECT_EQ(static_cast<double>(p["v0"]), kb.cy);
  EXPECT_NE(files[1].text.find("camera_model: pinhole\n  intrinsics: [95.0, 96.0, 161.0, 118.0]\n  distortion_model: equidistant"),
            std::string::npos)
      << files[1].text;
}

// opencv.yaml of a distorted pinhole makes cv::projectPoints project as the camera does.
TEST(IntrinsicsFiles, ADistortedPinholeReadsBackIntoCvProjectPoints) {
  const PinholeRadTan pinhole{300.0, 302.0, 161.0, 118.0, {-0.2, 0.05, 0.001, -0.002, 0.01}};
  const LensCamera camera(lensRig(pinhole, 320, 240));
  const std::vector<IntrinsicsFile> files = intrinsicsFiles("side", camera);
  ASSERT_EQ(files.size(), 1u) << "Kalibr's and camodocal's radtan have no k3";
  cv::FileStorage fs(files[0].text, cv::FileStorage::READ | cv::FileStorage::MEMORY);
  cv::Mat k, d;
  fs["K"] >> k;
  fs["D"] >> d;
  std::vector<cv::Point3d> points;
  std::vector<Vec2> ours;
  seenPoints(camera, points, ours, 0.0);
  std::vector<cv::Point2d> projected;
  cv::projectPoints(points, cv::Vec3d(0, 0, 0), cv::Vec3d(0, 0, 0), k, d, projected);
  double worst = 0.0;
  for (size_t i = 0; i < points.size(); ++i) worst = std::max(worst, (Vec2(projected[i].x + 0.5, projected[i].y + 0.5) - ours[i]).norm());
  EXPECT_LE(worst, 1e-8);
}

// Models no tool's layout has get no file (their sidecar and rays.exr state them).
TEST(IntrinsicsFiles, APanoramaHasNoThirdPartyFile) {
  EXPECT_TRUE(intrinsicsFiles("pano", LensCamera(lensRig(Equirectangular{128, 64}, 128, 64))).empty());
}

}  // namespace
}  // namespace omnicam
