#pragma once
// Rigs the physical-camera tests share (physical_camera_test.cpp, fermat_path_test.cpp): one
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

// The other mirror shapes, each with the 2 mm / 1° misalignment (cameraDistance 0: the
// paraboloid's orthographic build).
inline RigSpec shaped(MirrorShape shape, double cameraDistance) {
  RigSpec rig = misaligned(2.0, 1.0);
  MirrorRig& mirror = rig.mirrorRig();
  mirror.shape.shape = shape;
  mirror.shape.cameraDistance = cameraDistance;
  mirror.shape.parabolaH = 0.02;
  mirror.rimElevationDeg = shape == MirrorShape::Paraboloid ? 30.0 : mirror.rimElevationDeg;
  mirror.shape.sphereRadius = 0.03;
  mirror.shape.capAngleDeg = 60.0;
  mirror.shape.coneHalfAngleDeg = 60.0;  // > 45°: the axial ray reflects below the horizon
  mirror.shape.coneRimRadius = 0.03;
  return rig;
}

}  // namespace omnicam::test
