#include "cubemap_renderer.h"

#include <gtest/gtest.h>

#include "central_camera.h"

#include <cmath>
#include <cstring>

#include "errors.h"
#include "image_compare.h"
#include "rings.h"
#include "scene_loader.h"
#include "texture.h"
#include "thread_count_testing.h"

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
  EXPECT_GE(r.psnrDb, 43.0);  // measured 45.9 dB: a floor 3 dB under it
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
    EXPECT_GE(r.psnrDb, 62.5);  // measured 77.1 and 65.6 dB: a floor 3 dB under the lower
  }
}

// A floor 2 km wide: its triangles, clipped at the faces' near plane, reach ~1e9 texels out,
// past int; rasterised they must still cover what one ray per texel sees (the faces lost them).
TEST(CubeMap, RasterisedFacesKeepAFloorAKilometreWide) {
  const Scene floor = loadSceneFromText(R"({"format": "omnicam-scene/1", "materials": {"grey": {"color": 0.6}},
    "objects": [{"type": "quad", "material": "grey", "origin": [-1000, -1000, 0], "edge_u": [2000, 0, 0], "edge_v": [0, 2000, 0]}]})",
                                        "floor.json");
  const FastRenderer fast(floor);
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(floor, 1);
  CubeMapOptions raster, rays;
  rays.rasterize = false;
  const CompareResult r = compareImages(cube.render(RobotPose{0.3, -0.2, 20.0}, settings, rays),
                                        cube.render(RobotPose{0.3, -0.2, 20.0}, settings, raster));
  std::printf("2 km floor, rasterised vs ray-cast faces: PSNR %.2f dB, max abs %.3g\n", r.psnrDb, r.maxAbs);
  EXPECT_LT(r.maxAbs, 1e-6);
}

// A small room with textured floor and wall, plain walls and a box, and a grey background
// (the room is open at the top).
Scene texturedRoom() {
  Scene s;
  std::vector<float> rgb;
  for (int k = 0; k < 8 * 8; ++k)  // a fixed pseudo-random 8×8 texture
    for (int c = 0; c < 3; ++c) rgb.push_back(static_cast<float>((k * 37 + c * 101) % 97) / 96.0f);
  const auto texture = std::make_shared<Texture>(8, 8, rgb);
  s.materials.push_back({"floor", {1.0f, 0.9f, 0.8f}, texture, "t.png", {3, 2}, 0.2f, 0.8f, ""});
  s.materials.push_back({"wall", {0.2f, 0.5f, 0.9f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  s.materials.push_back({"poster", {1.0f, 1.0f, 1.0f}, texture, "t.png", {1, 1}, 0.2f, 0.8f, ""});
  s.materials.push_back({"box", {0.9f, 0.3f, 0.1f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  s.objects.push_back({"floor", 0, Quad{{-2, -2, 0}, {4, 0, 0}, {0, 4, 0}}, ""});
  s.objects.push_back({"north", 1, Quad{{-2, 2, 0}, {4, 0, 0}, {0, 0, 0.6}}, ""});
  s.objects.push_back({"south", 1, Quad{{-2, -2, 0}, {4, 0, 0}, {0, 0, 0.6}}, ""});
  s.objects.push_back({"west", 1, Quad{{-2, -2, 0}, {0, 4, 0}, {0, 0, 0.6}}, ""});
  s.objects.push_back({"east", 2, Quad{{2, -2, 0}, {0, 4, 0}, {0, 0, 0.6}}, ""});
  s.objects.push_back({"box", 3, Box{{0.8, 0.5, 0.15}, {0.3, 0.4, 0.3}, 20.0}, ""});
  s.background = {0.3f, 0.3f, 0.3f};
  return s;
}

TEST(CubeMap, RasterisedTexturedFacesMatchRayCastFaces) {
  // Textured surfaces keep their own texel colours, the others go through the palette; with
  // more materials than palette indices every texel keeps its own colour. All must agree.
  Scene room = texturedRoom();
  const FastRenderer fast(room);
  const CubeMapRenderer cube(fast);
  RenderSettings settings;
  settings.rig = room.rig;
  settings.spp = 4;
  CubeMapOptions raster, rays;
  rays.rasterize = false;
  const RobotPose pose{0.3, -0.4, 30.0};
  const ImageRGBA rasterised = cube.render(pose, settings, raster);
  const CompareResult r = compareImages(cube.render(pose, settings, rays), rasterised);
  std::printf("textured room, rasterised vs ray-cast faces: PSNR %.2f dB\n", r.psnrDb);
  EXPECT_GE(r.psnrDb, 120.0);  // measured 146 dB: no curved primitives, the same image to float rounding
  // The textures show: untextured, the same view differs clearly.
  Scene plain = texturedRoom();
  for (Material& m : plain.materials) m.texture = nullptr;
  const FastRenderer plainFast(plain);
  const CubeMapRenderer plainCube(plainFast);
  const double plainPsnr = compareImages(rasterised, plainCube.render(pose, settings, raster)).psnrDb;
  std::printf("textured vs untextured: PSNR %.2f dB\n", plainPsnr);
  EXPECT_LT(plainPsnr, 25.0);

  for (int k = 0; k < 300; ++k) room.materials.push_back({"unused", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  const FastRenderer manyFast(room);
  const CubeMapRenderer manyCube(manyFast);
  EXPECT_LT(compareImages(rasterised, manyCube.render(pose, settings, raster)).maxAbs, 1e-5);
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

TEST(CubeMap, ThesisMeshBendsIncidenceRingsLessWithMorePolygons) {
  // Per-azimuth ring radii against the exact model: the cube map stays near the measurement's
  // floor, the thesis mesh bends the rings, less with each doubling of its sectors and rings.
  const Scene rings = loadScene(OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json");
  const FastRenderer fast(rings);
  const CubeMapRenderer cube(fast);
  const RenderSettings settings = settingsFor(rings, 4);
  const CentralCamera camera(settings.rig);
  const double cubeRms =
      measureRingProfiles(cube.render(rings.startPose, settings, CubeMapOptions{}), camera, defaultRingThetasDeg()).rmsPx;
  std::printf("incidence rings per azimuth: cube map %.3f px", cubeRms);
  double previous = 1e9;
  for (int polygons : {16, 64, 256, 1024}) {
    CubeMapOptions options;
    options.mode = OmniMode::ThesisMesh;
    options.polygons = polygons;
    const double rms = measureRingProfiles(cube.render(rings.startPose, settings, options), camera, defaultRingThetasDeg()).rmsPx;
    std::printf(", %d polygons %.3f px", polygons, rms);
    EXPECT_LT(rms, previous) << polygons;
    EXPECT_GT(rms, 3.0 * cubeRms) << polygons;
    previous = rms;
  }
  std::printf("\n");
  EXPECT_LT(cubeRms, 0.2);
}

// A white sky all around: what five faces miss shows as black.
Scene skyScene() {
  Scene s;
  s.materials.push_back({"sky", {1.0f, 1.0f, 1.0f}, nullptr, "", {1, 1}, 1.0f, 0.0f, ""});
  s.objects.push_back({"sky", 0, Sphere{{0, 0, 0.4}, 50.0}, ""});
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
  const ImageRGBA image = cube.render(RobotPose{0, 0, 0}, settings, five);
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
  // One thread against four (more than this machine may have cores; all four in the arena when
  // the render starts), each with its own renderers, so that their lookups are built there too.
  const FastRenderer fastOne(arena()), fastFour(arena());
  const CubeMapRenderer cubeOne(fastOne), cubeFour(fastFour);
  ImageRGBA one, four;
  EXPECT_EQ(runOnThreads(1, [&] { one = cubeOne.render(arena().startPose, settings, options); }), 1);
  EXPECT_EQ(runOnThreads(4, [&] { four = cubeFour.render(arena().startPose, settings, options); }), 4);
  ASSERT_EQ(one.pixels.size(), four.pixels.size());
  EXPECT_EQ(std::memcmp(one.pixels.data(), four.pixels.data(), one.pixels.size() * sizeof(float)), 0);
  // A reused output image (here holding another pose at another size) is wholly overwritten.
  Film reused = filmFor(settings);
  cube.render(RobotPose{0.5, 0.5, 10.0}, settings, options, reused);
  cube.render(arena().startPose, settings, options, reused);
  ASSERT_EQ(reused.image().pixels.size(), one.pixels.size());
  EXPECT_EQ(reused.image().width, one.width);
  EXPECT_EQ(std::memcmp(one.pixels.data(), reused.image().pixels.data(), one.pixels.size() * sizeof(float)), 0);
  // A film of another size is refused, not resized behind the caller's back.
  RenderSettings small = settings;
  small.rig.mirrorRig().imageSize = 97;
  EXPECT_THROW(cube.render(arena().startPose, small, options, reused), std::invalid_argument);
  options.faces = 4;
  EXPECT_THROW(cube.render(arena().startPose, settings, options), InputError);
  options.faces = 6;
  options.mode = OmniMode::ThesisMesh;
  options.polygons = 100;
  EXPECT_THROW(cube.render(arena().startPose, settings, options), InputError);
}

}  // namespace
}  // namespace omnicam
