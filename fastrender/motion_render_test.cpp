// The fast renderer under motion (docs/motion.md) against closed forms and an independent
// per-sample renderer built from the camera interface, the SE(2) motion and the shutter's times.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>

#include "aov_renderer.h"
#include "fast_renderer.h"
#include "make_camera.h"
#include "scene_loader.h"
#include "thread_count_testing.h"
#include "placement.h"
#include "film.h"

namespace omnicam {
namespace {

const Scene& robocup() {
  static const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return s;
}

// 1 m/s forward while turning at 90°/s: the thesis loop's pace.
constexpr BodyVelocity kDriving{1.0, 0.0, 90.0};
const RobotPose kStart{0.4, -0.3, 20.0};
const CameraPlacement kDrivingFromStart(kStart, kDriving);

RenderSettings settingsOf(int size, int spp, const Shutter& shutter, bool physical = false) {
  RenderSettings settings;
  settings.rig = robocup().rig.resized(size);
  if (physical) settings.rig.mirrorRig().mount.offsetMm = {1.5, -1.0, 2.0};
  settings.rig.shutter = shutter;
  settings.spp = spp;
  return settings;
}

bool bitIdentical(const std::vector<float>& a, const std::vector<float>& b) {
  return a.size() == b.size() && std::memcmp(a.data(), b.data(), a.size() * sizeof(float)) == 0;
}

double maxAbsDifference(const ImageRGBA& a, const ImageRGBA& b) {
  double worst = 0.0;
  for (size_t k = 0; k < a.pixels.size(); ++k) worst = std::max(worst, std::abs(double{a.pixels[k]} - b.pixels[k]));
  return worst;
}

TEST(MotionRender, AStillRobotGivesTheStaticImageBitForBitWhateverTheShutter) {
  const FastRenderer renderer(robocup());
  const RenderSettings still = settingsOf(96, 4, Shutter{});
  AovFrame staticAovs;
  const ImageRGBA staticImage = renderer.render(kStart, still, staticAovs);
  for (const Shutter& shutter : {Shutter{0.02, std::nullopt, 0}, Shutter{0.02, std::nullopt, 3},
                                 Shutter{0.01, RollingShutter{40.0, Readout::LeftToRight}, 0}}) {
    AovFrame aovs;
    const ImageRGBA image = renderer.render(kStart, settingsOf(96, 4, shutter), aovs);
    EXPECT_TRUE(bitIdentical(image.pixels, staticImage.pixels));
    EXPECT_EQ(aovs.depth, staticAovs.depth);
    EXPECT_EQ(aovs.instance, staticAovs.instance);
  }
  // And a moving robot with an instantaneous global shutter is the static image at its pose.
  EXPECT_TRUE(bitIdentical(renderer.render(kDrivingFromStart, settingsOf(96, 4, Shutter{})).pixels, staticImage.pixels));
}

TEST(MotionRender, AFrameOfFixedInstantsIsTheMeanOfStaticFramesAtThem) {
  const FastRenderer renderer(robocup());
  for (bool physical : {false, true}) {
    const Shutter shutter{0.04, std::nullopt, 4};
    const ImageRGBA blurred = renderer.render(kDrivingFromStart, settingsOf(96, 4, shutter, physical));
    ImageRGBA mean(96, 96);
    for (int m = 0; m < 4; ++m) {
      const RobotPose pose = poseAfter(kStart, kDriving, instantTime(shutter, m, 4));
      const ImageRGBA frame = renderer.render(pose, settingsOf(96, 4, Shutter{}, physical));
      for (size_t k = 0; k < mean.pixels.size(); ++k) mean.pixels[k] += frame.pixels[k] / 4.0f;
    }
    EXPECT_LT(maxAbsDifference(blurred, mean), 2e-6) << (physical ? "physical" : "ideal");
    // The blur is there: the frame differs from the static one at its start by far more.
    EXPECT_GT(maxAbsDifference(blurred, renderer.render(kStart, settingsOf(96, 4, Shutter{}, physical))), 0.1);
  }
}

TEST(MotionRender, ARollingShutterReadsEachLineAtItsOwnPose) {
  // No exposure, one instant per line: line l is the static image at the pose of time l · line
  // time, row by row (or column by column), exactly.
  const FastRenderer renderer(robocup());
  for (Readout readout : {Readout::TopToBottom, Readout::BottomToTop, Readout::LeftToRight, Readout::RightToLeft}) {
    const Shutter shutter{0.0, RollingShutter{250.0, readout}, 0};
    const RenderSettings settings = settingsOf(48, 4, shutter);
    const ImageRGBA rolled = renderer.render(kDrivingFromStart, settings);
    bool allEqual = true;
    for (int line = 0; line < 48; ++line) {
      const ImageRGBA at = renderer.render(poseAfter(kStart, kDriving, lineStart(shutter, line)), settingsOf(48, 4, Shutter{}));
      for (int j = 0; j < 48; ++j)
        for (int i = 0; i < 48; ++i)
          if (lineOf(shutter, i, j, 48, 48) == line)
            for (int c = 0; c < 4; ++c) allEqual = allEqual && rolled.at(i, j)[c] == at.at(i, j)[c];
    }
    EXPECT_TRUE(allEqual) << readoutName(readout);
  }
}

// The stratified frame, sample by sample, from the camera interface: each sample's ray at its own
// instant, traced by the renderer's radiance() one at a time.
ImageRGBA perSampleReference(const FastRenderer& renderer, const RenderSettings& settings) {
  const auto camera = makeCamera(settings.rig);
  const int n = *samplesPerAxis(settings.spp), size = settings.rig.mirrorRig().imageSize;
  const Shutter& shutter = settings.rig.shutter;
  const PixelInstants instants = pixelInstants(shutter, n);
  ImageRGBA out(size, size);
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      Vec3f sum = Vec3f::Zero();
      int inside = 0;
      for (int pass = 0; pass < instants.passes; ++pass)
        for (int b = 0; b < n; ++b)
          for (int a = 0; a < n; ++a) {
            const auto ray = camera->generateRay({Film::sample(i, j, a, b, n)});
            if (!ray) continue;
            const double t = lineStart(shutter, lineOf(shutter, i, j, size, size)) +
                             instantTime(shutter, instantOf(shutter, a, b, n, pass), instants.count);
            const Rigid worldFromView = CameraPlacement(poseAfter(kStart, kDriving, t)).worldFromViewpoint(settings.rig);
            sum += renderer.radiance(worldFromView * ray->origin, worldFromView.linear() * ray->direction, settings.shading);
            inside += pass == 0;
          }
      for (int c = 0; c < 3; ++c) out.at(i, j)[c] = sum[c] / static_cast<float>(n * n * instants.passes);
      out.at(i, j)[3] = static_cast<float>(inside) / static_cast<float>(n * n);
    }
  return out;
}

TEST(MotionRender, StratifiedAndRollingFramesMatchAPerSampleRenderer) {
  const FastRenderer renderer(robocup());
  const Shutter shutters[] = {{0.03, std::nullopt, 0}, {0.01, RollingShutter{300.0, Readout::TopToBottom}, 0},
                              {0.01, RollingShutter{300.0, Readout::RightToLeft}, 2}};
  for (const Shutter& shutter : shutters)
    for (bool physical : {false, true}) {
      const RenderSettings settings = settingsOf(40, 9, shutter, physical);
      const ImageRGBA fast = renderer.render(kDrivingFromStart, settings);
      EXPECT_LT(maxAbsDifference(fast, perSampleReference(renderer, settings)), 1e-4)
          << shutter.exposureS << (shutter.rolling ? " rolling" : " global") << (physical ? " physical" : " ideal");
    }
}

TEST(MotionRender, AovsArePointSamplesAtEachPixelsOwnTime) {
  const FastRenderer renderer(robocup());
  // Global: every pixel at mid-exposure, so the AOVs are the static AOVs there.
  const Shutter global{0.04, std::nullopt, 0};
  AovFrame moving, atMiddle;
  renderer.render(kDrivingFromStart, settingsOf(64, 4, global), moving);
  atMiddle = renderAovs(renderer, poseAfter(kStart, kDriving, 0.02), settingsOf(64, 1, Shutter{}));
  EXPECT_EQ(moving.depth, atMiddle.depth);
  EXPECT_EQ(moving.instance, atMiddle.instance);
  EXPECT_EQ(moving.normal, atMiddle.normal);
  // Rolling: row j at its own line's mid-exposure.
  const Shutter rolling{0.002, RollingShutter{500.0, Readout::TopToBottom}, 0};
  AovFrame rolled;
  renderer.render(kDrivingFromStart, settingsOf(64, 9, rolling), rolled);
  bool rowsMatch = true;
  for (int j = 0; j < 64; j += 9) {
    const AovFrame row =
        renderAovs(renderer, poseAfter(kStart, kDriving, pixelTime(rolling, 0, j, 64, 64)), settingsOf(64, 1, Shutter{}));
    for (int i = 0; i < 64; ++i) rowsMatch = rowsMatch && row.depth[j * 64 + i] == rolled.depth[j * 64 + i];
  }
  EXPECT_TRUE(rowsMatch);
  const AovFrame only = renderAovs(renderer, kDrivingFromStart, settingsOf(64, 9, rolling));
  EXPECT_EQ(only.depth, rolled.depth);
}

TEST(MotionRender, MovingFramesAreBitIdenticalForAnyThreadCount) {
  const FastRenderer one(robocup()), four(robocup());
  const RenderSettings settings = settingsOf(160, 4, Shutter{0.02, RollingShutter{50.0, Readout::BottomToTop}, 0});
  ImageRGBA a, b;
  EXPECT_EQ(runOnThreads(1, [&] { a = one.render(kDrivingFromStart, settings); }), 1);
  EXPECT_EQ(runOnThreads(4, [&] { b = four.render(kDrivingFromStart, settings); }), 4);
  EXPECT_TRUE(bitIdentical(a.pixels, b.pixels));
}

}  // namespace
}  // namespace omnicam
