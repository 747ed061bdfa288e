// Ground truth under motion (docs/motion.md): a moving frame is the mean of still POV-Ray renders,
// one per readout line and instant, each with the robot and the mirror where they are then. The
// fast renderer must agree with it pixel by pixel.
#include <gtest/gtest.h>

#include <unistd.h>

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <utility>
#include <vector>

#include "fast_renderer.h"
#include "image_compare.h"
#include "povray_renderer.h"
#include "scene_loader.h"

namespace omnicam {
namespace {

namespace fs = std::filesystem;

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

namespace omnicam {
namespace {

// Render threads cap a moving frame's POV-Ray processes (dataset --threads): each renders on one
// thread, and no more run at once than threads were given. Counted by a wrapper that notes how
// many are running as each starts; the frame is the uncapped one, pixel for pixel.
TEST(PovrayMoving, RenderThreadsCapTheProcessesRunningAtOnce) {
  const fs::path dir = fs::temp_directory_path() / ("omnicam_povray_cap_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir / "running");
  const fs::path wrapper = dir / "povray";
  // It runs in the job's folder: its render.ini says the render threads.
  std::ofstream(wrapper) << "#!/bin/sh\n: > '" << (dir / "running").string() << "'/$$\nls '" << (dir / "running").string()
                         << "' | wc -l >> '" << (dir / "counts").string() << "'\ngrep -h Work_Threads render.ini >> '"
                         << (dir / "threads").string() << "'\npovray \"$@\"\nstatus=$?\nrm -f '" << (dir / "running").string()
                         << "'/$$\nexit $status\n";
  fs::permissions(wrapper, fs::perms::owner_all);
  RenderSettings settings;
  settings.rig = robocup().rig.resized(8);
  settings.rig.shutter = {0.004, RollingShutter{1000.0, Readout::TopToBottom}, 1};
  settings.spp = 1;
  const CameraPlacement driving({-0.6, 0.4, 30.0}, kDriving);
  const ImageRGBA uncapped = renderWithPovray(robocup(), driving, settings);
  for (int threads : {1, 2}) {
    fs::remove(dir / "counts");
    fs::remove(dir / "threads");
    PovrayOptions options;
    options.executable = wrapper.string();
    options.threads = threads;
    const ImageRGBA capped = renderWithPovray(robocup(), driving, settings, options);
    EXPECT_EQ(capped.pixels, uncapped.pixels) << threads << " threads";
    std::ifstream counts(dir / "counts");
    std::vector<int> running;
    for (int n; counts >> n;) running.push_back(n);
    ASSERT_EQ(running.size(), 8u) << threads << " threads: a render per row";
    EXPECT_LE(*std::max_element(running.begin(), running.end()), threads);
    std::ifstream threadLines(dir / "threads");
    int renders = 0;
    for (std::string line; std::getline(threadLines, line); ++renders) EXPECT_EQ(line, "Work_Threads=1") << threads << " threads";
    EXPECT_EQ(renders, 8) << threads << " threads";
  }
  fs::remove_all(dir);
}

}  // namespace
}  // namespace omnicam
