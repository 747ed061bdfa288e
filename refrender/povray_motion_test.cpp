// Ground truth under motion (docs/motion.md): a moving frame is the mean of still POV-Ray renders,
// one per readout line and instant, each with the robot and the mirror where they are then. The
// fast renderer must agree with it pixel by pixel.
#include <gtest/gtest.h>

#include <cstdio>
#include <utility>
#include <vector>

#include "fast_renderer.h"
#include "image_compare.h"
#include "povray_renderer.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

const Scene& robocup() {
  static const Scene s = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return s;
}

// The thesis loop's pace: 1 m/s while turning at 90°/s.
constexpr BodyVelocity kDriving{1.0, 0.0, 90.0};

struct MotionCase {
  const char* name;  // the test's
  const char* label;
  int size;
  Shutter shutter;
};

class FastVsPovrayMoving : public ::testing::TestWithParam<MotionCase> {};

TEST_P(FastVsPovrayMoving, UnlitAtSixteenSamplesPerPixel) {
  const MotionCase& c = GetParam();
  RenderSettings settings;
  settings.rig = robocup().rig.resized(c.size);
  settings.rig.shutter = c.shutter;
  settings.spp = 16;
  const RobotPose start{-0.6, 0.4, 30.0};
  const CameraPlacement driving(start, kDriving);
  const ImageRGBA truth = renderWithPovray(robocup(), driving, settings);
  const FastRenderer fast(robocup());
  const CompareResult r = compareImages(fast.render(driving, settings), truth);
  const double unmoved = compareImages(fast.render(start, settings), truth).psnrDb;
  std::printf("fast vs POV-Ray, moving, %s: PSNR %.2f dB, SSIM %.5f, max abs %.4f (the still robot's image: %.2f dB)\n",
              c.label, r.psnrDb, r.ssim, r.maxAbs, unmoved);
  EXPECT_GE(r.psnrDb, 60.0);
  EXPECT_LT(unmoved, 40.0);  // the motion is there to be matched
}

const MotionCase kCases[] = {
    {"GlobalFixedInstants", "global, 1/30 s, 4 fixed instants", 96, {1.0 / 30.0, std::nullopt, 4}},
    {"GlobalStratified", "global, 1/30 s, stratified (16 instants)", 96, {1.0 / 30.0, std::nullopt, 0}},
    {"RollingRows", "rolling top-to-bottom, 1 ms lines, 4 ms exposure, 2 instants", 48,
     {0.004, RollingShutter{1000.0, Readout::TopToBottom}, 2}},
    {"RollingColumns", "rolling right-to-left, 1 ms lines, no exposure", 48,
     {0.0, RollingShutter{1000.0, Readout::RightToLeft}, 0}},
};

std::string caseName(const ::testing::TestParamInfo<MotionCase>& param) { return param.param.name; }

INSTANTIATE_TEST_SUITE_P(Shutters, FastVsPovrayMoving, ::testing::ValuesIn(kCases), caseName);

// A moving frame is many POV-Ray renders (one per readout line and instant): the count before the
// first, then each once summed, in order, so a long frame shows its progress. 8 rows × 2 instants
// = 16 renders.
TEST(PovrayMoving, ReportsEachRenderAsItIsSummed) {
  RenderSettings settings;
  settings.rig = robocup().rig.resized(8);
  settings.rig.shutter = {0.004, RollingShutter{1000.0, Readout::TopToBottom}, 2};
  settings.spp = 1;
  PovrayOptions options;
  std::vector<std::pair<int, int>> reports;
  options.onRenderSummed = [&](int done, int total) { reports.emplace_back(done, total); };
  renderWithPovray(robocup(), CameraPlacement({-0.6, 0.4, 30.0}, kDriving), settings, options);
  ASSERT_EQ(reports.size(), 17u);
  for (size_t k = 0; k < reports.size(); ++k) EXPECT_EQ(reports[k], std::make_pair(static_cast<int>(k), 16));
}

}  // namespace
}  // namespace omnicam
