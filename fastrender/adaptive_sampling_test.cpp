// Adaptive sampling (RenderSampling::adaptiveSpp): each pixel of an adaptive frame is the same
// pixel of a fixed frame of one of its grids, chosen where the first grid's noise is high; the
// frame does not depend on the thread count.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>

#include "errors.h"
#include "fast_renderer.h"
#include "scene_loader.h"
#include "thread_count_testing.h"

namespace omnicam {
namespace {

struct AdaptiveCase {
  Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/tiled-room.json");
  RenderSettings settings;
  AdaptiveCase() {
    scene.lights[0].diameter = 0.4;  // a disc's soft shadows: noise that varies over the frame
    settings.rig = scene.rig;
    settings.rig.mirrorRig().imageSize = 64;
    settings.spp = 4;
    settings.shading = Shading::Path;
    settings.adaptiveSpp = 64;
    settings.targetError = 0.05;
  }
  ImageRGBA fixedFrame(int spp) const {
    RenderSettings fixed = settings;
    fixed.adaptiveSpp = 0;
    fixed.spp = spp;
    return FastRenderer(scene).render(scene.startPose, fixed);
  }
};

void expectPixelsOfFixedFrames(const AdaptiveCase& c);

// Bit for bit except where a sample's ray meets two surfaces at exactly the same distance: Embree's
// packets, which hold other rays than the fixed frame's, may then find either. In the tiled room
// at its start pose the rays along the image's diagonals meet the room's corners, where two walls
// end (12 of 4096 pixels): there the pixel is its grid's within a few samples' share (measured ≤ 0.023).
TEST(AdaptiveSampling, EachPixelIsTheSamePixelOfAFixedFrameOfItsGrid) {
  for (const bool traced : {false, true}) {  // the closed-form camera, and the one traced through the mirror (non-central)
    SCOPED_TRACE(traced ? "traced" : "closed form");
    AdaptiveCase c;
    c.settings.traced = traced;
    expectPixelsOfFixedFrames(c);
  }
}

void expectPixelsOfFixedFrames(const AdaptiveCase& c) {
  const ImageRGBA adaptive = FastRenderer(c.scene).render(c.scene.startPose, c.settings);
  const std::map<int, ImageRGBA> fixed{{4, c.fixedFrame(4)}, {16, c.fixedFrame(16)}, {64, c.fixedFrame(64)}};
  std::map<int, int> pixelsOf;  // by the grid whose pixel it is (the first that matches); 0: none exactly
  for (size_t p = 0; p < adaptive.pixels.size(); p += 4) {
    int grid = 0;
    float nearest = 1e30f;
    for (const auto& [spp, frame] : fixed) {
      if (std::equal(&adaptive.pixels[p], &adaptive.pixels[p + 4], &frame.pixels[p])) {
        grid = spp;
        break;
      }
      float difference = 0.0f;
      for (int ch = 0; ch < 4; ++ch) difference = std::max(difference, std::abs(adaptive.pixels[p + ch] - frame.pixels[p + ch]));
      nearest = std::min(nearest, difference);
    }
    if (grid == 0) {
      EXPECT_LT(nearest, 0.03f) << "pixel " << p / 4 << " is no fixed frame's";
    }
    ++pixelsOf[grid];
  }
  std::printf("adaptive 4..64 spp at target 0.05: %d, %d, %d pixels of the 4-, 16- and 64-spp frames, %d ties\n",
              pixelsOf[4], pixelsOf[16], pixelsOf[64], pixelsOf[0]);
  EXPECT_LE(pixelsOf[0], 16);
  // Both finer grids are used, and most of the image keeps the first (the black rim among it).
  EXPECT_GT(pixelsOf[16], 50);
  EXPECT_GT(pixelsOf[64], 50);
  EXPECT_GT(pixelsOf[4], pixelsOf[16] + pixelsOf[64]);
}

// A looser target refines fewer pixels, and the noisiest pixels of the first grid are refined
// first: every pixel refined at 0.1 is refined at 0.05 too.
TEST(AdaptiveSampling, ALooserTargetRefinesASubsetOfThePixels) {
  AdaptiveCase c;
  const ImageRGBA tight = FastRenderer(c.scene).render(c.scene.startPose, c.settings);
  c.settings.targetError = 0.1;
  const ImageRGBA loose = FastRenderer(c.scene).render(c.scene.startPose, c.settings);
  const ImageRGBA first = c.fixedFrame(4);
  int refinedTight = 0, refinedLoose = 0;
  for (size_t p = 0; p < first.pixels.size(); p += 4) {
    const bool tightRefined = !std::equal(&tight.pixels[p], &tight.pixels[p + 4], &first.pixels[p]);
    const bool looseRefined = !std::equal(&loose.pixels[p], &loose.pixels[p + 4], &first.pixels[p]);
    refinedTight += tightRefined;
    refinedLoose += looseRefined;
    EXPECT_TRUE(tightRefined || !looseRefined) << "pixel " << p / 4;
  }
  EXPECT_LT(refinedLoose, refinedTight);
  EXPECT_GT(refinedLoose, 0);
}

TEST(AdaptiveSampling, FramesAreBitIdenticalForAnyThreadCount) {
  AdaptiveCase c;
  c.settings.rig.mirrorRig().imageSize = 96;  // work enough for four threads to share
  expectSameFrameOnOneAndFourThreads<FastRenderer>(c.scene, c.settings);
}

TEST(AdaptiveSampling, OnlyUnfilteredPathShadingOfStillFramesIsRefined) {
  AdaptiveCase c;
  const FastRenderer renderer(c.scene);
  const auto errorOf = [&](const RenderSettings& s, const CameraPlacement& placement) -> std::string {
    try {
      (void)renderer.render(placement, s);
    } catch (const InputError& e) {
      return e.what();
    }
    return "";
  };
  EXPECT_EQ(errorOf(c.settings, CameraPlacement(c.scene.startPose, BodyVelocity{1.0, 0.0, 0.0})), "");  // no shutter: still
  RenderSettings moving = c.settings;
  moving.rig.shutter.exposureS = 0.01;
  EXPECT_EQ(errorOf(moving, CameraPlacement(c.scene.startPose, BodyVelocity{1.0, 0.0, 0.0})),
            "adaptive sampling: not with a moving frame (its shutter is open while the robot moves)");
  RenderSettings denoised = c.settings;
  denoised.denoise = true;
  EXPECT_EQ(errorOf(denoised, c.scene.startPose), "adaptive sampling: only unfiltered path shading");
  RenderSettings single = c.settings;  // one sample has no spread to measure
  single.spp = 1;
  single.adaptiveSpp = 16;
  EXPECT_EQ(errorOf(single, c.scene.startPose), "adaptive sampling: needs spp of at least 4 (its noise is measured from its samples)");
  RenderSettings uneven = c.settings;
  uneven.adaptiveSpp = 32;
  EXPECT_EQ(errorOf(uneven, c.scene.startPose),
            "adaptive sampling: its most samples (32) must be spp times 4, 16, 64, … up to 1024");
}

}  // namespace
}  // namespace omnicam
