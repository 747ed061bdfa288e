// End to end: `omnicam experiment texture-realism --quick` (fast and Blender renders, classifiers,
// detection, EKF, matplotlib figures, report) and `omnicam arena hall` from a real 360° photo and
// from an omni image unwrapped with `omnicam view --as panorama`.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <sstream>

#include "image.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;
using nlohmann::json;

testing::CommandResult omnicam(const std::string& args) {
  return testing::runShell(std::string(OMNICAM_BINARY) + " " + args + " 2>&1");
}

class ExperimentCliTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_experiment_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  std::string path(const std::string& name) const { return (dir_ / name).string(); }
  fs::path dir_;
};

TEST_F(ExperimentCliTest, QuickTextureRealismWritesResultsFiguresAndReport) {
  const auto r = omnicam("experiment texture-realism --quick -o " + path("run") + " --doc " + path("doc.md"));
  ASSERT_EQ(r.code, 0) << r.out;
  std::ifstream in(path("run/results.json"));
  const json results = json::parse(in);
  for (const char* condition : {"plain_to_plain", "plain_to_textured", "plain_to_realistic", "random_textures_to_realistic"}) {
    ASSERT_TRUE(results["conditions"].contains(condition)) << condition;
    const json& c = results["conditions"][condition];
    EXPECT_EQ(c["frames"], 4) << condition;
    for (const char* key : {"true_positives", "false_positives", "mean_localisation_error_px"})
      EXPECT_TRUE(c[key].is_number()) << condition << " " << key;
    ASSERT_TRUE(results["ekf"].contains(condition)) << condition;
    const json& e = results["ekf"][condition];
    EXPECT_NEAR(e["mean_improvement_cm"].get<double>(),
                e["mean_error_odometry_cm"].get<double>() - e["mean_error_ekf_cm"].get<double>(), 1e-9);
  }
  // On the plain hall the classifiers find beacons, to within a pixel, and the EKF uses them.
  const json& plain = results["conditions"]["plain_to_plain"];
  EXPECT_GE(plain["true_positives"].get<int>(), 4);
  EXPECT_LT(plain["mean_localisation_error_px"].get<double>(), 1.5);
  EXPECT_LT(results["ekf"]["plain_to_plain"]["mean_error_ekf_cm"].get<double>(),
            results["ekf"]["plain_to_plain"]["mean_error_odometry_cm"].get<double>());
  for (const char* figure : {"detections_per_frame", "histograms", "ekf_path", "ekf_covariance"}) {
    const ImageRGBA png = readImage(path(std::string("run/figures/") + figure + ".png"));
    EXPECT_GT(png.width, 300) << figure;
  }
  std::stringstream html;
  html << std::ifstream(path("run/report.html")).rdbuf();
  EXPECT_NE(html.str().find("figures/ekf_path.png"), std::string::npos);
  EXPECT_NE(html.str().find("frames/plain_to_realistic.png"), std::string::npos);
  EXPECT_TRUE(fs::exists(path("run/frames/plain_to_textured.png")));
  std::stringstream doc;
  doc << std::ifstream(path("doc.md")).rdbuf();
  EXPECT_NE(doc.str().find("| plain_to_plain | USARSim, plain walls | 94 | 2 |"), std::string::npos) << doc.str();
  EXPECT_NE(doc.str().find("Which findings reproduce"), std::string::npos);
}

TEST_F(ExperimentCliTest, ArenaHallFromARealPhotoAndFromAnUnwrappedOmniImage) {
  auto r = omnicam("arena hall --photo /usr/share/blender/datafiles/studiolights/world/interior.exr -o " + path("lab/hall.json"));
  ASSERT_EQ(r.code, 0) << r.out;
  r = omnicam("render " + path("lab/hall.json") + " --size 96 -o " + path("lab.png"));
  ASSERT_EQ(r.code, 0) << r.out;

  // The thesis' route: an omni image, unwrapped, projected onto the walls.
  ASSERT_EQ(omnicam("render " + path("lab/hall.json") + " --size 200 --shading lit -o " + path("omni.png")).code, 0);
  ASSERT_EQ(omnicam("view " + path("omni.png") + " --as panorama -o " + path("pano.png")).code, 0);
  r = omnicam("arena hall --photo " + path("pano.png") + " -o " + path("fromomni/hall.json"));
  ASSERT_EQ(r.code, 0) << r.out;
  EXPECT_TRUE(fs::exists(path("fromomni/hall_textures/hall_wall_north.png")));
  ASSERT_EQ(omnicam("render " + path("fromomni/hall.json") + " --size 96 -o " + path("fromomni.png")).code, 0);

  // A panorama in the thesis variant has no exact elevation per row: refused, nothing written.
  ASSERT_EQ(omnicam("view " + path("omni.png") + " --as panorama --variant thesis -o " + path("thesis.png")).code, 0);
  r = omnicam("arena hall --photo " + path("thesis.png") + " -o " + path("bad/hall.json"));
  EXPECT_EQ(r.code, 2) << r.out;
  EXPECT_NE(r.out.find("view.variant"), std::string::npos) << r.out;
  EXPECT_FALSE(fs::exists(path("bad/hall.json")));
  r = omnicam("arena maze -o " + path("x.json"));
  EXPECT_EQ(r.code, 2) << r.out;
}

}  // namespace
}  // namespace omnicam
