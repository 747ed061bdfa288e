// Lens cameras (issue #37) against Blender Cycles' own cameras: the panoramic ones (fisheye
// equidistant, equisolid and lens polynomial, equirectangular) and the perspective one
// (docs/blender.md, "Lens cameras"). Cycles samples each pixel at random: ≥ 35 dB at 64 spp.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "blender_renderer.h"
#include "fast_renderer.h"
#include "image_compare.h"
#include "scene_loader.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

using test::fTheta;

struct LensCase {
  const char* label;
  LensCameraSpec lens;
  RobotPose pose;
  double height;
};

void PrintTo(const LensCase& c, std::ostream* os) { *os << c.label; }

FThetaLens polynomial() {
  FThetaLens lens = fTheta(FThetaLens::Kind::Polynomial, 0.0, 190.0, 101.0, 73.5);
  lens.k = {0.0, 0.0125, 1.5e-5, -4e-8, 0.0};  // θ(r), r in pixels: grows over the whole image
  return lens;
}

class FastVsBlenderLens : public ::testing::TestWithParam<LensCase> {};

TEST_P(FastVsBlenderLens, UnlitAt64Spp) {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  static const FastRenderer fast(scene);
  const LensCase& c = GetParam();
  RenderSettings settings;
  settings.rig.kind = c.lens;
  settings.rig.height = c.height;
  settings.spp = 64;
  const ImageRGBA truth = renderWithBlender(scene, {CameraPlacement(c.pose)}, settings).front();
  const ImageRGBA ours = fast.render(c.pose, settings);
  const CompareResult r = compareImages(ours, truth);
  // The same view a degree turned: what a convention slip would give.
  RenderSettings turned = settings;
  turned.rig.lensCamera().rotationDeg[2] += 1.0;
  const double fromTurned = compareImages(fast.render(c.pose, turned), truth).psnrDb;
  std::printf("fast vs Blender, %s, unlit, 64 spp: PSNR %.2f dB, SSIM %.5f (turned 1 deg: %.2f dB)\n", c.label, r.psnrDb, r.ssim,
              fromTurned);
  EXPECT_GE(r.psnrDb, 35.0);
  EXPECT_LT(fromTurned, r.psnrDb - 5.0);
}

constexpr double kHalfPixel = 0.5;

INSTANTIATE_TEST_SUITE_P(
    Lenses, FastVsBlenderLens,
    ::testing::Values(
        LensCase{"fisheye equidistant, circle filling a square (Cycles' FISHEYE_EQUIDISTANT)",
                 {fTheta(FThetaLens::Kind::Equidistant, 160.0 / kPi, 180.0, 79.5, 79.5), 160, 160, {0.0, 0.0, 0.0}},
                 {2.7, -1.8, 180.0}, 0.4},
        LensCase{"fisheye equidistant 200 deg, off-centre, wide (as a lens polynomial)",
                 {fTheta(FThetaLens::Kind::Equidistant, 40.0, 200.0, 105.0 - kHalfPixel, 70.0), 200, 150, {10.0, 40.0, 30.0}},
                 {1.0, -1.5, 137.0}, 0.3},
        LensCase{"fisheye equisolid 180 deg",
                 {fTheta(FThetaLens::Kind::Equisolid, 55.0, 180.0, 79.5, 79.5), 160, 160, {0.0, 20.0, -30.0}},
                 {0.1, 0.05, 0.0}, 0.5},
        LensCase{"fisheye lens polynomial 190 deg", {polynomial(), 200, 150, {0.0, 30.0, 0.0}}, {-2.4, 0.2, -63.0}, 0.4},
        LensCase{"full panorama", {Equirectangular{256, 128, -kPi, kPi, -kPi / 2, kPi / 2}, 256, 128, {0.0, 0.0, 0.0}},
                 {0.1, 0.05, 0.0}, 0.4},
        LensCase{"partial asymmetric panorama, turned",
                 {Equirectangular{200, 90, radians(-120.0), radians(60.0), radians(-60.0), radians(20.0)}, 200, 90, {5.0, 10.0, -40.0}},
                 {-2.4, 0.2, -63.0}, 0.5},
        LensCase{"pinhole, principal point off", {PinholeRadTan{110.0, 110.0, 84.0, 55.0, {}}, 160, 120, {3.0, 20.0, 15.0}},
                 {0.5, -1.0, 90.0}, 0.6}),
    [](const auto& param) { return "lens" + std::to_string(param.index); });

}  // namespace
}  // namespace omnicam
