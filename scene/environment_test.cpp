#include "environment.h"

#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "errors.h"
#include "image.h"
#include "scene_loader.h"
#include "shell_command.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// Cycles' Environment Texture (kernel/camera/projection.h, direction_to_equirectangular with its
// range (−2π, π, −π, π)): u = (atan2(y, x) − π)/(−2π), v = (acos(z) − π)/(−π). Written out here
// from those formulas, apart from the implementation's atan2-of-elevation form.
Eigen::Vector2d cyclesEquirect(const Vec3& d) {
  return {(std::atan2(d.y(), d.x()) - kPi) / (-2.0 * kPi), (std::acos(d.z() / d.norm()) - kPi) / (-kPi)};
}

TEST(Environment, DirectionsMapAsCyclesMapsThem) {
  for (const Vec3& d : {Vec3(1, 0, 0), Vec3(0, 1, 0), Vec3(0, -1, 0), Vec3(0.3, -0.4, 0.866), Vec3(-0.5, 0.2, -0.7),
                        Vec3(-1, 1e-9, 0.01)}) {
    const Vec3 unit = d.normalized();
    const Eigen::Vector2d uv = equirectFromDirection(unit), cycles = cyclesEquirect(unit);
    EXPECT_NEAR(uv.x(), cycles.x(), 1e-12) << unit.transpose();
    EXPECT_NEAR(uv.y(), cycles.y(), 1e-12) << unit.transpose();
    EXPECT_NEAR((directionFromEquirect(uv) - unit).norm(), 0.0, 1e-12) << unit.transpose();
  }
  // The image's centre looks along +X, a quarter to the left along +Y; the top row is the zenith.
  EXPECT_NEAR(equirectFromDirection({0, 1, 0}).x(), 0.25, 1e-15);
  EXPECT_NEAR(equirectFromDirection({0, 0, 1}).y(), 1.0, 1e-15);
}

// A 4×2 image whose every texel differs: the column a direction reads, and a rotation that turns it.
TEST(Environment, RotationTurnsTheSkyCounterClockwiseAndStrengthScalesIt) {
  std::vector<float> rgb;
  for (int t = 0; t < 8; ++t) rgb.insert(rgb.end(), {float(t), 0.0f, 1.0f});
  Environment environment;
  environment.image = std::make_shared<Texture>(4, 2, rgb);
  // The upper row's texel centres sit at azimuths 135°, 45°, −45°, −135° (columns 0–3), elevation 45°.
  const auto along = [](double azimuthDeg) {
    return Vec3(std::cos(radians(azimuthDeg)), std::sin(radians(azimuthDeg)), 1.0).normalized();
  };
  EXPECT_FLOAT_EQ(environment.radiance(along(135)).x(), 0.0f);
  EXPECT_FLOAT_EQ(environment.radiance(along(45)).x(), 1.0f);
  EXPECT_FLOAT_EQ(environment.radiance(along(-45)).x(), 2.0f);
  environment.rotationDeg = 90.0;
  environment.strength = 3.0f;
  EXPECT_FLOAT_EQ(environment.radiance(along(135)).x(), 3.0f * 1.0f);  // what 45° showed, turned by 90°
  EXPECT_FLOAT_EQ(environment.radiance(along(45)).x(), 3.0f * 2.0f);
  EXPECT_FLOAT_EQ(environment.radiance(along(135)).z(), 3.0f);
  const Vec3 d = Vec3(0.2, -0.7, 0.3).normalized();
  EXPECT_NEAR((environment.imageFromWorld(environment.worldFromImage(d)) - d).norm(), 0.0, 1e-15);
}

class EnvironmentLoadTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_environment_test_" + std::to_string(::getpid()));
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  void writeSky(const std::string& name, float value) {
    ImageRGBA sky(8, 4);
    for (size_t p = 0; p < sky.pixels.size(); p += 4) sky.pixels[p] = sky.pixels[p + 1] = sky.pixels[p + 2] = sky.pixels[p + 3] = 1.0f;
    sky.pixels[0] = value;
    writeImageAtomic((dir_ / name).string(), sky);
  }
  // The scene's load error, or "" when it loads.
  std::string errorOf(const std::string& environment) {
    const fs::path file = dir_ / "scene.json";
    std::ofstream(file) << R"({"format": "omnicam-scene/1", "environment": )" + environment +
                               R"(, "materials": {"m": {}}, "objects": []})";
    try {
      scene_ = loadScene(file.string());
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  }
  fs::path dir_;
  Scene scene_;
};

TEST_F(EnvironmentLoadTest, AnEquirectangularImageLoadsWithItsStrengthAndRotation) {
  writeSky("sky.exr", 5.0f);
  EXPECT_EQ(errorOf(R"({"file": "sky.exr", "strength": 2, "rotation_deg": -30})"), "");
  ASSERT_TRUE(scene_.environment);
  EXPECT_EQ(scene_.environment->file, "sky.exr");
  EXPECT_EQ(scene_.environment->image->width(), 8);
  EXPECT_FLOAT_EQ(scene_.environment->image->rgbLinear()[0], 5.0f);  // HDR kept
  EXPECT_FLOAT_EQ(scene_.environment->strength, 2.0f);
  EXPECT_DOUBLE_EQ(scene_.environment->rotationDeg, -30.0);
  EXPECT_EQ(errorOf(R"({"file": "sky.exr"})"), "");
  EXPECT_FLOAT_EQ(scene_.environment->strength, 1.0f);
  // Blender's own worlds by name (Debian's blender-data): 1024 × 512 HDR skies.
  EXPECT_EQ(errorOf(R"({"blender_world": "forest"})"), "");
  EXPECT_EQ(scene_.environment->file, "forest");
  EXPECT_EQ(scene_.environment->image->width(), 1024);
  EXPECT_EQ(scene_.environment->image->height(), 512);
  // It is one of the files the scene reads, by its full path, hashed (independently: coreutils).
  const std::string forest = "/usr/share/blender/datafiles/studiolights/world/forest.exr";
  ASSERT_EQ(scene_.inputDigests.size(), 1u);
  EXPECT_EQ(scene_.inputDigests[0].path, forest);
  EXPECT_EQ(scene_.inputDigests[0].sha256, testing::runShell("sha256sum " + forest).out.substr(0, 64));
}

TEST_F(EnvironmentLoadTest, BadEnvironmentsAreRefusedWithOneLine) {
  const std::string file = (dir_ / "scene.json").string();
  writeSky("sky.exr", 1.0f);
  writeSky("bright.exr", 5e5f);
  EXPECT_EQ(errorOf(R"({"file": "bright.exr", "strength": 3})"),
            file + ": environment.strength: the image's brightest value (500000) times strength must be at most 1e+06, a light's limit");
  writeSky("negative.exr", -1.0f);  // lossy compression leaves small negative values: no light
  EXPECT_EQ(errorOf(R"({"file": "negative.exr"})"), "");
  EXPECT_EQ(scene_.environment->image->rgbLinear()[0], 0.0f);
  EXPECT_EQ(errorOf(R"({"file": "sky.exr", "strength": -1})"), file + ": environment.strength: must be in [0, 1e+06] (got -1)");
  EXPECT_EQ(errorOf(R"({"file": "sky.exr", "rotation": 3})"), file + ": environment.rotation: unknown field (did you mean rotation_deg?)");
  EXPECT_NE(errorOf(R"({"file": "none.exr"})").find(file + ": environment.file: file not found"), std::string::npos);
  EXPECT_NE(errorOf(R"({"file": "../../sky.exr"})").find("resolves outside the scene's folder"), std::string::npos);
  EXPECT_EQ(errorOf(R"("sky.exr")"), file + ": environment: must be an object (got string)");
  EXPECT_EQ(errorOf(R"({"strength": 2})"), file + ": environment.file: give either file or blender_world");
  EXPECT_EQ(errorOf(R"({"file": "sky.exr", "blender_world": "forest"})"), file + ": environment.file: give either file or blender_world");
  EXPECT_EQ(errorOf(R"({"blender_world": "../forest"})"),
            file + ": environment.blender_world: no world \"../forest\" in /usr/share/blender/datafiles/studiolights/world "
                   "(city, courtyard, forest, interior, night, studio, sunrise, sunset)");
}

}  // namespace
}  // namespace omnicam
