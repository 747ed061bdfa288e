// The fast renderer traces the physical camera: for the ideal rig it must reproduce the closed
// form it otherwise uses; for a misaligned rig its rays leave the mirror, and depth is measured
// from there.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "fast_renderer.h"
#include "image_compare.h"
#include "make_camera.h"
#include "scene_loader.h"
#include "thread_count_testing.h"
#include "placement.h"
#include "aov_renderer.h"
#include "film.h"

namespace omnicam {
namespace {

const Scene& robocup() {
  static const Scene scene = loadScene(OMNICAM_SOURCE_DIR "/scenes/robocup2006.json");
  return scene;
}

RigSpec misalignedRig() {
  RigSpec rig = robocup().rig;
  rig.mirrorRig().mount.offsetMm = {2.0, -1.5, 1.0};
  rig.mirrorRig().mount.rotationDeg = {1.0, -0.7, 0.5};
  rig.mirrorRig().mount.distortion = {-0.08, 0.01, 0.0005, -0.0004, 0.0};
  return rig;
}

class TracedIdealRig : public ::testing::TestWithParam<Shading> {};

TEST_P(TracedIdealRig, MatchesTheClosedFormAt16Spp) {
  const FastRenderer renderer(robocup());
  RenderSettings settings;
  settings.rig = robocup().rig;
  settings.spp = 16;
  settings.shading = GetParam();
  for (const RobotPose pose : {RobotPose{2.7, -1.8, 180.0}, RobotPose{1.0, -1.5, 137.0}}) {
    settings.traced = false;
    const ImageRGBA closedForm = renderer.render(pose, settings);
    settings.traced = true;
    const ImageRGBA traced = renderer.render(pose, settings);
    const CompareResult r = compareImages(traced, closedForm);
    std::printf("traced vs closed form, %s, pose (%g, %g, %g): PSNR %.2f dB, max abs %.3g\n",
                shadingName(GetParam()), pose.x, pose.y, pose.yawDeg, r.psnrDb, r.maxAbs);
    EXPECT_GE(r.psnrDb, 90.0);  // the bound
    EXPECT_TRUE(traced.pixels == closedForm.pixels) << "docs/physical-camera.md states bit-identical";
  }
}

INSTANTIATE_TEST_SUITE_P(Shadings, TracedIdealRig, ::testing::Values(Shading::Unlit, Shading::Lit),
                         [](const auto& param) { return std::string(shadingName(param.param)); });

TEST(PhysicalRender, DepthOfANonCentralRayRunsFromItsMirrorPoint) {
  Scene floor;
  floor.materials.push_back({"grey", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.25f, 0.75f, ""});
  floor.objects.push_back({"floor", 0, Quad{{-50, -50, 0}, {100, 0, 0}, {0, 100, 0}}, ""});
  const FastRenderer renderer(floor);
  RenderSettings settings;
  settings.rig = misalignedRig();
  settings.rig.mirrorRig().imageSize = 96;
  const RobotPose pose{0.3, -0.2, 30.0};
  const AovFrame aovs = renderAovs(renderer, pose, settings);
  const auto camera = makeCamera(settings.rig);
  ASSERT_FALSE(camera->central());
  const Rigid worldFromView = CameraPlacement(pose).worldFromViewpoint(settings.rig);
  int floorPixels = 0;
  for (int j = 0; j < 96; ++j)
    for (int i = 0; i < 96; ++i) {
      const auto ray = camera->generateRay({Film::sample(i, j, 0, 0, 1)});
      const float depth = aovs.depth[static_cast<size_t>(j) * 96 + i];
      if (!ray || ray->direction.z() >= -1e-3) continue;
      // The floor z = 0 along the reflected ray, from the mirror point, in closed form.
      const Vec3 origin = worldFromView * ray->origin;
      const Vec3 direction = worldFromView.linear() * ray->direction;
      const double expected = -origin.z() / direction.z();
      if (expected > 40.0) continue;  // beyond the floor's edge
      ASSERT_NEAR(depth, expected, 2e-6 * expected) << i << ", " << j;
      ++floorPixels;
    }
  EXPECT_GT(floorPixels, 1000);
}

TEST(PhysicalRender, AMisalignedFrameIsBitIdenticalForAnyThreadCount) {
  const FastRenderer renderer(robocup()), rendererFour(robocup());
  RenderSettings settings;
  settings.rig = misalignedRig();
  settings.rig.mirrorRig().imageSize = 200;
  settings.spp = 4;
  settings.shading = Shading::Lit;
  const RobotPose pose{0.4, 0.2, 75.0};
  ImageRGBA one, four;
  ASSERT_EQ(runOnThreads(1, [&] { one = renderer.render(pose, settings); }), 1);
  ASSERT_EQ(runOnThreads(4, [&] { four = rendererFour.render(pose, settings); }), 4);
  EXPECT_EQ(one.pixels, four.pixels);
  // And it is not the ideal rig's frame.
  settings.rig = settings.rig.idealized();
  const ImageRGBA ideal = renderer.render(pose, settings);
  EXPECT_LT(compareImages(one, ideal).psnrDb, 40.0);
}

}  // namespace
}  // namespace omnicam
