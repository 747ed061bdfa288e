// Ground truth: POV-Ray traces the real optics (pinhole + exact quadric mirror); the fast
// renderer must agree pixel by pixel (docs/conventions.md §7) and POV-Ray's rings must match the model.
#include "povray_renderer.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <sys/wait.h>
#include <unistd.h>

#include "blender_renderer.h"
#include "errors.h"
#include "fast_renderer.h"
#include "image_compare.h"
#include "job_folder.h"
#include "rings.h"
#include "scene_loader.h"
#include "test_rigs.h"

namespace omnicam {
namespace {

struct PoseCase {
  const char* label;
  RobotPose pose;
};

class FastVsPovray : public ::testing::TestWithParam<std::tuple<PoseCase, Shading>> {};

TEST_P(FastVsPovray, Robocup2006AtSixteenSamplesPerPixel) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  const auto& [pose, shading] = GetParam();
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.spp = 16;
  settings.shading = shading;
  const ImageRGBA ours = fast.render(pose.pose, settings);
  const ImageRGBA truth = renderWithPovray(scene, pose.pose, settings);
  const CompareResult r = compareImages(ours, truth);
  const double target = shading == Shading::Unlit ? 45.0 : 40.0;
  std::printf("fast vs POV-Ray, %s, %s: PSNR %.2f dB, SSIM %.5f, max abs %.4f\n", pose.label, shadingName(shading),
              r.psnrDb, r.ssim, r.maxAbs);
  EXPECT_GE(r.psnrDb, target);
  // Regression floor: both engines trace the same rays at the same sample positions, so they
  // agree far beyond the spec's targets (measured 73.2 dB at the thesis start corner, lit, to
  // 102 dB); a half-pixel or convention slip drops this below 60 dB.
  EXPECT_GE(r.psnrDb, 70.0);
  // Alpha is geometry: the same rim coverage in both.
  for (size_t p = 3; p < ours.pixels.size(); p += 4) ASSERT_FLOAT_EQ(ours.pixels[p], truth.pixels[p]);
}

INSTANTIATE_TEST_SUITE_P(
    Poses, FastVsPovray,
    ::testing::Combine(::testing::Values(PoseCase{"thesis start corner", {2.7, -1.8, 180.0}},
                                         PoseCase{"centre circle", {0.1, 0.05, 0.0}},
                                         PoseCase{"rotated 137 deg near a beacon", {1.0, -1.5, 137.0}},
                                         PoseCase{"blue goal mouth", {-2.4, 0.2, -63.0}},
                                         PoseCase{"north edge", {0.5, 1.7, 90.0}}),
                       ::testing::Values(Shading::Unlit, Shading::Lit)),
    [](const auto& param) {
      return std::string("pose") + std::to_string(param.index / 2) + "_" + shadingName(std::get<1>(param.param));
    });

// The physical camera: POV-Ray places the pinhole where the mount puts it and traces the exact
// quadric, so its image is the ground truth of a misaligned rig.
// A vibrating robot's rig is one more case: the whole rig tilted on the robot as well
// (POV-Ray then places its mirror with the full rotation).
struct MountCase {
  const char* label;
  CameraMount mount;
  RobotPose pose;
  std::array<double, 2> tiltDeg{0.0, 0.0};
};

class FastVsPovrayMisaligned : public ::testing::TestWithParam<MountCase> {};

TEST_P(FastVsPovrayMisaligned, UnlitAtSixteenSamplesPerPixel) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().mount = GetParam().mount;
  settings.rig.tiltDeg = GetParam().tiltDeg;
  settings.spp = 16;
  const ImageRGBA ours = fast.render(GetParam().pose, settings);
  const ImageRGBA truth = renderWithPovray(scene, GetParam().pose, settings);
  const CompareResult r = compareImages(ours, truth);
  settings.rig = settings.rig.idealized();
  settings.rig.tiltDeg = {0.0, 0.0};
  const double fromIdeal = compareImages(fast.render(GetParam().pose, settings), truth).psnrDb;
  std::printf("fast vs POV-Ray, %s: PSNR %.2f dB, SSIM %.5f, max abs %.4f (the ideal rig's image: %.2f dB)\n",
              GetParam().label, r.psnrDb, r.ssim, r.maxAbs, fromIdeal);
  EXPECT_GE(r.psnrDb, 60.0);
  EXPECT_LT(fromIdeal, 35.0);  // the misalignment shows: rendering the ideal rig instead fails
  for (size_t p = 3; p < ours.pixels.size(); p += 4) ASSERT_FLOAT_EQ(ours.pixels[p], truth.pixels[p]);
}

INSTANTIATE_TEST_SUITE_P(
    Mounts, FastVsPovrayMisaligned,
    ::testing::Values(
        MountCase{"3 mm, 2 deg, principal point off", {{3.0, -2.0, 1.5}, {2.0, -1.5, 1.0}, {}, {1.5, -0.75}}, {2.7, -1.8, 180.0}},
        MountCase{"-3 mm along the axis, 2 deg about it", {{-1.0, 2.5, -3.0}, {-0.5, 1.0, -2.0}, {}, {0.0, 0.0}}, {1.0, -1.5, 137.0}},
        MountCase{"rig tilted (2.5, -1.5) deg, camera shaken", {{0.8, -0.6, 0.3}, {0.4, -0.3, 0.2}, {}, {0.0, 0.0}},
                  {1.0, -1.5, 137.0}, {2.5, -1.5}}),
    [](const auto& param) { return "mount" + std::to_string(param.index); });

// A rocking robot (placement.h): the robot's own tilt turns each mounted camera about the robot's
// origin, so a camera standing off-centre also rises or sinks. POV-Ray places mirror and camera
// by the same chain; tilting the rig on its own foot instead gives another image.
TEST(FastVsPovrayRockingRobot, EveryMountedCameraTiltsAboutTheRobotsOrigin) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  RenderSettings settings;
  settings.rig = scene.rig.resized(120);
  settings.spp = 16;
  const RobotPose robot{1.0, -1.5, 137.0};
  const RobotTilt rocking{2.0, -3.0};
  for (const RobotMount& mount : {RobotMount{0.25, 0.0, 0.0}, RobotMount{-0.2, 0.1, 180.0}}) {
    const CameraPlacement placement(robot, {}, mount, rocking);
    const ImageRGBA ours = fast.render(placement, settings);
    const ImageRGBA truth = renderWithPovray(scene, placement, settings);
    const CompareResult r = compareImages(ours, truth);
    RenderSettings ownTilt = settings;
    ownTilt.rig.tiltDeg = rocking;
    const double rigTilted = compareImages(fast.render(CameraPlacement(robot, {}, mount), ownTilt), truth).psnrDb;
    std::printf("fast vs POV-Ray, robot tilted (2, -3) deg, camera mounted at (%.2f, %.2f, %.0f deg): PSNR %.2f dB, SSIM %.5f "
                "(the rig tilted on its own foot instead: %.2f dB)\n",
                mount.x, mount.y, mount.yawDeg, r.psnrDb, r.ssim, rigTilted);
    EXPECT_GE(r.psnrDb, 60.0);
    EXPECT_LT(rigTilted, 40.0);  // where the tilt applies shows
  }
}

// The other mirror shapes, each with its camera moved (2, −1, 1) mm and turned (1, −0.5, 0.5)°:
// POV-Ray traces the exact surface (quadric, sphere, cone) from the same camera — orthographic
// for the paraboloid's central build. In the tiled room, whose striped walls rise 0.6 m above F',
// so that the mirror's outer part, which images what lies above the horizon, is compared too (on
// the field alone POV-Ray's paraboloid, cut short of its rim, passed).
struct ShapeCase {
  const char* label;
  MirrorShapeSpec shape;
};

class FastVsPovrayShapes : public ::testing::TestWithParam<ShapeCase> {};

TEST_P(FastVsPovrayShapes, UnlitAtSixteenSamplesPerPixel) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json");
  static const FastRenderer fast(scene);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().shape = GetParam().shape;
  settings.rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
  settings.rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
  settings.spp = 16;
  const RobotPose pose{0.6, -0.4, 150.0};
  const ImageRGBA ours = fast.render(pose, settings);
  const ImageRGBA truth = renderWithPovray(scene, pose, settings);
  const CompareResult r = compareImages(ours, truth);
  settings.rig.mirrorRig().mount = {};
  const double aligned = compareImages(fast.render(pose, settings), truth).psnrDb;
  std::printf("fast vs POV-Ray, %s, moved 2 mm / turned 1 deg: PSNR %.2f dB, SSIM %.5f, max abs %.4f (the aligned "
              "camera's image: %.2f dB)\n", GetParam().label, r.psnrDb, r.ssim, r.maxAbs, aligned);
  EXPECT_GE(r.psnrDb, 60.0);
  EXPECT_LT(aligned, 40.0);  // the misalignment shows
}

INSTANTIATE_TEST_SUITE_P(
    Shapes, FastVsPovrayShapes,
    ::testing::Values(ShapeCase{"paraboloid, orthographic camera", test::shapeOf(MirrorShape::Paraboloid, 0.0)},
                      ShapeCase{"paraboloid, perspective camera 0.15 m below", test::shapeOf(MirrorShape::Paraboloid, 0.15)},
                      ShapeCase{"sphere r 3 cm, cap 60 deg, camera 0.12 m below", test::shapeOf(MirrorShape::Sphere, 0.12)},
                      ShapeCase{"cone 60 deg, rim 3 cm, camera 0.05 m below", test::shapeOf(MirrorShape::Cone, 0.05)}),
    [](const auto& param) { return std::string(mirrorShapeName(param.param.shape)) + std::to_string(param.index); });

TEST(Povray, LensDistortionIsRefusedNotIgnored) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().mount.distortion.k1 = -0.1;
  EXPECT_THROW(renderWithPovray(scene, scene.startPose, settings), InputError);
}

TEST(Povray, RingImageMatchesTheExactModel) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.spp = 16;
  const ImageRGBA image = renderWithPovray(scene, scene.startPose, settings);
  const RingReport r = measureRings(image, settings.rig.camera(), defaultRingThetasDeg());
  std::printf("POV-Ray rings: RMS %.4f px, max %.4f px, Eq. 3.2 MSE %.4f px^2\n", r.rmsPxExact, r.maxAbsPxExact,
              r.msePx2Eq32);
  // Measured RMS 0.0128 px, max 0.0435 px: bounds about twice that, under the 0.05 px target of
  // docs/conventions.md §7, so that a regression shows.
  EXPECT_LE(r.rmsPxExact, 0.025);
  EXPECT_LE(r.maxAbsPxExact, 0.09);
  EXPECT_NEAR(r.msePx2Eq32, 0.256, 0.02);
}

// A scene with no symmetry (and a texture): a mirrored or rotated export cannot match.
Scene asymmetricScene(const std::string& dir) {
  ImageRGBA tex(8, 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      float* p = tex.at(i, j);
      p[0] = 0.1f + 0.1f * i, p[1] = 0.1f + 0.1f * j, p[2] = ((i * 3 + j * 5) % 7) / 7.0f, p[3] = 1.0f;
    }
  writeImageAtomic(dir + "/asym.png", tex);
  const std::string path = dir + "/asym.json";
  FILE* f = std::fopen(path.c_str(), "w");
  std::fputs(R"({"format": "omnicam-scene/1",
    "materials": {"floor": {"texture": {"file": "asym.png", "scale": [3, 2]}},
                  "red": {"color": [0.9, 0.1, 0.1]}, "green": {"color": [0.1, 0.8, 0.2]},
                  "blue": {"color": [0.1, 0.2, 0.9]}},
    "objects": [
      {"type": "quad", "material": "floor", "origin": [-3, -2, 0], "edge_u": [6, 0, 0], "edge_v": [0, 4, 0]},
      {"type": "box", "material": "red", "center": [1.2, 0, 0.2], "size": [0.2, 0.6, 0.4], "yaw_deg": 20},
      {"type": "sphere", "material": "green", "center": [0, 1.0, 0.3], "radius": 0.25},
      {"type": "cylinder", "material": "blue", "base": [-0.8, -0.9, 0], "top": [-0.8, -0.9, 0.9], "radius": 0.1},
      {"type": "disc", "material": "red", "center": [-0.5, 0.6, 0.01], "normal": [0, 0, 1], "radius": 0.3, "inner_radius": 0.1},
      {"type": "mesh", "material": "green", "vertices": [[0.5, -1.2, 0], [1.0, -1.0, 0.6], [0.3, -0.7, 0.3]],
       "triangles": [[0, 1, 2]]}]})",
             f);
  std::fclose(f);
  return loadScene(path);
}

TEST(Povray, AsymmetricTexturedSceneProvesAxesHandednessAndTextures) {
  const auto dir = std::filesystem::temp_directory_path() / ("omnicam_asym_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Scene scene = asymmetricScene(dir.string());
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 160;
  settings.spp = 4;
  const RobotPose pose{0.2, -0.1, 30.0};
  const ImageRGBA ours = FastRenderer(scene).render(pose, settings);
  const ImageRGBA truth = renderWithPovray(scene, pose, settings);
  const CompareResult same = compareImages(ours, truth);
  EXPECT_GE(same.psnrDb, 87.0);  // measured 90.7 dB: a floor 3 dB under it
  // The same comparison against our image mirrored left–right must fail badly: the test can tell.
  ImageRGBA mirrored = ours;
  for (int j = 0; j < ours.height; ++j)
    for (int i = 0; i < ours.width; ++i)
      for (int c = 0; c < 4; ++c) mirrored.at(i, j)[c] = ours.at(ours.width - 1 - i, j)[c];
  EXPECT_LT(compareImages(mirrored, truth).psnrDb, 25.0);
  std::printf("asymmetric scene: PSNR %.2f dB (mirrored: %.2f dB)\n", same.psnrDb,
              compareImages(mirrored, truth).psnrDb);
  std::filesystem::remove_all(dir);
}

// Textures on the curved primitives. POV-Ray has UV for spheres only; a cylinder's comes from a
// cylindrical warp and a disc's from the planar map, placed in each shape's frame. Tilted shapes,
// caps, an annulus and repeats (scale 3 × 2) of a texture with no symmetry: the engines must read
// the same texels, and the fast renderer reading the texture flipped must not pass for it.
Scene texturedCurvedScene(const std::string& dir, bool flipU, bool flipV) {
  ImageRGBA tex(8, 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      const int a = flipU ? 7 - i : i, b = flipV ? 7 - j : j;
      float* p = tex.at(i, j);
      p[0] = 0.1f + 0.1f * a, p[1] = 0.1f + 0.1f * b, p[2] = ((a * 3 + b * 5) % 7) / 7.0f, p[3] = 1.0f;
    }
  const std::string name = std::string("curved_") + (flipU ? "u" : "") + (flipV ? "v" : "");
  writeImageAtomic(dir + "/" + name + ".png", tex);
  const std::string path = dir + "/" + name + ".json";
  std::ofstream(path) << R"({"format": "omnicam-scene/1",
    "materials": {"floor": {"color": [0.5, 0.5, 0.5]},
                  "tex": {"texture": {"file": ")" << name << R"(.png", "scale": [3, 2]}}},
    "objects": [
      {"type": "quad", "material": "floor", "origin": [-3, -3, 0], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]},
      {"type": "sphere", "material": "tex", "center": [0.8, 0.3, 0.35], "radius": 0.3},
      {"type": "cylinder", "material": "tex", "base": [-0.5, -0.6, 0.1], "top": [-0.9, -0.3, 0.8], "radius": 0.18},
      {"type": "disc", "material": "tex", "center": [0.1, -1.0, 0.35], "normal": [0.2, 0.6, 0.7],
       "radius": 0.4, "inner_radius": 0.08},
      {"type": "cylinder", "material": "tex", "base": [-0.3, 1.0, 0.3], "top": [0.3, 1.1, 0.3], "radius": 0.2,
       "caps": false}]})";
  return loadScene(path);
}

// A small room of every shape, `x0`, `y0` metres from the world's origin.
Scene roomAt(const std::string& dir, double x0, double y0) {
  const auto at = [&](double x, double y, double z) {
    return "[" + std::to_string(x0 + x) + ", " + std::to_string(y0 + y) + ", " + std::to_string(z) + "]";
  };
  const std::string path = dir + "/room_" + std::to_string(static_cast<long>(x0)) + ".json";
  std::ofstream(path) << R"({"format": "omnicam-scene/1",
    "start_pose": )" << at(0.3, 0.2, 20.0) << R"(,
    "materials": {"floor": {"color": [0.6, 0.6, 0.6]}, "red": {"color": [0.8, 0.1, 0.1]}, "blue": {"color": [0.1, 0.2, 0.8]}},
    "objects": [
      {"type": "quad", "material": "floor", "origin": )" << at(-3, -3, 0) << R"(, "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]},
      {"type": "box", "material": "red", "center": )" << at(0.9, 0.2, 0.2) << R"(, "size": [0.3, 0.5, 0.4], "yaw_deg": 30},
      {"type": "sphere", "material": "blue", "center": )" << at(-0.7, 0.6, 0.25) << R"(, "radius": 0.25},
      {"type": "cylinder", "material": "red", "base": )" << at(-0.4, -0.9, 0) << R"(, "top": )" << at(-0.4, -0.9, 0.6)
                      << R"(, "radius": 0.1},
      {"type": "disc", "material": "blue", "center": )" << at(0.5, -0.6, 0.002) << R"(, "normal": [0, 0, 1], "radius": 0.2}],
    "lights": [{"name": "lamp", "position": )" << at(0.3, 0.2, 2.0) << R"(, "intensity": 0.9}]})";
  return loadScene(path);
}

// POV-Ray's intersection tolerances and glTF's 32-bit floats lose the mirror far from the origin
// (83 dB fell to 30 dB at 2 km; Blender's lost 11 dB at 1 km in an earlier scene): both ground truths are given a
// world whose origin is near the robot, and agree kilometres out as they do at the origin. So does
// the fast renderer, whose Embree scene counts from the whole metre nearest the scene's start pose
// (at 9 km its world-origin floats had stepped 1 mm: 55 dB against POV-Ray).

TEST(GroundTruths, AgreeKilometresFromTheOriginAsAtIt) {
  const auto dir = std::filesystem::temp_directory_path() / ("omnicam_far_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  RenderSettings settings;
  settings.rig = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig;
  settings.rig.mirrorRig().imageSize = 96;
  settings.spp = 4;
  settings.shading = Shading::Lit;
  std::map<double, std::pair<double, double>> psnr;  // offset → (POV-Ray, Blender) against the fast renderer
  for (const double offset : {0.0, 2000.0, 9000.0}) {
    const Scene scene = roomAt(dir.string(), offset, -offset);
    const RobotPose pose{offset + 0.3, -offset + 0.2, 20.0};
    const ImageRGBA ours = FastRenderer(scene).render(pose, settings);
    RenderSettings unlit = settings;
    unlit.shading = Shading::Unlit;  // Blender lit is not a pixel comparison
    psnr[offset] = {compareImages(ours, renderWithPovray(scene, pose, settings)).psnrDb,
                    compareImages(FastRenderer(scene).render(pose, unlit), renderWithBlender(scene, {pose}, unlit).front()).psnrDb};
    std::printf("%.0f m from the origin: fast vs POV-Ray %.2f dB, fast vs Blender %.2f dB\n", offset, psnr[offset].first,
                psnr[offset].second);
  }
  std::filesystem::remove_all(dir);
  EXPECT_GE(psnr[0.0].first, 70.0);
  EXPECT_GE(psnr[0.0].second, 35.0);  // Blender's triangulated shapes and 32-bit floats
  for (const double far : {2000.0, 9000.0}) {
    EXPECT_NEAR(psnr[far].first, psnr[0.0].first, 1.0) << far << " m out";
    EXPECT_NEAR(psnr[far].second, psnr[0.0].second, 1.0) << far << " m out";
  }
}

TEST(Povray, TexturedSphereCylinderAndDiscReadTheFastRenderersTexels) {
  const auto dir = std::filesystem::temp_directory_path() / ("omnicam_curved_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const Scene scene = texturedCurvedScene(dir.string(), false, false);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 160;
  settings.spp = 4;
  settings.shading = Shading::Unlit;
  const RobotPose pose{0.0, 0.0, 20.0};
  const ImageRGBA truth = renderWithPovray(scene, pose, settings);
  const double same = compareImages(FastRenderer(scene).render(pose, settings), truth).psnrDb;
  const double flippedU =
      compareImages(FastRenderer(texturedCurvedScene(dir.string(), true, false)).render(pose, settings), truth).psnrDb;
  const double flippedV =
      compareImages(FastRenderer(texturedCurvedScene(dir.string(), false, true)).render(pose, settings), truth).psnrDb;
  std::printf("textured sphere, cylinders and disc, fast vs POV-Ray: PSNR %.2f dB (texture flipped in u: %.2f dB, "
              "in v: %.2f dB)\n", same, flippedU, flippedV);
  EXPECT_GE(same, 60.0);
  EXPECT_LT(flippedU, 40.0);
  EXPECT_LT(flippedV, 40.0);
  std::filesystem::remove_all(dir);
}

// The documented rig ranges (input_limits.h, docs/robustness.md) are where both engines still
// agree: at their corners POV-Ray's millimetre scene and the fast renderer give the same image,
// and the image is not black.
TEST(Povray, RigRangeCornersRenderTheSameInBothEngines) {
  const Scene base = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  struct Corner {
    const char* label;
    double k, c, height;
  };
  for (const Corner& corner : {Corner{"smallest mirror, lowest rig, largest k", 100.0, 0.001, 0.01},
                               Corner{"largest mirror, highest rig, small k", 5.0, 1.0, 100.0},
                               Corner{"largest mirror and k", 100.0, 1.0, 1.5},
                               Corner{"thesis mirror, highest rig", 11.546, 0.02321, 100.0}}) {
    Scene scene = base;
    // From 100 m up the field fills less than a pixel: a sky colour makes every ray count.
    scene.background = Vec3f(0.2f, 0.3f, 0.4f);
    scene.rig.mirrorRig().hyperboloid().k = corner.k, scene.rig.mirrorRig().hyperboloid().c = corner.c, scene.rig.height = corner.height;
    scene.rig.mirrorRig().imageSize = 64;
    const FastRenderer fast(scene);
    RenderSettings settings;
    settings.rig = scene.rig;
    settings.spp = 4;
    const RobotPose pose{0.3, -0.2, 30.0};
    const ImageRGBA ours = fast.render(pose, settings);
    const ImageRGBA truth = renderWithPovray(scene, pose, settings);
    const CompareResult r = compareImages(ours, truth);
    double mean = 0.0;
    for (size_t p = 0; p < truth.pixels.size(); p += 4) mean += truth.pixels[p + 2];
    mean /= truth.pixels.size() / 4.0;
    std::printf("rig corner (%s): k %g c %g m height %g m: PSNR %.2f dB, POV-Ray mean blue %.3f\n", corner.label,
                corner.k, corner.c, corner.height, r.psnrDb, mean);
    EXPECT_GE(r.psnrDb, 81.0) << corner.label;  // measured 84.3–84.6 dB: a floor 3 dB under them
    EXPECT_GT(mean, 0.1) << corner.label << ": POV-Ray image is (nearly) black";
  }
}

// Job folders of killed runs do not pile up: the next run removes those whose owner is gone.
TEST(JobFolders, StaleFoldersOfDeadProcessesAreRemoved) {
  namespace fs = std::filesystem;
  const pid_t dead = ::fork();
  if (dead == 0) ::_exit(0);
  ASSERT_GT(dead, 0);
  ::waitpid(dead, nullptr, 0);  // reaped: this pid now names no process
  const auto make = [](const std::string& name, const std::string& owner) {
    const fs::path folder = fs::temp_directory_path() / name;
    fs::create_directories(folder);
    if (!owner.empty()) std::ofstream(folder / "owner.pid") << owner << "\n";
    std::ofstream(folder / "render.exr") << "partial";
    return folder;
  };
  const fs::path stale = make("omnicam-testjob-stale1", std::to_string(dead));
  const fs::path alive = make("omnicam-testjob-alive1", "1");           // init: alive
  const fs::path unknown = make("omnicam-testjob-nopid1", "");          // not ours to judge
  const fs::path other = make("omnicam-otherjob-stale", std::to_string(dead));  // another prefix
  // A pid means something on its own machine and pid namespace only (a TMPDIR on shared scratch, containers
  // sharing /tmp): another's folder is never judged here; this one's is.
  char host[256] = {};
  ASSERT_EQ(::gethostname(host, sizeof host - 1), 0);
  const std::string here = std::string(host) + " " + fs::read_symlink("/proc/self/ns/pid").string();
  const fs::path elsewhere = make("omnicam-testjob-host01", std::to_string(dead) + "\nanother-host pid:[4026531836]");
  const fs::path staleHere = make("omnicam-testjob-here01", std::to_string(dead) + "\n" + here);
  EXPECT_EQ(removeStaleJobFolders("omnicam-testjob"), 2);
  EXPECT_FALSE(fs::exists(stale));
  EXPECT_FALSE(fs::exists(staleHere));
  EXPECT_TRUE(fs::exists(alive));
  EXPECT_TRUE(fs::exists(unknown));
  EXPECT_TRUE(fs::exists(other));
  EXPECT_TRUE(fs::exists(elsewhere));
  for (const auto& f : {alive, unknown, other, elsewhere}) fs::remove_all(f);
  {
    const JobFolder job("omnicam-testjob", false);
    std::ifstream in(fs::path(job.path()) / "owner.pid");
    long pid = 0;
    std::string place;
    in >> pid >> std::ws;
    std::getline(in, place);
    EXPECT_EQ(pid, ::getpid());
    EXPECT_EQ(place, here);
  }
}

}  // namespace
}  // namespace omnicam
