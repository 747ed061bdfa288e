#include "fast_renderer.h"

#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <filesystem>

#include "errors.h"
#include "scene_loader.h"
#include "thread_count_testing.h"
#include "placement.h"

namespace omnicam {
namespace {

// A grey floor quad under the robot, one light straight above, black sky.
Scene floorScene(double lightHeight) {
  Scene s;
  s.materials.push_back({"grey", {0.5f, 0.4f, 0.3f}, nullptr, "", {1, 1}, 0.25f, 0.75f, ""});
  s.objects.push_back({"floor", 0, Quad{{-50, -50, 0}, {100, 0, 0}, {0, 100, 0}}, ""});
  s.lights.push_back({"lamp", {0.3, -0.2, lightHeight}, {1.0f, 1.0f, 1.0f}});
  return s;
}

TEST(FastRenderer, UnlitFloorIsTheAlbedoBelowTheHorizonAndSkyAbove) {
  const Scene s = floorScene(3.0);
  const FastRenderer renderer(s);
  RenderSettings settings;
  settings.spp = 4;
  const ImageRGBA img = renderer.render(RobotPose{0, 0, 0}, settings);
  const OmniCamera cam = settings.rig.camera();
  const float* centre = img.at(180, 180);
  EXPECT_FLOAT_EQ(centre[0], 0.5f);
  EXPECT_FLOAT_EQ(centre[2], 0.3f);
  EXPECT_FLOAT_EQ(centre[3], 1.0f);
  // A pixel wholly between the horizon circle (h) and the rim sees the sky: black, opaque.
  const int i = 180 + static_cast<int>(cam.horizonRadius() + 20.0);
  EXPECT_FLOAT_EQ(img.at(i, 180)[0], 0.0f);
  EXPECT_FLOAT_EQ(img.at(i, 180)[3], 1.0f);
  // Corners lie outside the rim: RGB 0, alpha 0.
  EXPECT_FLOAT_EQ(img.at(0, 0)[3], 0.0f);
  EXPECT_FLOAT_EQ(img.at(0, 0)[1], 0.0f);
}

TEST(FastRenderer, RimPixelsCarryTheFractionOfSamplesInside) {
  const Scene s = floorScene(3.0);
  const FastRenderer renderer(s);
  RenderSettings settings;
  settings.spp = 16;
  const ImageRGBA img = renderer.render(RobotPose{0, 0, 0}, settings);
  const OmniCamera cam = settings.rig.camera();
  int partial = 0;
  for (int j = 0; j < img.height; ++j)
    for (int i = 0; i < img.width; ++i) {
      int inside = 0;
      for (int b = 0; b < 4; ++b)
        for (int a = 0; a < 4; ++a) inside += cam.insideRim({i + (a + 0.5) / 4, j + (b + 0.5) / 4});
      ASSERT_FLOAT_EQ(img.at(i, j)[3], inside / 16.0f);
      partial += inside > 0 && inside < 16;
    }
  EXPECT_GT(partial, 500);
}

TEST(FastRenderer, LitShadingMatchesLambertInClosedForm) {
  const double lightHeight = 2.5;
  const Scene s = floorScene(lightHeight);
  const FastRenderer renderer(s);
  RenderSettings settings;
  settings.shading = Shading::Lit;
  const ImageRGBA img = renderer.render(RobotPose{0, 0, 0}, settings);
  const OmniCamera cam = settings.rig.camera();
  const Rigid wfc = CameraPlacement({0, 0, 0}).worldFromCamera(settings.rig);
  for (int j = 100; j < 260; j += 13) {
    for (int i = 100; i < 260; i += 11) {
      const Vec3 d = wfc.linear() * cam.cameraFromRaster({i + 0.5, j + 0.5});
      if (d.z() >= 0.0) continue;
      const Vec3 p = wfc.translation() + (-wfc.translation().z() / d.z()) * d;
      const Vec3 toLight = s.lights[0].position - p;
      const double cosine = toLight.z() / toLight.norm();
      const double expected = 0.5 * (0.25 + 0.75 * cosine);
      EXPECT_NEAR(img.at(i, j)[0], expected, 1e-5) << i << "," << j;
    }
  }
}

TEST(FastRenderer, HardShadowsLeaveOnlyAmbient) {
  Scene s = floorScene(3.0);
  // A ball on the line from the lamp to the floor point straight below the viewpoint.
  s.objects.push_back({"ball", 0, Sphere{{1.0, 0.0, 1.5}, 0.3}, ""});
  s.lights[0].position = {2.0, 0.0, 3.0};
  const FastRenderer renderer(s);
  // Floor point on the line lamp → ball centre: (0, 0, 0).
  const Vec3 origin(0.0, 0.0, 0.4);
  const Vec3 toFloor = Vec3(0.0, 0.0, 0.0) - origin;
  const Vec3f shadowed = renderer.radiance(origin, toFloor, Shading::Lit);
  EXPECT_NEAR(shadowed[0], 0.5 * 0.25, 1e-6);
  const Vec3f lit = renderer.radiance(origin, Vec3(-1.0, 0.0, -0.4), Shading::Lit);
  EXPECT_GT(lit[0], 0.5 * 0.25 + 0.1);
}

TEST(FastRenderer, OutputIsBitIdenticalForAnyThreadCount) {
  const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = s.rig;
  settings.spp = 4;
  settings.shading = Shading::Lit;
  // One thread against four (more than this machine may have cores; all four in the arena when
  // the render starts), each with its own renderer, so that its tables are built there too.
  expectSameFrameOnOneAndFourThreads<FastRenderer>(s, settings);
}

TEST(FastRenderer, TexturedFloorShowsTheSrgbDecodedBilinearTexel) {
  // A 4×4 PNG texture (sRGB on disk) on a 2 m floor quad: the pixel straight below the
  // viewpoint must show the bilinear texel at the UV of that floor point, decoded to linear.
  const auto dir = std::filesystem::temp_directory_path() / ("omnicam_tex_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  ImageRGBA tex(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      float* p = tex.at(i, j);
      p[0] = 0.05f + 0.3f * i;
      p[1] = 0.05f + 0.2f * j;
      p[2] = 0.5f;
      p[3] = 1.0f;
    }
  const std::string texPath = (dir / "t.png").string();
  writeImageAtomic(texPath, tex);
  Scene s;
  s.materials.push_back({"tex", {1.0f, 1.0f, 1.0f}, Texture::load(texPath), "t.png", {1, 1}, 0.2f, 0.8f, ""});
  s.objects.push_back({"floor", 0, Quad{{-1, -1, 0}, {2, 0, 0}, {0, 2, 0}}, ""});
  const FastRenderer renderer(s);
  for (const Vec2& floor : {Vec2(0.0, 0.0), Vec2(0.3, -0.55), Vec2(-0.71, 0.2)}) {
    const Vec3f got = renderer.radiance({floor.x(), floor.y(), 0.4}, {0, 0, -1}, Shading::Unlit);
    // UV of the floor point: (s, t) along the quad's edges; v = 0 is the image's bottom row.
    const double u = (floor.x() + 1.0) / 2.0, v = (floor.y() + 1.0) / 2.0;
    const double x = u * 4 - 0.5, y = (1.0 - v) * 4 - 0.5;
    const int i0 = static_cast<int>(std::floor(x)), j0 = static_cast<int>(std::floor(y));
    const double fx = x - i0, fy = y - j0;
    auto texel = [&](int i, int j, int c) {  // what the PNG stores, decoded
      i = (i + 4) % 4, j = (j + 4) % 4;
      const float stored = std::round(linearToSrgb(tex.at(i, j)[c]) * 255.0f) / 255.0f;
      return static_cast<double>(srgbToLinear(stored));
    };
    for (int c = 0; c < 3; ++c) {
      const double expected = (1 - fy) * ((1 - fx) * texel(i0, j0, c) + fx * texel(i0 + 1, j0, c)) +
                              fy * ((1 - fx) * texel(i0, j0 + 1, c) + fx * texel(i0 + 1, j0 + 1, c));
      EXPECT_NEAR(got[c], expected, 1e-5) << floor.transpose() << " channel " << c;
    }
  }
  std::filesystem::remove_all(dir);
}

TEST(FastRenderer, RejectsNonSquareSampleCounts) {
  const Scene s = floorScene(3.0);
  const FastRenderer renderer(s);
  RenderSettings settings;
  settings.spp = 5;
  EXPECT_THROW(renderer.render(RobotPose{0, 0, 0}, settings), InputError);
}

}  // namespace
}  // namespace omnicam
