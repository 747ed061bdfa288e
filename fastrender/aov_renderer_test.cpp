// AOVs against closed-form geometry: a floor at a known height, a box whose top face is at a
// known distance; every value belongs to the pixel centre's own viewing ray.
#include "aov_renderer.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include "thread_count_testing.h"
#include "placement.h"

namespace omnicam {
namespace {

Scene floorAndBox() {
  Scene s;
  s.materials.push_back({"grey", {0.5f, 0.5f, 0.5f}, nullptr, "", {1, 1}, 0.2f, 0.8f, ""});
  s.objects.push_back({"floor", 0, Quad{{-50, -50, 0}, {100, 0, 0}, {0, 100, 0}}, ""});
  s.objects.push_back({"box", 0, Box{{1.0, 0.5, 0.15}, {0.4, 0.4, 0.3}, 0.0}, ""});
  return s;
}

TEST(AovRenderer, DepthInstanceAndNormalAreTheGeometryAtEachPixelCentre) {
  const Scene scene = floorAndBox();
  const FastRenderer renderer(scene);
  RenderSettings settings;
  settings.rig.mirrorRig().imageSize = 120;
  const RobotPose pose{0.2, -0.1, 30.0};
  const AovFrame aov = renderAovs(renderer, pose, settings);
  const OmniCamera camera = settings.rig.camera();
  const Rigid worldFromCam = CameraPlacement(pose).worldFromCamera(settings.rig), camFromWorld = worldFromCam.inverse();
  int floorPixels = 0, boxPixels = 0, empty = 0;
  for (int j = 0; j < aov.height; ++j)
    for (int i = 0; i < aov.width; ++i) {
      const size_t p = static_cast<size_t>(j) * aov.width + i;
      const Vec2 centre(i + 0.5, j + 0.5);
      if (aov.instance[p] == 0) {
        EXPECT_EQ(aov.depth[p], 0.0f);
        ++empty;
        continue;
      }
      ASSERT_TRUE(camera.insideRim(centre));
      const Vec3 direction = worldFromCam.linear() * camera.cameraFromRaster(centre);
      const Vec3 point = worldFromCam.translation() + aov.depth[p] * direction;
      // The AOV's ray is this pixel centre's viewing ray: its world point projects back onto it.
      const auto back = camera.rasterFromCamera(camFromWorld * point);
      ASSERT_TRUE(back);
      EXPECT_LT((*back - centre).norm(), 1e-4) << i << "," << j;
      const Vec3 n(aov.normal[3 * p], aov.normal[3 * p + 1], aov.normal[3 * p + 2]);
      EXPECT_NEAR(n.norm(), 1.0, 1e-6);
      EXPECT_LT(n.dot(direction), 0.0) << "faces F'";
      if (aov.instance[p] == 1) {  // the floor: z = 0, normal up, depth = height / cos(incidence)
        EXPECT_NEAR(point.z(), 0.0, 1e-5);
        EXPECT_NEAR(n.z(), 1.0, 1e-6);
        EXPECT_NEAR(aov.depth[p], settings.rig.height / -direction.z(), 1e-5 * aov.depth[p]);
        ++floorPixels;
      } else {
        ASSERT_EQ(aov.instance[p], 2);
        const Vec3 local = point - Vec3(1.0, 0.5, 0.15);  // on one of the box's faces
        EXPECT_NEAR(local.cwiseAbs().cwiseQuotient(Vec3(0.2, 0.2, 0.15)).maxCoeff(), 1.0, 1e-4);
        ++boxPixels;
      }
    }
  EXPECT_GT(floorPixels, 1000);
  EXPECT_GT(boxPixels, 20);
  EXPECT_GT(empty, 1000);  // above the horizon and beyond the rim
}

TEST(AovRenderer, TheBoxTopIsAtItsClosedFormDistance) {
  // Straight below F' nothing but the floor; from a pose whose pixel centre looks at the box
  // top's centre the depth is the distance to it.
  const Scene scene = floorAndBox();
  const FastRenderer renderer(scene);
  RenderSettings settings;
  settings.rig.mirrorRig().imageSize = 240;
  const RobotPose pose{0.0, 0.0, 0.0};
  const OmniCamera camera = settings.rig.camera();
  const Vec3 top(1.0, 0.5, 0.3);
  const auto raster = camera.rasterFromCamera(CameraPlacement(pose).worldFromCamera(settings.rig).inverse() * top);
  ASSERT_TRUE(raster);
  const int i = static_cast<int>(raster->x()), j = static_cast<int>(raster->y());
  const AovFrame aov = renderAovs(renderer, pose, settings);
  const size_t p = static_cast<size_t>(j) * aov.width + i;
  ASSERT_EQ(aov.instance[p], 2);
  const Vec3 fPrime(0.0, 0.0, settings.rig.height);
  const Vec3 direction = CameraPlacement(pose).worldFromCamera(settings.rig).linear() * camera.cameraFromRaster({i + 0.5, j + 0.5});
  // The ray meets the plane z = 0.3 of the top face at t = (0.3 − 0.4) / d_z.
  EXPECT_NEAR(aov.depth[p], (top.z() - fPrime.z()) / direction.z(), 1e-5);
  EXPECT_NEAR(aov.normal[3 * p + 2], 1.0f, 1e-6f);
}

TEST(AovRenderer, IndependentOfTheThreadCount) {
  // One thread against four (more than this machine may have cores; all four in the arena when
  // the render starts), each with its own renderer, so that its tables are built there too.
  const Scene scene = floorAndBox();
  const FastRenderer one(scene), four(scene);
  RenderSettings settings;
  settings.rig.mirrorRig().imageSize = 360;
  AovFrame single, many;
  EXPECT_EQ(runOnThreads(1, [&] { single = renderAovs(one, RobotPose{0.3, 0.2, 45.0}, settings); }), 1);
  EXPECT_EQ(runOnThreads(4, [&] { many = renderAovs(four, RobotPose{0.3, 0.2, 45.0}, settings); }), 4);
  EXPECT_EQ(many.depth, single.depth);
  EXPECT_EQ(many.instance, single.instance);
  EXPECT_EQ(many.normal, single.normal);
  EXPECT_GT(std::count(single.instance.begin(), single.instance.end(), 2), 10);  // the box is in view
}

// The one-pass render (colour + AOVs) gives the colour image of render() and the AOVs of
// renderAovs(), bit for bit: at odd n by reusing the centre sample, at even n with its own ray.
TEST(AovRenderer, OnePassGivesTheSameImageAndAovs) {
  const Scene scene = floorAndBox();
  const FastRenderer renderer(scene);
  for (int spp : {1, 4, 9}) {
    RenderSettings settings;
    settings.rig.mirrorRig().imageSize = 80;
    settings.spp = spp;
    settings.shading = Shading::Lit;
    const RobotPose pose{0.1, -0.3, 70.0};
    AovFrame fused;
    const ImageRGBA image = renderer.render(pose, settings, fused);
    const AovFrame separate = renderAovs(renderer, pose, settings);
    EXPECT_EQ(image.pixels, renderer.render(pose, settings).pixels) << "spp " << spp;
    EXPECT_EQ(fused.depth, separate.depth) << "spp " << spp;
    EXPECT_EQ(fused.instance, separate.instance) << "spp " << spp;
    EXPECT_EQ(fused.normal, separate.normal) << "spp " << spp;
    EXPECT_GT(std::count(fused.instance.begin(), fused.instance.end(), 2), 10);  // the box is in view
  }
}

// A frame reused for another pose holds nothing of the earlier one (no clearing between uses).
TEST(AovRenderer, AReusedFrameHoldsOnlyTheNewPose) {
  const Scene scene = floorAndBox();
  const FastRenderer renderer(scene);
  RenderSettings settings;
  settings.rig.mirrorRig().imageSize = 64;
  AovFrame reused, fresh;
  renderer.render(RobotPose{1.0, 0.5, 0.0}, settings, reused);  // right next to the box: a different picture
  renderer.render(RobotPose{-2.0, -1.0, 120.0}, settings, reused);
  renderer.render(RobotPose{-2.0, -1.0, 120.0}, settings, fresh);
  EXPECT_EQ(reused.depth, fresh.depth);
  EXPECT_EQ(reused.instance, fresh.instance);
  EXPECT_EQ(reused.normal, fresh.normal);
}

}  // namespace
}  // namespace omnicam
