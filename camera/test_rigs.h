#pragma once
// Rigs the physical-camera tests share (physical_camera_test.cpp, fermat_path_test.cpp, the POV-Ray shapes): one
// definition, so that both test the same misalignments and shapes.
#include "rig.h"

namespace omnicam::test {

// The camera moved (offsetMm, −0.7·offsetMm, 0.5·offsetMm) and turned (r, −0.6·r, 0.8·r).
inline RigSpec misaligned(double offsetMm, double rotationDeg) {
  RigSpec rig;
  CameraMount& mount = rig.mirrorRig().mount;
  mount.offsetMm = {offsetMm, -0.7 * offsetMm, 0.5 * offsetMm};
  mount.rotationDeg = {rotationDeg, -0.6 * rotationDeg, 0.8 * rotationDeg};
  return rig;
}

// The other mirror shapes' test builds (cameraDistance 0: the paraboloid's orthographic one).
inline MirrorShapeSpec shapeOf(MirrorShape shape, double cameraDistance) {
  switch (shape) {
    case MirrorShape::Paraboloid: return ParaboloidMirror{0.02, 30.0, cameraDistance};
    case MirrorShape::Sphere: return SphereMirror{0.03, 60.0, cameraDistance};
    case MirrorShape::Cone: return ConeMirror{60.0, 0.03, cameraDistance};  // > 45°: the axial ray reflects below the horizon
    case MirrorShape::Hyperboloid: break;
  }
  return HyperboloidMirror{};
}

// Those shapes, each with the 2 mm / 1° misalignment.
inline RigSpec shaped(MirrorShape shape, double cameraDistance) {
  RigSpec rig = misaligned(2.0, 1.0);
  rig.mirrorRig().shape = shapeOf(shape, cameraDistance);
  return rig;
}

}  // namespace omnicam::test
