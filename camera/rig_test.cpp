// A rig's camera is a mirror or a lens by its type (rig.h, CameraKind): each kind owns its image
// size and parameters, and the rig's questions answer from the kind it holds.
#include "rig.h"

#include <gtest/gtest.h>

#include "errors.h"
#include "test_lenses.h"

namespace omnicam {
namespace {

RigSpec misalignedSphere() {
  RigSpec rig;
  MirrorRig& mirror = rig.mirrorRig();
  mirror.shape = SphereMirror{0.03, 60.0, 0.12};
  mirror.mount.offsetMm = {2.0, -1.0, 1.0};
  mirror.mount.rotationDeg = {1.0, -0.5, 0.5};
  mirror.mount.principalPointOffsetPx = {1.5, -0.75};
  return rig;
}

TEST(Rig, TheDefaultRigIsTheIdealHyperboloidAt360) {
  const RigSpec rig;
  ASSERT_TRUE(std::holds_alternative<MirrorRig>(rig.kind));
  EXPECT_TRUE(rig.ideal());
  EXPECT_EQ(rig.imageWidth(), 360);
  EXPECT_EQ(rig.imageHeight(), 360);
  EXPECT_EQ(rig.imageSizeText(), "360^2");
  EXPECT_EQ(rig.mirrorRig().shapeKind(), MirrorShape::Hyperboloid);
  EXPECT_EQ(rig.mirrorRig().hyperboloid(), (HyperboloidMirror{11.546, 0.02321, 45.0, 45.0}));  // the thesis' mirror
}

// Resizing scales what is in pixels (a mirror rig's image and principal point offset; a lens'
// image and intrinsics) and keeps everything else of the kind as it was.
TEST(Rig, ResizingKeepsEachKindsOwnFields) {
  const RigSpec mirrorRig = misalignedSphere();
  const RigSpec large = mirrorRig.resized(720);
  ASSERT_TRUE(std::holds_alternative<MirrorRig>(large.kind));
  MirrorRig expected = mirrorRig.mirrorRig();
  expected.imageSize = 720;
  expected.mount.principalPointOffsetPx = {3.0, -1.5};
  EXPECT_EQ(large.mirrorRig(), expected);
  EXPECT_EQ(large.height, mirrorRig.height);

  const RigSpec lensRig = test::lensRig(test::equidistant(60.0, 180.0, 200, 100), 200, 100, {1.0, -20.0, 30.0}, 0.7);
  const RigSpec wide = lensRig.resized(400);
  ASSERT_TRUE(std::holds_alternative<LensCameraSpec>(wide.kind));
  EXPECT_EQ(wide.imageWidth(), 400);
  EXPECT_EQ(wide.imageHeight(), 200);
  EXPECT_EQ(wide.imageSizeText(), "400x200");
  EXPECT_EQ(wide.lensCamera().rotationDeg, lensRig.lensCamera().rotationDeg);
  EXPECT_EQ(wide.lensCamera().model, scaledLens(lensRig.lensCamera().model, 2.0));
  EXPECT_EQ(wide.height, 0.7);
}

// Equality sees the kind and every field of it; a mirror rig and a lens rig are never equal.
TEST(Rig, EqualitySeesTheKindAndItsFields) {
  const RigSpec a = misalignedSphere();
  RigSpec b = a;
  EXPECT_EQ(a, b);
  std::get<SphereMirror>(b.mirrorRig().shape).capAngleDeg += 1e-9;
  EXPECT_NE(a, b);
  b = a;  // another shape with the same numbers is another mirror
  b.mirrorRig().shape = ConeMirror{0.03, 60.0, 0.12};
  EXPECT_NE(a, b);
  b = a;
  b.mirrorRig().mount.rotationDeg[2] += 1e-9;
  EXPECT_NE(a, b);
  const RigSpec lens = test::lensRig(test::equidistant(60.0, 180.0, 360, 360), 360, 360);
  EXPECT_NE(RigSpec{}, lens);
  EXPECT_EQ(lens.imageWidth(), RigSpec{}.imageWidth());
}

// A lens camera has no mirror, hence no camera below one to mount: asking for its mirror rig is
// refused, and idealizing it leaves it as it is (its rotation is where it looks, not a misalignment).
TEST(Rig, ALensRigCannotCarryAMount) {
  const RigSpec lens = test::lensRig(test::equidistant(60.0, 180.0, 360, 360), 360, 360, {0.0, 10.0, 20.0});
  try {
    (void)lens.mirrorRig("rig.camera");
    ADD_FAILURE() << "a lens rig gave a mirror rig";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(), "rig.camera: a lens camera (rig.lens) has no mirror");
  }
  EXPECT_FALSE(lens.ideal());
  EXPECT_EQ(lens.idealized(), lens);
  EXPECT_THROW((void)lens.camera(), InputError);
  EXPECT_THROW((void)RigSpec{}.lensCamera(), std::bad_variant_access);
  EXPECT_EQ(misalignedSphere().idealized().mirrorRig().mount, CameraMount{});
}

// A mirror's shape carries only its own parameters; what needs the hyperboloid's (the central
// model) says which shape it got.
TEST(Rig, OnlyTheHyperboloidHasTheCentralModelsMirror) {
  const RigSpec sphere = misalignedSphere();
  EXPECT_EQ(sphere.mirrorRig().shapeKind(), MirrorShape::Sphere);
  EXPECT_STREQ(mirrorShapeName(sphere.mirrorRig().shape), "sphere");
  EXPECT_FALSE(sphere.idealized().ideal());  // the camera put back is still not a single viewpoint
  try {
    (void)sphere.idealized().camera();
    ADD_FAILURE() << "a sphere gave a central model";
  } catch (const InputError& e) {
    EXPECT_STREQ(e.what(),
                 "rig.mirror.shape: this needs the hyperboloid (the central (Mei) model's mirror); a sphere mirror is traced "
                 "physically only");
  }
  const MirrorShapeSpec shapes[] = {HyperboloidMirror{}, ParaboloidMirror{}, SphereMirror{}, ConeMirror{}};
  const char* names[] = {"hyperboloid", "paraboloid", "sphere", "cone"};
  for (size_t i = 0; i < 4; ++i) EXPECT_STREQ(mirrorShapeName(shapes[i]), names[i]);
}

// The camera frame is the kind's: the unified model's for a mirror, the lens' OpenCV frame.
TEST(Rig, TheCameraFrameIsTheKinds) {
  EXPECT_TRUE(cameraFromViewpoint(RigSpec{}).isApprox(unifiedCameraFromViewpoint()));
  const RigSpec lens = test::lensRig(test::equidistant(60.0, 180.0, 360, 360), 360, 360, {0.0, 0.0, 90.0});
  const Rigid cameraFromView = cameraFromViewpoint(lens);
  // Turned 90° about z: the optical axis (camera Z) looks along robot +y.
  EXPECT_TRUE((cameraFromView.linear().transpose() * Vec3::UnitZ()).isApprox(Vec3::UnitY(), 1e-12));
  EXPECT_TRUE(cameraFromView.translation().isZero());
}

}  // namespace
}  // namespace omnicam
