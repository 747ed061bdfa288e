// The hall: a synthetic 360° photo whose colour says its direction lands on the wall that faces
// that direction, at the height where the projection puts it; the hall fills the mirror.
#include "hall_arena.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>

#include "errors.h"
#include "fast_renderer.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

class HallArenaTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("omnicam_hall_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }
  HallOptions options() const {
    HallOptions o;
    o.fieldScene = std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json";
    o.texelsPerMetre = 16;
    return o;
  }
  fs::path dir_;
};

// Equirectangular: red toward +x (azimuth ±45°), green toward +y, blue toward −x, white toward
// −y; the upper half bright, the lower half at a quarter.
std::string writeCompassPhoto(const fs::path& path) {
  ImageRGBA photo(256, 128);
  for (int j = 0; j < photo.height; ++j)
    for (int i = 0; i < photo.width; ++i) {
      const double azimuth = M_PI - 2 * M_PI * (i + 0.5) / photo.width;
      const int quadrant = static_cast<int>(std::lround(azimuth / (M_PI / 2))) & 3;  // 0 +x, 1 +y, 2 −x, 3 −y
      const float level = j < photo.height / 2 ? 0.8f : 0.2f;
      const float colours[4][3] = {{1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {1, 1, 1}};
      float* p = photo.at(i, j);
      for (int c = 0; c < 3; ++c) p[c] = level * colours[quadrant][c];
      p[3] = 1.0f;
    }
  writeImageAtomic(path.string(), photo);
  return path.string();
}

TEST_F(HallArenaTest, EachWallShowsThePhotoInItsDirectionAtTheRightHeight) {
  HallOptions o = options();
  o.photos = {writeCompassPhoto(dir_ / "compass.png")};
  const std::vector<std::string> textures = writeHallArena(o, (dir_ / "hall.json").string());
  ASSERT_EQ(textures.size(), 4u);
  const std::map<std::string, Vec3f> expected = {
      {"east", {1, 0, 0}}, {"north", {0, 1, 0}}, {"west", {0, 0, 1}}, {"south", {1, 1, 1}}};
  for (const auto& [wall, colour] : expected) {
    const ImageRGBA texture = readImage((dir_ / "hall_textures" / ("hall_wall_" + wall + ".png")).string());
    // Wall middle: straight out from the centre. Rows above the projection height are above the
    // horizon (bright), rows below it below (dark). 1.6 m of 3.2 m: the horizon is mid-wall.
    const int i = texture.width / 2;
    for (const auto& [row, level] : {std::pair{texture.height / 4, 0.8f}, std::pair{3 * texture.height / 4, 0.2f}}) {
      const float* p = texture.at(i, row);
      for (int c = 0; c < 3; ++c) EXPECT_NEAR(p[c], level * colour[c], 0.02) << wall << " row " << row << " channel " << c;
    }
  }
  // The scene loads and names its walls' class.
  const Scene scene = loadScene((dir_ / "hall.json").string());
  int walls = 0;
  for (const SceneObject& object : scene.objects)
    if (object.name.rfind("hall_wall_", 0) == 0) {
      ++walls;
      EXPECT_EQ(scene.materials[object.material].semanticClass, "wall");
    }
  EXPECT_EQ(walls, 4);
}

TEST_F(HallArenaTest, TheHallFillsTheMirrorWhereTheOpenFieldIsBlack) {
  writeHallArena(options(), (dir_ / "plain.json").string());
  const Scene hall = loadScene((dir_ / "plain.json").string());
  const Scene field = loadScene(options().fieldScene);
  RenderSettings settings;
  settings.rig = field.rig;
  settings.rig.mirrorRig().imageSize = 120;
  auto missFraction = [&](const Scene& scene) {
    AovFrame aovs;
    const ImageRGBA image = FastRenderer(scene).render(field.startPose, settings, aovs);
    int inside = 0, missed = 0;
    for (size_t p = 0; p < aovs.instance.size(); ++p)
      if (image.pixels[p * 4 + 3] > 0.999f) ++inside, missed += aovs.instance[p] == 0;
    return static_cast<double>(missed) / inside;
  };
  EXPECT_GT(missFraction(field), 0.5);
  EXPECT_EQ(missFraction(hall), 0.0);
  // The field's lamps hang in the hall as luminaires of real size, where they were, with their power.
  ASSERT_EQ(hall.lights.size(), field.lights.size());
  for (size_t k = 0; k < hall.lights.size(); ++k) {
    EXPECT_EQ(field.lights[k].diameter, 0.0);
    EXPECT_EQ(hall.lights[k].diameter, 0.5);
    EXPECT_EQ(hall.lights[k].position, field.lights[k].position);
    EXPECT_EQ(hall.lights[k].intensity, field.lights[k].intensity);
  }
}

TEST_F(HallArenaTest, AnUnwrappedOmniImageNeedsTheExactPanoramaSidecar) {
  ImageRGBA pano(64, 20);
  for (size_t p = 3; p < pano.pixels.size(); p += 4) pano.pixels[p] = 1.0f;
  writeImageAtomic((dir_ / "pano.png").string(), pano);
  HallOptions o = options();
  o.photos = {(dir_ / "pano.png").string()};
  // No sidecar and not 2:1: refused with the reason.
  EXPECT_THROW(writeHallArena(o, (dir_ / "hall.json").string()), InputError);
  std::ofstream(dir_ / "pano.png.json") << R"({"view": {"kind": "panorama", "variant": "thesis"}, "rig": {}})";
  try {
    writeHallArena(o, (dir_ / "hall.json").string());
    FAIL() << "a thesis-variant panorama was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("view.variant"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(fs::exists(dir_ / "hall.json"));
}

}  // namespace
}  // namespace omnicam
