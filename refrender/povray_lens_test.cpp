// Lens cameras (issue #37) against POV-Ray's own cameras: `fisheye` is the equidistant lens,
// `spherical` the equirectangular panorama, `perspective` the pinhole (docs/povray.md, "Lens
// cameras"). Both engines trace the same rays at the same sample positions, unlit, 16 spp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "errors.h"
#include "fast_renderer.h"
#include "image_compare.h"
#include "povray_renderer.h"
#include "scene_loader.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

using test::equidistant;
using test::panorama;

struct LensCase {
  const char* label;
  LensCameraSpec lens;
  RobotPose pose;
  double height;
};

void PrintTo(const LensCase& c, std::ostream* os) { *os << c.label; }

class FastVsPovrayLens : public ::testing::TestWithParam<LensCase> {};

TEST_P(FastVsPovrayLens, UnlitAtSixteenSamplesPerPixel) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  const LensCase& c = GetParam();
  RenderSettings settings;
  settings.rig.kind = c.lens;
  settings.rig.height = c.height;
  settings.spp = 16;
  const ImageRGBA ours = fast.render(c.pose, settings);
  const ImageRGBA truth = renderWithPovray(scene, c.pose, settings);
  const CompareResult r = compareImages(ours, truth);
  std::printf("fast vs POV-Ray, %s: PSNR %.2f dB, SSIM %.5f, max abs %.4f\n", c.label, r.psnrDb, r.ssim, r.maxAbs);
  EXPECT_GE(r.psnrDb, 60.0);
  // The view shows the field: most pixels seen, and not one colour (else agreement proves nothing).
  size_t lit = 0, differing = 0;
  for (size_t p = 0; p < truth.pixels.size(); p += 4) {
    lit += truth.pixels[p] + truth.pixels[p + 1] + truth.pixels[p + 2] > 0.05f;
    differing += std::abs(truth.pixels[p + 1] - truth.pixels[1]) > 0.1f;
  }
  EXPECT_GT(lit, truth.pixels.size() / 4 / 5);
  EXPECT_GT(differing, truth.pixels.size() / 4 / 20);
  // Alpha is geometry: the same image circle in both.
  for (size_t p = 3; p < ours.pixels.size(); p += 4) ASSERT_FLOAT_EQ(ours.pixels[p], truth.pixels[p]) << p / 4;
}

INSTANTIATE_TEST_SUITE_P(
    Lenses, FastVsPovrayLens,
    ::testing::Values(
        LensCase{"fisheye 180 deg ahead", {equidistant(50.0, 180.0, 160, 160), 160, 160, {0.0, 0.0, 0.0}}, {2.7, -1.8, 180.0}, 0.4},
        LensCase{"fisheye 210 deg turned down and round, wide image",
                 {equidistant(40.0, 210.0, 200, 150), 200, 150, {10.0, 50.0, 30.0}}, {1.0, -1.5, 137.0}, 0.3},
        LensCase{"full panorama", {panorama(256, 128, 180.0, 90.0), 256, 128, {0.0, 0.0, 0.0}}, {0.1, 0.05, 0.0}, 0.4},
        LensCase{"partial panorama, turned", {panorama(200, 90, 100.0, 45.0), 200, 90, {5.0, 20.0, -40.0}}, {-2.4, 0.2, -63.0}, 0.5},
        LensCase{"pinhole", {PinholeRadTan{110.0, 110.0, 79.5, 59.5, {}}, 160, 120, {3.0, 20.0, 15.0}}, {0.5, -1.0, 90.0}, 0.6}),
    [](const auto& param) { return "lens" + std::to_string(param.index); });

// A lens camera moves with the shutter like the mirror camera (docs/motion.md): the truth is the
// mean of still POV-Ray renders, one per readout line and instant. A non-square fisheye read out
// column by column, and a panorama over a global exposure.
struct MovingLensCase {
  const char* label;
  LensCameraSpec lens;
  Shutter shutter;
};

void PrintTo(const MovingLensCase& c, std::ostream* os) { *os << c.label; }

class FastVsPovrayMovingLens : public ::testing::TestWithParam<MovingLensCase> {};

TEST_P(FastVsPovrayMovingLens, UnlitAtSixteenSamplesPerPixel) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  const MovingLensCase& c = GetParam();
  RenderSettings settings;
  settings.rig.kind = c.lens;
  settings.rig.height = 0.4;
  settings.rig.shutter = c.shutter;
  settings.spp = 16;
  const RobotPose start{-0.6, 0.4, 30.0};
  const CameraPlacement driving(start, BodyVelocity{1.0, 0.0, 90.0});
  const ImageRGBA truth = renderWithPovray(scene, driving, settings);
  const CompareResult r = compareImages(fast.render(driving, settings), truth);
  const double unmoved = compareImages(fast.render(start, settings), truth).psnrDb;
  std::printf("fast vs POV-Ray, moving, %s: PSNR %.2f dB, SSIM %.5f (the still robot's image: %.2f dB)\n", c.label, r.psnrDb,
              r.ssim, unmoved);
  EXPECT_GE(r.psnrDb, 60.0);
  EXPECT_LT(unmoved, 40.0);  // the motion is there to be matched
}

INSTANTIATE_TEST_SUITE_P(
    Shutters, FastVsPovrayMovingLens,
    ::testing::Values(
        MovingLensCase{"fisheye 190 deg, 64x48, rolling right-to-left, 1 ms lines",
                       {equidistant(16.0, 190.0, 64, 48), 64, 48, {0.0, 20.0, 0.0}},
                       {0.0, RollingShutter{1000.0, Readout::RightToLeft}, 0}},
        MovingLensCase{"panorama 96x48, global 1/30 s, 4 instants",
                       {panorama(96, 48, 180.0, 90.0), 96, 48, {0.0, 0.0, 0.0}}, {1.0 / 30.0, std::nullopt, 4}}),
    [](const auto& param) { return "moving" + std::to_string(param.index); });

// What POV-Ray's cameras cannot be is refused before anything runs, naming the field at fault.
TEST(PovrayLens, LensesPovrayHasNoCameraForAreRefused) {
  const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  RenderSettings settings;
  FThetaLens offCentre = equidistant(50.0, 180.0, 160, 160);
  offCentre.cx += 3.0;
  settings.rig.kind = LensCameraSpec{offCentre, 160, 160, {0.0, 0.0, 0.0}};
  EXPECT_THROW(
      {
        try {
          (void)renderWithPovray(scene, RobotPose{}, settings);
        } catch (const InputError& e) {
          EXPECT_NE(std::string(e.what()).find("rig.lens.cx, cy"), std::string::npos) << e.what();
          throw;
        }
      },
      InputError);
  settings.rig.kind = LensCameraSpec{KannalaBrandt{50.0, 50.0, 79.5, 79.5, {0.01, 0.0, 0.0, 0.0}}, 160, 160, {0.0, 0.0, 0.0}};
  try {
    (void)renderWithPovray(scene, RobotPose{}, settings);
    ADD_FAILURE() << "Kannala-Brandt rendered by POV-Ray";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("has no kannala_brandt camera; render it with the fast engine"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace omnicam
