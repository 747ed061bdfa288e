#include "cubemap_renderer.h"

#include <gtest/gtest.h>
#include <tbb/global_control.h>

#include <cmath>
#include <cstring>

#include "errors.h"
#include "image_compare.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

const Scene& arena() {
  static const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return s;
}

RenderSettings settingsFor(const Scene& s, int spp) {
  RenderSettings r;
  r.rig = s.rig;
  r.spp = spp;
  return r;
}

TEST(CubeMap, SixFacesMatchExactModeAt16Spp) {
  const FastRenderer fast(arena());
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(arena(), 16);
  CubeMapOptions options;
  const CompareResult r = compareImages(fast.render(arena().startPose, settings), cube.render(arena().startPose, settings, options));
  std::printf("cube map (6 faces, 512) vs exact, 16 spp: PSNR %.2f dB\n", r.psnrDb);
  EXPECT_GE(r.psnrDb, 40.0);
}

TEST(CubeMap, RasterisedFacesMatchRayCastFaces) {
  // Two independent ways to fill the faces: one ray per texel centre, or rasterising the
  // (tessellated) scene at texel centres. Only curved primitives' tessellation may differ.
  const FastRenderer fast(arena());
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(arena(), 4);
  CubeMapOptions raster, rays;
  rays.rasterize = false;
  for (const RobotPose& pose : {arena().startPose, RobotPose{-0.4, 0.9, 250.0}}) {
    const CompareResult r = compareImages(cube.render(pose, settings, rays), cube.render(pose, settings, raster));
    std::printf("rasterised vs ray-cast faces: PSNR %.2f dB\n", r.psnrDb);
    EXPECT_GE(r.psnrDb, 60.0);
  }
}

TEST(CubeMap, ThesisMeshDistortionShrinksWithPolygonCount) {
  const FastRenderer fast(arena());
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(arena(), 4);
  const ImageRGBA exact = fast.render(arena().startPose, settings);
  double previous = 0.0;
  for (int polygons : {16, 64, 256, 1024}) {
    CubeMapOptions options;
    options.mode = OmniMode::ThesisMesh;
    options.polygons = polygons;
    const double psnr = compareImages(exact, cube.render(arena().startPose, settings, options)).psnrDb;
    std::printf("thesis mesh %4d polygons vs exact: PSNR %.2f dB\n", polygons, psnr);
    EXPECT_GT(psnr, previous + 1.0) << polygons;
    previous = psnr;
  }
}

// A white sky all around: what five faces miss shows as black.
Scene skyScene() {
  Scene s;
  s.materials.push_back({"sky", {1.0f, 1.0f, 1.0f}, nullptr, "", {1, 1}, 1.0f, 0.0f});
  s.objects.push_back({"sky", 0, Sphere{{0, 0, 0.4}, 50.0}});
  return s;
}

TEST(CubeMap, FiveFacesMissTheCornersOfA45DegreeRim) {
  const Scene sky = skyScene();
  const FastRenderer fast(sky);
  const CubeMapRenderer cube(fast);
  RenderSettings settings;
  settings.spp = 4;
  CubeMapOptions five;
  five.faces = 5;
  const ImageRGBA image = cube.render({0, 0, 0}, settings, five);
  const CubeLookupStats stats = cube.stats(settings, five);
  // The image's black samples are exactly the lookup's missed ones.
  double black = 0.0, inside = 0.0;
  for (int j = 0; j < image.height; ++j)
    for (int i = 0; i < image.width; ++i) {
      inside += image.at(i, j)[3];
      black += image.at(i, j)[3] - image.at(i, j)[0];
    }
  EXPECT_NEAR(black / inside, static_cast<double>(stats.missedSamples) / stats.samples, 1e-4);
  std::printf("five faces miss %.3f%% of the mirror disc\n", 100.0 * stats.missedSamples / stats.samples);
  EXPECT_GT(stats.missedSamples, 0);
  // Near the rim: black along a diagonal azimuth (the face corners reach only 35.3°), covered
  // along an axis (face centres reach 45°).
  const OmniCamera cam = settings.rig.camera();
  const double r = cam.rimRadius() - 2.0;
  const Vec2 c = cam.centre();
  EXPECT_LT(image.at(static_cast<int>(c.x() + r / std::sqrt(2.0)), static_cast<int>(c.y() + r / std::sqrt(2.0)))[0], 0.01f);
  EXPECT_GT(image.at(static_cast<int>(c.x() + r), static_cast<int>(c.y()))[0], 0.99f);
  CubeMapOptions six;
  EXPECT_EQ(cube.stats(settings, six).missedSamples, 0);
}

TEST(CubeMap, OutputIsBitIdenticalForAnyThreadCountAndOptionsAreChecked) {
  const FastRenderer fast(arena());
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(arena(), 1);
  CubeMapOptions options;
  ImageRGBA one, two;
  {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, 1);
    one = cube.render(arena().startPose, settings, options);
  }
  two = cube.render(arena().startPose, settings, options);
  EXPECT_EQ(std::memcmp(one.pixels.data(), two.pixels.data(), one.pixels.size() * sizeof(float)), 0);
  options.faces = 4;
  EXPECT_THROW(cube.render(arena().startPose, settings, options), InputError);
  options.faces = 6;
  options.mode = OmniMode::ThesisMesh;
  options.polygons = 100;
  EXPECT_THROW(cube.render(arena().startPose, settings, options), InputError);
}

}  // namespace
}  // namespace omnicam
