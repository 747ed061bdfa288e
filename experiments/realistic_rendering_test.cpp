// The guard against render noise in the realistic frames (issue #20): two seeds of a 64-px
// realistic frame must agree as converged frames do; the settings before the fix must not.
#include "realistic_rendering.h"

#include <gtest/gtest.h>

#include <filesystem>

#include "hall_arena.h"
#include "render_noise.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

// Two seeds of the realistic frame: the PSNR of one against the other (8-bit sRGB, disc).
double seedPairPsnr(const Scene& hall, const RobotPose& pose, const RealisticRendering& setup) {
  const ImageRGBA a = renderRealistic(hall, {pose}, setup, 64, setup.spp, 1, 600.0).front();
  const ImageRGBA b = renderRealistic(hall, {pose}, setup, 64, setup.spp, 2, 600.0).front();
  return measureRenderNoise(a, b).psnrDb;
}

// Measured (seeds 1 and 2, thesis-loop pose 0): today's setup 29.8 dB, the one before issue #20
// 17.4 dB. The bound sits between them with room on both sides.
constexpr double kPairBoundDb = 26.0;

TEST(RealisticNoiseGuard, TwoSeedsOfARealisticFrameAgreeAndTheOldSettingsDoNot) {
  const std::string lab = "/usr/share/blender/datafiles/studiolights/world/interior.exr";
  ASSERT_TRUE(fs::exists(lab)) << lab << " is missing: Debian's blender-data ships it (make deps)";
  const fs::path folder = fs::path(::testing::TempDir()) / "realistic_noise_guard";
  fs::remove_all(folder);
  HallOptions options;
  options.fieldScene = std::string(OMNICAM_SOURCE_DIR) + "/scenes/robocup2006.json";
  options.photos = {lab};
  writeHallArena(options, (folder / "hall-textured.json").string());
  const Scene hall = loadScene((folder / "hall-textured.json").string());
  const RobotPose pose = hall.findPath("thesis-loop")->poses.front();

  const double today = seedPairPsnr(hall, pose, realisticRendering());
  const double before = seedPairPsnr(hall, pose, realisticRenderingBefore());
  EXPECT_GE(today, kPairBoundDb) << "the realistic frames are noisy again: " << realisticRendering().describe();
  EXPECT_LT(before, kPairBoundDb) << "the guard cannot fail: the settings before issue #20 pass it";
  std::printf("seed-pair PSNR at 64 px: today %.1f dB, before %.1f dB (bound %.1f)\n", today, before, kPairBoundDb);
  fs::remove_all(folder);
}

}  // namespace
}  // namespace omnicam
