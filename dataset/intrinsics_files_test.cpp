#include "intrinsics_files.h"

#include <gtest/gtest.h>

#include <opencv2/calib3d.hpp>
#include <opencv2/ccalib/omnidir.hpp>
#include <opencv2/core.hpp>
#include <regex>

#include "opencv_omnidir.h"
#include "rig.h"

namespace omnicam {
namespace {

// cv::omnidir::projectPoints with K, xi and D read back from opencv.yaml reproduces omnicam's
// projection (OpenCV's pixel centres are integers: ours minus 0.5), for a robot turned and
// moved in the world — γ_y < 0 included.
TEST(IntrinsicsFiles, OpenCvReadsTheYamlAndReproducesOurProjection) {
  RigSpec rig;
  rig.imageSize = 300;
  const OmniCamera camera = rig.camera();
  cv::FileStorage fs(openCvIntrinsicsYaml(camera), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(fs.isOpened());
  const OmnidirIntrinsics k = readOmnidirIntrinsics(fs);
  EXPECT_LT(k.K.at<double>(1, 1), 0.0);
  EXPECT_EQ(static_cast<int>(fs["image_width"]), 300);

  const RobotPose pose{1.5, -0.7, 125.0};
  const Rigid cfw = cameraFromWorld(rig, pose);
  std::vector<cv::Vec3d> world;
  std::vector<Vec2> ours;
  for (const Vec3& p : {Vec3(3, 1, 0), Vec3(-1, 2, 0.5), Vec3(1.6, -0.2, 0.0), Vec3(0, -3, 0.6), Vec3(2.5, -0.7, 0.39)}) {
    const auto raster = camera.rasterFromCamera(cfw * p);
    ASSERT_TRUE(raster);
    world.emplace_back(p.x(), p.y(), p.z());
    ours.push_back(*raster);
  }
  cv::Mat rvec, tvec;
  omnidirExtrinsics(cfw, rvec, tvec);
  std::vector<cv::Vec2d> projected;
  cv::omnidir::projectPoints(world, projected, rvec, tvec, k.K, k.xi, k.D);
  for (size_t i = 0; i < world.size(); ++i) {
    EXPECT_NEAR(projected[i][0] + 0.5, ours[i].x(), 1e-9);
    EXPECT_NEAR(projected[i][1] + 0.5, ours[i].y(), 1e-9);
  }
}

TEST(IntrinsicsFiles, KalibrAndCamodocalCarryTheSameNumbers) {
  RigSpec rig;
  const OmniCamera camera = rig.camera();
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  cv::FileStorage mei(camodocalIntrinsicsYaml("front", camera), cv::FileStorage::READ | cv::FileStorage::MEMORY);
  ASSERT_TRUE(mei.isOpened());
  EXPECT_EQ(static_cast<std::string>(mei["model_type"]), "MEI");
  EXPECT_EQ(static_cast<double>(mei["mirror_parameters"]["xi"]), k.xi);
  EXPECT_EQ(static_cast<double>(mei["projection_parameters"]["gamma2"]), k.gamma_y);
  EXPECT_EQ(static_cast<double>(mei["projection_parameters"]["u0"]), k.cx);

  const std::string kalibr = kalibrIntrinsicsYaml("front", camera);
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

}  // namespace
}  // namespace omnicam
