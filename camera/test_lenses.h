#pragma once
// Lens cameras the tests share (camera/, fastrender/, refrender/): one definition of how a test
// builds a lens rig.
#include "rig.h"

namespace omnicam::test {

// A rig whose camera is `model` on a width × height image, turned by rotationDeg.
inline RigSpec lensRig(const LensModel& model, int width, int height, std::array<double, 3> rotationDeg = {0.0, 0.0, 0.0},
                       double height_m = 0.4) {
  RigSpec rig;
  rig.kind = LensCameraSpec{model, width, height, rotationDeg};
  rig.height = height_m;
  return rig;
}

// An f-θ lens seeing fovDeg across its circle about (cx, cy) (OpenCV's pixel convention).
inline FThetaLens fTheta(FThetaLens::Kind kind, double f, double fovDeg, double cx, double cy) {
  FThetaLens lens;
  lens.kind = kind;
  lens.f = f;
  lens.cx = cx, lens.cy = cy;
  lens.maxThetaRad = radians(fovDeg / 2.0);
  return lens;
}

// The equidistant lens centred on a width × height image.
inline FThetaLens equidistant(double f, double fovDeg, int width, int height) {
  return fTheta(FThetaLens::Kind::Equidistant, f, fovDeg, (width - 1) / 2.0, (height - 1) / 2.0);
}

// A panorama over ±lonDeg and ±latDeg.
inline Equirectangular panorama(int width, int height, double lonDeg, double latDeg) {
  return {width, height, radians(-lonDeg), radians(lonDeg), radians(-latDeg), radians(latDeg)};
}

}  // namespace omnicam::test
