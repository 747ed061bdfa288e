// Proves that the intrinsics and extrinsics we export make OpenCV's cv::omnidir (Mei model)
// reproduce our projection, including the sign flip a mirror image needs (gamma_y < 0).
#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <random>

#include "rig.h"
#include "placement.h"

namespace omnicam {
namespace {

TEST(OpenCvInterop, OmnidirProjectPointsReproducesOurProjection) {
  RigSpec rig;
  const OmniCamera cam = rig.camera();
  const RobotPose pose{0.7, -1.1, 123.0};  // rotated robot
  const Rigid cfw = CameraPlacement(pose).worldFromCamera(rig).inverse();
  const OpenCvIntrinsics k = cam.openCvIntrinsics();

  std::mt19937 rng(3);
  std::uniform_real_distribution<double> xy(-4.0, 4.0), z(0.0, 1.5);
  std::vector<cv::Point3d> world;
  std::vector<Vec2> ours;
  while (world.size() < 500) {
    const Vec3 p(xy(rng), xy(rng), z(rng));
    const auto raster = cam.rasterFromCamera(cfw * p);
    if (!raster) continue;
    world.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*raster);
  }
  cv::Mat rotation(3, 3, CV_64F), rvec, tvec(3, 1, CV_64F);
  for (int i = 0; i < 3; ++i) {
    for (int j = 0; j < 3; ++j) rotation.at<double>(i, j) = cfw.linear()(i, j);
    tvec.at<double>(i) = cfw.translation()(i);
  }
  cv::Rodrigues(rotation, rvec);
  const cv::Matx33d K(k.gamma_x, 0.0, k.cx, 0.0, k.gamma_y, k.cy, 0.0, 0.0, 1.0);
  const cv::Matx14d D(0.0, 0.0, 0.0, 0.0);
  std::vector<cv::Point2d> projected;
  cv::omnidir::projectPoints(world, projected, rvec, tvec, K, k.xi, D);
  ASSERT_EQ(projected.size(), world.size());
  double worst = 0.0;
  for (size_t i = 0; i < world.size(); ++i) {
    // OpenCV puts pixel centres at integers; ours are at +0.5.
    const Vec2 cvRaster(projected[i].x + 0.5, projected[i].y + 0.5);
    worst = std::max(worst, (cvRaster - ours[i]).norm());
  }
  EXPECT_LE(worst, 0.01);
  EXPECT_LT(k.gamma_y, 0.0);
}

}  // namespace
}  // namespace omnicam
