// Second ground truth: Blender Cycles looking into the certified mirror mesh (docs/conventions.md §7).
#include "blender_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>

#include "atomic_file.h"
#include "exr_channels.h"

#include "errors.h"
#include "fast_renderer.h"
#include "gltf_exporter.h"
#include "indirect_filter.h"
#include "image_compare.h"
#include "povray_renderer.h"
#include "rings.h"
#include "scene_loader.h"
#include "scratch_folder.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

TEST(Blender, AgreesWithTheFastRendererUnlitAt64Spp) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.spp = 64;
  const std::vector<RobotPose> poses{{2.7, -1.8, 180.0}, {1.0, -1.5, 137.0}};
  const BlenderFrames session = renderWithBlenderTimed(scene, {poses[0], poses[1]}, settings);  // one Blender session
  const std::vector<ImageRGBA>& truth = session.images;
  ASSERT_EQ(truth.size(), poses.size());
  // The session says what each frame's render took inside it; the rest is its start-up.
  const BlenderTimings& t = session.timings;
  ASSERT_EQ(t.frameSeconds.size(), poses.size());
  for (double seconds : t.frameSeconds) EXPECT_GT(seconds, 0.0);
  EXPECT_GT(t.startupSeconds(), 0.0);
  EXPECT_DOUBLE_EQ(t.startupSeconds() + t.frameSeconds[0] + t.frameSeconds[1], t.sessionSeconds);
  EXPECT_DOUBLE_EQ(t.batchedFrameSeconds(), t.frameSeconds[1]);
  const FastRenderer fast(scene);
  for (size_t k = 0; k < poses.size(); ++k) {
    const CompareResult r = compareImages(fast.render(poses[k], settings), truth[k]);
    std::printf("fast vs Blender, pose (%.2f, %.2f, %.0f), unlit, 64 spp: PSNR %.2f dB, SSIM %.5f\n", poses[k].x,
                poses[k].y, poses[k].yawDeg, r.psnrDb, r.ssim);
    // Measured 55.9 and 54.7 dB (Cycles' seed is fixed): a floor 3 dB under them, well above
    // the 35 dB target of docs/conventions.md §7, so that a regression shows.
    EXPECT_GE(r.psnrDb, 52.0);
  }
}

// Unlit and lit keep the scene's background (docs/conventions.md §3): rays that hit nothing, seen
// directly or in the mirror, see it in Blender as in the fast renderer. A floor under a blue sky.
TEST(Blender, UnlitAndLitFramesSeeTheBackgroundWhereRaysHitNothing) {
  const Scene scene = loadSceneFromText(R"({"format": "omnicam-scene/1", "background": [0.1, 0.1, 0.3],
    "materials": {"g": {"color": 0.5, "ambient": 0.3}},
    "objects": [{"type": "quad", "material": "g", "origin": [-5, -5, 0], "edge_u": [10, 0, 0], "edge_v": [0, 10, 0]}],
    "lights": [{"name": "lamp", "position": [1, 1, 3], "intensity": 0.8}]})",
                                        "sky.json");
  RenderSettings settings;
  settings.rig = scene.rig.resized(96);
  settings.spp = 64;
  const FastRenderer fast(scene);
  for (Shading shading : {Shading::Unlit, Shading::Lit}) {
    settings.shading = shading;
    const ImageRGBA truth = renderWithBlender(scene, {RobotPose{}}, settings).front();
    const ImageRGBA mine = fast.render(RobotPose{}, settings);
    // The pixel just inside the rim on the right looks up past the horizon: the sky.
    const float* sky = mine.at(88, 48);
    ASSERT_NEAR(sky[2], 0.3f, 1e-6f) << "not the sky: pick another pixel";
    EXPECT_NEAR(truth.at(88, 48)[2], 0.3f, 0.02f) << shadingName(shading);
    const CompareResult r = compareImages(mine, truth);
    std::printf("fast vs Blender, blue sky, %s, 64 spp: PSNR %.2f dB\n", shadingName(shading), r.psnrDb);
    // docs/conventions.md §7 holds Blender to 35 dB unlit (measured 49 dB here; 16 dB when Blender's
    // sky was black); lit has no Blender target (Cycles' lamps are not omnicam's point lights).
    if (shading == Shading::Unlit) {
      EXPECT_GE(r.psnrDb, 35.0);
    }
  }
}

// A frame's cost in a batch is the frames after the first (whose render also builds what later
// frames reuse); the start-up is the session less its frames.
TEST(BlenderTimings, ABatchedFrameIsTheMeanAfterTheFirst) {
  const BlenderTimings three{10.0, {4.0, 1.0, 2.0}};
  EXPECT_DOUBLE_EQ(three.startupSeconds(), 3.0);
  EXPECT_DOUBLE_EQ(three.batchedFrameSeconds(), 1.5);
  EXPECT_DOUBLE_EQ((BlenderTimings{5.0, {4.0}}).batchedFrameSeconds(), 4.0);
  EXPECT_DOUBLE_EQ(BlenderTimings{}.batchedFrameSeconds(), 0.0);
}

// A driver need not time its frames (OMNICAM_BLENDER_DRIVER may name another): the images are
// rendered all the same, and only the timed render says that the times are missing.
TEST(Blender, ADriverWithoutFrameTimesStillRendersAndOnlyTheTimedRenderSaysSo) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_untimed_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const std::string driver = (dir / "untimed_driver.py").string();
  std::ofstream(driver) << "import json, runpy, sys\n"
                           "path = sys.argv[sys.argv.index('--') + 1]\n"
                           "job = json.load(open(path))\n"
                           "job.pop('timings_output')\n"
                           "json.dump(job, open(path, 'w'))\n"
                           "runpy.run_path('" OMNICAM_SOURCE_DIR "/refrender/blender_driver.py', run_name='__main__')\n";
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig.resized(32);
  settings.spp = 1;
  BlenderOptions options;
  options.driver = driver;
  EXPECT_EQ(renderWithBlender(scene, {RobotPose{2.7, -1.8, 180.0}}, settings, options).size(), 1u);
  try {
    (void)renderWithBlenderTimed(scene, {RobotPose{2.7, -1.8, 180.0}}, settings, options);
    ADD_FAILURE() << "a session without frame times was timed";
  } catch (const ExternalError& e) {
    EXPECT_NE(std::string(e.what()).find("blender: the driver wrote no frame times (timings.json)"), std::string::npos) << e.what();
  }
  fs::remove_all(dir);
}

// Cycles' own motion blur against the fast renderer's exact arc, for the mirror rig and a lens
// camera: the robot drives 1 m/s at 90 deg/s over a 1/30 s global shutter. The blur must be the
// one of that velocity: the same frame rendered at 2/3 and 3/2 of it must both be further off (a
// driver whose keys Blender merged blurred 1.5x too long and still passed a bare PSNR floor).
struct MovingRig {
  const char* label;
  RigSpec rig;
};

void PrintTo(const MovingRig& c, std::ostream* os) { *os << c.label; }

class CyclesMotionBlur : public ::testing::TestWithParam<MovingRig> {};

TEST_P(CyclesMotionBlur, IsTheBlurOfTheGivenVelocity) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  RenderSettings settings;
  settings.rig = GetParam().rig;
  settings.rig.shutter.exposureS = 1.0 / 30.0;
  settings.spp = 64;
  const RobotPose pose{1.0, -1.5, 137.0};
  const BodyVelocity velocity{1.0, 0.0, 90.0};
  const ImageRGBA truth = renderWithBlender(scene, {CameraPlacement(pose, velocity)}, settings).front();
  const auto psnrAt = [&](double scale) {
    const BodyVelocity scaled{velocity.vx * scale, velocity.vy * scale, velocity.yawRateDegPerS * scale};
    return compareImages(fast.render(CameraPlacement(pose, scaled), settings), truth).psnrDb;
  };
  const double atVelocity = psnrAt(1.0), slower = psnrAt(2.0 / 3.0), faster = psnrAt(1.5);
  const double fromStill = compareImages(fast.render(pose, settings), truth).psnrDb;
  std::printf("fast vs Blender Cycles motion blur, %s, 1 m/s and 90 deg/s over 1/30 s, unlit, 64 spp: PSNR %.2f dB "
              "(at 2/3 of the velocity %.2f dB, at 3/2 %.2f dB, the still robot %.2f dB)\n",
              GetParam().label, atVelocity, slower, faster, fromStill);
  EXPECT_GE(atVelocity, 40.0);  // measured 48.9 dB (mirror) and 43.9 dB (fisheye); the issue asked 35
  EXPECT_GT(atVelocity, slower + 3.0);
  EXPECT_GT(atVelocity, faster + 3.0);
  EXPECT_LT(fromStill, atVelocity - 5.0);  // the blur shows: the still image is clearly further off
}

RigSpec robocupRig() { return loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig; }

RigSpec fisheyeRig() {
  RigSpec rig;
  rig.kind = LensCameraSpec{test::fTheta(FThetaLens::Kind::Equidistant, 40.0, 200.0, 104.5, 70.0), 200, 150, {10.0, 40.0, 30.0}};
  rig.height = 0.3;
  return rig;
}

INSTANTIATE_TEST_SUITE_P(Rigs, CyclesMotionBlur,
                         ::testing::Values(MovingRig{"the thesis' mirror rig", robocupRig()},
                                           MovingRig{"fisheye equidistant 200 deg", fisheyeRig()}),
                         [](const auto& param) { return param.index == 0 ? std::string("mirror") : std::string("fisheye"); });

// Cycles has no rolling shutter omnicam trusts and samples time at random: both are refused.
TEST(Blender, ARollingShutterOrFixedInstantsAreRefused) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.shutter.exposureS = 1.0 / 30.0;
  const CameraPlacement driving(RobotPose{1.0, -1.5, 137.0}, {1.0, 0.0, 90.0});
  RenderSettings rolling = settings;
  rolling.rig.shutter.rolling = RollingShutter{30.0, Readout::TopToBottom};
  EXPECT_THROW(renderWithBlender(scene, {driving}, rolling), InputError);
  RenderSettings instants = settings;
  instants.rig.shutter.timeSamples = 4;
  EXPECT_THROW(renderWithBlender(scene, {driving}, instants), InputError);
}

// The physical camera in Blender: the pinhole moved, turned and with its principal point off,
// placed by the glTF export, looking into the same certified mirror mesh (issue #21: ≥ 35 dB).
TEST(Blender, AgreesWithTheFastRendererOnAMisalignedRig) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().mount.offsetMm = {3.0, -2.0, 1.5};
  settings.rig.mirrorRig().mount.rotationDeg = {2.0, -1.5, 1.0};
  settings.rig.mirrorRig().mount.principalPointOffsetPx = {1.5, -0.75};
  settings.spp = 64;
  const RobotPose pose{2.7, -1.8, 180.0};
  const ImageRGBA truth = renderWithBlender(scene, {pose}, settings).front();
  const FastRenderer fast(scene);
  const CompareResult r = compareImages(fast.render(pose, settings), truth);
  settings.rig = settings.rig.idealized();
  const double fromIdeal = compareImages(fast.render(pose, settings), truth).psnrDb;
  std::printf("fast vs Blender, misaligned 3 mm / 2 deg / principal point off, unlit, 64 spp: PSNR %.2f dB, SSIM %.5f "
              "(the ideal rig's image: %.2f dB)\n", r.psnrDb, r.ssim, fromIdeal);
  EXPECT_GE(r.psnrDb, 35.0);
  EXPECT_LT(fromIdeal, 30.0);  // the misalignment shows: the ideal rig's image is far off this truth
}

// The sphere (non-central: every ray from its own mirror point), its pinhole moved and turned, in
// Blender through its certified cap mesh (issue #21: ≥ 35 dB at 64 spp).
TEST(Blender, AgreesWithTheFastRendererOnAMisalignedSphere) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().shape = SphereMirror{0.03, 60.0, 0.12};
  settings.rig.mirrorRig().mount.offsetMm = {2.0, -1.0, 1.0};
  settings.rig.mirrorRig().mount.rotationDeg = {1.0, -0.5, 0.5};
  settings.spp = 64;
  const RobotPose pose{2.7, -1.8, 180.0};
  const ImageRGBA truth = renderWithBlender(scene, {pose}, settings).front();
  const FastRenderer fast(scene);
  const CompareResult r = compareImages(fast.render(pose, settings), truth);
  std::printf("fast vs Blender, sphere, moved 2 mm / turned 1 deg, unlit, 64 spp: PSNR %.2f dB, SSIM %.5f\n", r.psnrDb, r.ssim);
  EXPECT_GE(r.psnrDb, 35.0);
}

TEST(Blender, ALensIsRefusedNotIgnored) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().mount.distortion.k1 = -0.05;
  EXPECT_THROW(renderWithBlender(scene, {RobotPose{}}, settings), InputError);
}

// With no bounce after the first surface, the full render and its direct-light twin are the same
// samples (same seed): the filtered frame is the unfiltered one, bit for bit. Were the twin's samples
// other ones, the two would differ by render noise.
TEST(Blender, TheDirectTwinTracesTheSameSamples) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 48;
  settings.spp = 4;
  settings.shading = Shading::Lit;
  BlenderOptions options;
  options.pathTracing.diffuseBounces = 0;
  options.pathTracing.glossyBounces = 1;
  const ImageRGBA traced = renderWithBlender(scene, {scene.startPose}, settings, options).front();
  options.pathTracing.filterIndirect = true;
  const ImageRGBA filtered = renderWithBlender(scene, {scene.startPose}, settings, options).front();
  double mean = 0.0;
  for (size_t p = 0; p < traced.pixels.size(); p += 4) mean += traced.pixels[p];
  EXPECT_GT(mean, 1.0) << "nothing was lit";
  EXPECT_EQ(filtered.pixels, traced.pixels);
}

// What blender_driver.py writes with direct_pass, made here: a multilayer OpenEXR named as Cycles
// names it (the view layer's name may be any) and a plain RGB twin.
void writeExr(const std::string& path, const std::vector<std::string>& channels, int size, float base) {
  std::vector<float> data(static_cast<size_t>(size) * size * channels.size());
  for (size_t k = 0; k < data.size(); ++k) data[k] = base + 0.001f * static_cast<float>(k % 97);
  std::vector<ExrChannelSource> sources;
  for (size_t c = 0; c < channels.size(); ++c) sources.push_back({channels[c], ExrSampleType::Float, data.data() + c, nullptr, channels.size()});
  const std::vector<unsigned char> bytes = encodeExrChannels(path, size, size, sources, {});
  writeBytesAtomically(path, std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()));
}

TEST(Blender, TheDirectPassFramesAreReadByChannelName) {
  const test_support::ScratchFolder scratch("direct_pass_read");
  const fs::path& dir = scratch.path();
  const std::string full = (dir / "full.exr").string(), direct = (dir / "direct.exr").string();
  const std::vector<std::string> passes = {"Hall.Combined.R", "Hall.Combined.G", "Hall.Combined.B", "Hall.Combined.A",
                                           "Hall.Denoising Albedo.R", "Hall.Denoising Albedo.G", "Hall.Denoising Albedo.B",
                                           "Hall.Denoising Depth.Z", "Hall.Denoising Normal.X", "Hall.Denoising Normal.Y",
                                           "Hall.Denoising Normal.Z"};
  writeExr(full, passes, 16, 0.5f);
  writeExr(direct, {"R", "G", "B"}, 16, 0.2f);
  // The same inputs, assembled by hand from the values writeExr put in each channel.
  IndirectFilterInputs in;
  in.full = ImageRGBA(16, 16);
  in.direct = ImageRGBA(16, 16);
  for (size_t p = 0; p < 256; ++p) {
    auto value = [&](size_t channel, size_t count, float base) { return base + 0.001f * static_cast<float>((p * count + channel) % 97); };
    for (size_t c = 0; c < 3; ++c) {
      in.full.pixels[4 * p + c] = value(c, passes.size(), 0.5f);
      in.direct.pixels[4 * p + c] = value(c, 3, 0.2f);
      in.albedo.push_back(value(4 + c, passes.size(), 0.5f));
    }
    in.depth.push_back(value(7, passes.size(), 0.5f));
    for (size_t c = 0; c < 3; ++c) in.normal.push_back(value(8 + c, passes.size(), 0.5f));
  }
  EXPECT_EQ(readFilteredBlenderFrame(full, direct, 16, 16).pixels, filterIndirectLight(in).pixels);
  EXPECT_THROW(readFilteredBlenderFrame(full, direct, 32, 32), ExternalError);           // another size
  EXPECT_THROW(readFilteredBlenderFrame(direct, direct, 16, 16), ExternalError);         // no passes
  EXPECT_THROW(readFilteredBlenderFrame(full, (dir / "none.exr").string(), 16, 16), ExternalError);
  fs::remove_all(dir);
}

TEST(Blender, ObjectsNamedLikeTheRigOrLightsDoNotConfuseTheDriver) {
  // The driver finds the rig by extras roles and lights by index: user objects called
  // "omnicam_rig" / "omnicam_camera" and a light whose name an object would take in Blender
  // change nothing. Unlit: pixel-compared with the fast renderer; lit: every light is found
  // (the driver fails loudly otherwise) and lights the scene.
  const fs::path dir = fs::temp_directory_path() / ("omnicam_names_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "s.json") << R"({"format": "omnicam-scene/1",
    "materials": {"grey": {"color": 0.6}, "red": {"color": [0.8, 0.1, 0.1]}, "omnicam_perfect_mirror": {"color": [0.1, 0.1, 0.8]}},
    "objects": [{"name": "omnicam_rig", "type": "quad", "material": "grey", "origin": [-3, -3, 0], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]},
                {"name": "omnicam_camera", "type": "box", "material": "red", "center": [1, 0.3, 0.2], "size": [0.3, 0.3, 0.4]},
                {"name": "omnicam_mirror", "type": "box", "material": "omnicam_perfect_mirror", "center": [-0.8, -0.6, 0.2], "size": [0.3, 0.3, 0.4]}],
    "lights": [{"name": "lamp", "position": [0, 0, 2.5], "intensity": 0.8}, {"name": "lamp.001", "position": [2, 2, 2.5], "intensity": 0.4}],
    "start_pose": [0, 0, 0]})";
  const Scene scene = loadScene((dir / "s.json").string());
  fs::remove_all(dir);
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 96;
  settings.spp = 64;
  const ImageRGBA truth = renderWithBlender(scene, {scene.startPose}, settings).front();
  const CompareResult r = compareImages(FastRenderer(scene).render(scene.startPose, settings), truth);
  std::printf("fast vs Blender, objects named omnicam_*: PSNR %.2f dB\n", r.psnrDb);
  EXPECT_GE(r.psnrDb, 53.0);  // measured 56.1 dB
  settings.shading = Shading::Lit;
  settings.spp = 4;
  const ImageRGBA lit = renderWithBlender(scene, {scene.startPose}, settings).front();
  double mean = 0.0;
  for (size_t p = 0; p < lit.pixels.size(); p += 4) mean += lit.pixels[p];
  EXPECT_GT(mean / (lit.pixels.size() / 4), 0.02) << "the lights were not found";
}

TEST(Blender, RingImageMatchesTheExactModel) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/incidence-rings.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.spp = 64;
  const ImageRGBA image = renderWithBlender(scene, {scene.startPose}, settings).front();
  const RingReport r = measureRings(image, settings.rig.camera(), defaultRingThetasDeg());
  std::printf("Blender rings: RMS %.4f px, max %.4f px, Eq. 3.2 MSE %.4f px^2\n", r.rmsPxExact, r.maxAbsPxExact,
              r.msePx2Eq32);
  // Measured RMS 0.0104 px, max 0.0235 px: bounds about twice that, under the 0.1 px target of
  // docs/conventions.md §7, so that a regression shows.
  EXPECT_LE(r.rmsPxExact, 0.02);
  EXPECT_LE(r.maxAbsPxExact, 0.05);
}

TEST(Blender, AGltfArenaIsRenderedAlikeByAllThreeEngines) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_arena_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  // An arena authored as glTF (here: exported from a JSON scene), then used by reference.
  ImageRGBA tex(8, 8);
  for (int j = 0; j < 8; ++j)
    for (int i = 0; i < 8; ++i) {
      float* p = tex.at(i, j);
      p[0] = ((i + j) % 2) ? 0.8f : 0.1f, p[1] = 0.1f * j, p[2] = 0.1f * i, p[3] = 1.0f;
    }
  writeImageAtomic((dir / "checker.png").string(), tex);
  std::ofstream(dir / "source.json") << R"({"format": "omnicam-scene/1",
    "materials": {"floor": {"texture": {"file": "checker.png", "scale": [4, 4]}}, "wall": {"color": [0.2, 0.4, 0.8]}},
    "objects": [{"name": "floor", "type": "quad", "material": "floor", "origin": [-2, -2, 0], "edge_u": [4, 0, 0], "edge_v": [0, 4, 0]},
                {"name": "wall", "type": "box", "material": "wall", "center": [0.9, 0.3, 0.25], "size": [0.1, 1.2, 0.5]}]})";
  GltfExportOptions options;
  options.includeRig = false;
  exportGltf(loadScene((dir / "source.json").string()), options, (dir / "arena.glb").string());
  std::ofstream(dir / "scene.json") << R"({"format": "omnicam-scene/1", "materials": {},
    "objects": [{"name": "arena", "type": "gltf", "file": "arena.glb"}]})";
  const Scene scene = loadScene((dir / "scene.json").string());
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 120;
  settings.spp = 16;
  const RobotPose pose{0.1, -0.2, 25.0};
  const ImageRGBA fast = FastRenderer(scene).render(pose, settings);
  const CompareResult povray = compareImages(fast, renderWithPovray(scene, pose, settings));
  const CompareResult blender = compareImages(fast, renderWithBlender(scene, {pose}, settings).front());
  std::printf("glTF arena: fast vs POV-Ray %.2f dB, fast vs Blender (16 spp) %.2f dB\n", povray.psnrDb, blender.psnrDb);
  EXPECT_GE(povray.psnrDb, 87.0);   // measured 90.8 dB (target 45 dB)
  // Measured 49.1 dB (34.7 dB while Cycles blended the checker's texels in sRGB, before the job gave
  // it linear EXRs).
  EXPECT_GE(blender.psnrDb, 46.0);
  fs::remove_all(dir);
}

// A texture magnified over many pixels is interpolated between its texels in linear light in every
// engine. The glTF carries 8-bit sRGB PNGs, which Cycles
// interpolates before linearising: before the job gave Blender the linear texels, this frame was
// 26.6 dB from the fast renderer's (halfway between texels of 0.02 and 0.9 came out 0.27, not 0.46).
TEST(Blender, AMagnifiedTextureIsInterpolatedInLinearLight) {
  const test_support::ScratchFolder dir("omnicam_linear_texture");
  ImageRGBA texels(4, 4);
  for (int j = 0; j < 4; ++j)
    for (int i = 0; i < 4; ++i) {
      float* p = texels.at(i, j);
      const float v = ((i + j) % 2) ? 0.9f : 0.02f;
      p[0] = v, p[1] = 0.5f * v + 0.1f * j, p[2] = (i == 1 && j == 2) ? 0.0031f : v, p[3] = 1.0f;
    }
  writeImageAtomic(dir.file("texels.exr"), texels);
  std::ofstream(dir.path() / "scene.json") << R"({"format": "omnicam-scene/1",
    "materials": {"floor": {"texture": {"file": "texels.exr", "scale": [1.5, 1.5]}}},
    "objects": [{"name": "floor", "type": "quad", "material": "floor", "origin": [-3, -3, 0], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]}]})";
  const Scene scene = loadScene(dir.file("scene.json"));
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 96;
  settings.spp = 64;
  const RobotPose pose{0.2, -0.1, 15.0};
  const ImageRGBA fast = FastRenderer(scene).render(pose, settings);
  const CompareResult blender = compareImages(fast, renderWithBlender(scene, {pose}, settings).front());
  std::printf("magnified linear texture: fast vs Blender (64 spp) %.2f dB, max abs %.4f\n", blender.psnrDb, blender.maxAbs);
  EXPECT_GE(blender.psnrDb, 55.0);  // measured 59.9 dB (26.6 dB before)
}

// Calibration targets are generated textures: POV-Ray and Blender get them as every other texture.
TEST(Blender, CalibrationTargetsAreRenderedAlikeByAllThreeEngines) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_targets_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "scene.json") << R"({"format": "omnicam-scene/1", "materials": {"floor": {"color": [0.2, 0.5, 0.2]}},
    "objects": [{"name": "floor", "type": "quad", "material": "floor", "origin": [-3, -3, 0], "edge_u": [6, 0, 0], "edge_v": [0, 6, 0]},
      {"name": "grid", "type": "calibration_target", "origin": [0.6, 0.35, 0.1], "x_axis": [0, -1, 0], "y_axis": [0, 0, 1],
       "pattern": {"kind": "aprilgrid", "tag_rows": 6, "tag_columns": 6, "tag_size": 0.088, "tag_spacing": 0.3}},
      {"name": "chess", "type": "calibration_target", "origin": [-0.8, -0.2, 0.2], "x_axis": [0, 1, 0], "y_axis": [0, 0, 1],
       "pattern": {"kind": "checkerboard", "rows": 7, "columns": 10, "square": 0.05}}]})";
  const Scene scene = loadScene((dir / "scene.json").string());
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 160;
  settings.spp = 16;
  const RobotPose pose{0.0, 0.0, 10.0};
  const ImageRGBA fast = FastRenderer(scene).render(pose, settings);
  const CompareResult povray = compareImages(fast, renderWithPovray(scene, pose, settings));
  const CompareResult blender = compareImages(fast, renderWithBlender(scene, {pose}, settings).front());
  std::printf("calibration targets: fast vs POV-Ray %.2f dB, fast vs Blender (16 spp) %.2f dB\n", povray.psnrDb, blender.psnrDb);
  EXPECT_GE(povray.psnrDb, 88.0);   // measured 93.2 dB
  EXPECT_GE(blender.psnrDb, 35.0);  // measured 38.2 dB: 16 spp of random samples in the pixel (37.6 with sRGB texels)
  fs::remove_all(dir);
}

}  // namespace
}  // namespace omnicam

namespace omnicam {
namespace {

// Both engines' path-traced frames of `scene` at 64 px and 1024 spp: the fast frame's mean over
// Cycles', and their PSNR (linear, peak 1).
struct PathAgreement {
  double meanRatio = 0.0, psnrDb = 0.0;
};
PathAgreement pathAgreementWithCycles(const Scene& scene, const RobotPose& pose) {
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 64;
  settings.spp = 1024;
  settings.shading = Shading::Path;
  const ImageRGBA truth = renderWithBlender(scene, {pose}, settings).front();
  const ImageRGBA fast = FastRenderer(scene).render(pose, settings);
  double sumFast = 0.0, sumTruth = 0.0;
  for (size_t p = 0; p < fast.pixels.size(); p += 4)
    for (int c = 0; c < 3; ++c) {
      sumFast += fast.pixels[p + c];
      sumTruth += truth.pixels[p + c];
    }
  return {sumFast / sumTruth, compareImages(fast, truth).psnrDb};
}

// Path shading means the same light in both engines (docs/conventions.md §3): the tiled room with
// a glowing door (material emission), its lamp a disc luminaire, a second lamp a point, and a
// sky of constant radiance, converged in both. Measured (64 px, 1024 spp each): mean ratio
// fast/Cycles 0.9997; PSNR 37.2 dB (linear, peak 1), its largest errors alternating in sign along
// the edges of tiles lit to radiance 2–3 under the lamp, not in the light itself. (Before the disc
// became one-sided as in Cycles, rays from above ended on its back: 0.9988 and 34.2 dB.)
TEST(Blender, PathShadingConvergesToTheSameFrameAsCycles) {
  Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json");
  for (Material& m : scene.materials)
    if (m.name == "door") m.emission = {3.0f, 2.0f, 1.0f};
  scene.lights[0].diameter = 0.4;
  scene.lights.push_back({"point", {-1.2, 0.9, 1.8}, {0.2f, 0.25f, 0.3f}, 0.0});
  scene.background = {0.05f, 0.07f, 0.1f};
  const PathAgreement r = pathAgreementWithCycles(scene, {0.4, -0.3, 30.0});
  std::printf("fast vs Cycles, path shading, 64 px, 1024 spp each: mean ratio %.4f, PSNR %.2f dB\n", r.meanRatio, r.psnrDb);
  // A convention off (a disc's power, the bounce rule, emission, the sky) moves the mean by
  // several percent; the noise of both frames moves it by well under one.
  EXPECT_NEAR(r.meanRatio, 1.0, 0.005);
  EXPECT_GE(r.psnrDb, 35.0);
}

// An environment is the same sky in both engines (docs/conventions.md §3): the outdoor field lit by
// Blender's city world alone, turned 70° and at 0.7 of its strength, its sun's hard shadows on the
// grass and the sky seen in the mirror. Measured (64 px, 1024 spp each): mean ratio fast/Cycles
// 1.0001, PSNR 50.7 dB (linear, peak 1); a fast frame with the sky turned the other way (−70°)
// was at PSNR −4.5 dB from Cycles' frame (both at full strength).
TEST(Blender, AnEnvironmentLightsBothEnginesAlike) {
  Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/outdoor-field.json");
  ASSERT_TRUE(scene.environment);
  scene.environment->strength = 0.7f;
  const PathAgreement r = pathAgreementWithCycles(scene, {0.3, -0.2, 25.0});
  std::printf("fast vs Cycles under the city sky, 64 px, 1024 spp each: mean ratio %.4f, PSNR %.2f dB\n", r.meanRatio,
              r.psnrDb);
  EXPECT_NEAR(r.meanRatio, 1.0, 0.005);
  EXPECT_GE(r.psnrDb, 45.0);
}

// A closed box whose walls have albedo ρ and emit E, around the rig: with D diffuse bounces the
// radiance everywhere inside is E·(1 − ρ^(D+2))/(1 − ρ), light reflected at most D + 1 times
// (conventions §3; path_tracer_test proves the fast renderer's), whatever the box's shape. The
// mirror's reflection is a glossy bounce on top: Cycles' total bounce cap must not cut the path.
constexpr double kFurnaceAlbedo = 0.8, kFurnaceEmission = 0.2;
double furnaceClosedForm(int bounces) {
  return kFurnaceEmission * (1.0 - std::pow(kFurnaceAlbedo, bounces + 2)) / (1.0 - kFurnaceAlbedo);
}

// The mean radiance of the pixels wholly inside the mirror disc, and its standard error from their
// spread (each pixel an independent mean of its samples).
struct FurnaceReading {
  double mean = 0.0, standardError = 0.0;
};
FurnaceReading discMean(const ImageRGBA& frame) {
  double sum = 0.0, squares = 0.0;
  long count = 0;
  for (size_t p = 0; p < frame.pixels.size(); p += 4) {
    if (frame.pixels[p + 3] < 1.0f) continue;
    const double grey = (frame.pixels[p] + frame.pixels[p + 1] + frame.pixels[p + 2]) / 3.0;
    sum += grey;
    squares += grey * grey;
    ++count;
  }
  if (count < 2) return {};
  const double mean = sum / count;
  return {mean, std::sqrt(std::max(0.0, squares / count - mean * mean) / (count - 1))};
}

struct Furnace {
  Scene scene;
  RenderSettings settings;
  RobotPose pose{0.3, -0.2, 20.0};
};
Furnace furnace(int bounces) {
  Furnace f;
  Material walls;
  walls.name = "walls";
  walls.color = Vec3f::Constant(static_cast<float>(kFurnaceAlbedo));
  walls.emission = Vec3f::Constant(static_cast<float>(kFurnaceEmission));
  f.scene.materials.push_back(walls);
  f.scene.objects.push_back({"box", 0, Box{{0.0, 0.0, 1.0}, {4.0, 3.0, 3.0}, 20.0}, ""});
  f.settings.rig = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json").rig;
  f.settings.rig.mirrorRig().imageSize = 24;
  f.settings.spp = 256;
  f.settings.shading = Shading::Path;
  f.settings.bounces = bounces;
  return f;
}

// Cycles' furnace frames, one Blender session per bounce count, kept for the tests that share them.
const FurnaceReading& cyclesFurnace(int bounces) {
  static std::map<int, FurnaceReading> rendered;
  if (!rendered.count(bounces)) {
    const Furnace f = furnace(bounces);
    rendered[bounces] = discMean(renderWithBlender(f.scene, {f.pose}, f.settings).front());
  }
  return rendered[bounces];
}

// Issue #45: a fixed max_bounces of 8 held Cycles at 7 diffuse bounces (the mirror's reflection
// the eighth): at 12 it read 0.8674, the 7-bounce closed form. Measured now (24 px, 256 spp, the
// disc's pixels): closed form 0.9560, Cycles 0.9575 ± 0.0009 (+0.16 %, the standard error of the
// mean from the pixels' spread), fast (1024 spp) 0.9551 ± 0.0009.
TEST(Blender, CyclesFurnaceAtTwelveBouncesIsWithinHalfAPercentOfItsClosedForm) {
  const double expected = furnaceClosedForm(12);
  const FurnaceReading cycles = cyclesFurnace(12);
  Furnace f = furnace(12);
  f.settings.spp = 1024;  // the fast renderer's paths end sooner (Russian roulette): more of them
  const FurnaceReading fast = discMean(FastRenderer(f.scene).render(f.pose, f.settings));
  std::printf("furnace (albedo 0.8, emission 0.2), 12 bounces: closed form %.4f, Cycles %.4f ± %.4f, fast %.4f ± %.4f\n",
              expected, cycles.mean, cycles.standardError, fast.mean, fast.standardError);
  ASSERT_LT(cycles.standardError, 0.001 * expected) << "too noisy to test anything";
  EXPECT_NEAR(cycles.mean, expected, 0.005 * expected);
  EXPECT_NEAR(fast.mean, expected, 0.005 * expected);
}

// Seven and twelve bounces differ by the light reflected 9 to 14 times, E·(ρ^9 − ρ^14)/(1 − ρ):
// 0.0902. Measured: 7 bounces 0.8674 (closed form 0.8658), difference 0.0901 ± 0.0011; with the
// old cap the two frames were bit-identical.
TEST(Blender, CyclesFurnaceSevenAndTwelveBouncesDifferAsTheClosedFormSays) {
  const FurnaceReading& seven = cyclesFurnace(7);
  const FurnaceReading& twelve = cyclesFurnace(12);
  const double expected = furnaceClosedForm(12) - furnaceClosedForm(7);
  const double error = std::hypot(seven.standardError, twelve.standardError);
  std::printf("Cycles furnace: 7 bounces %.4f (closed form %.4f), 12 bounces %.4f; difference %.4f ± %.4f, closed form %.4f\n",
              seven.mean, furnaceClosedForm(7), twelve.mean, twelve.mean - seven.mean, error, expected);
  EXPECT_NEAR(seven.mean, furnaceClosedForm(7), 0.005 * furnaceClosedForm(7));
  EXPECT_NEAR(twelve.mean - seven.mean, expected, 4.0 * error);
}

}  // namespace
}  // namespace omnicam
