#include "ros_camera_info.h"

#include "lens_camera.h"
#include "lens_intrinsics_files.h"
#include "make_camera.h"

namespace omnicam {

namespace {

void setPinholeMatrices(RosCameraInfo& info, double fx, double fy, double cx, double cy) {
  info.k = {fx, 0.0, cx, 0.0, fy, cy, 0.0, 0.0, 1.0};
  info.p = {fx, 0.0, cx, 0.0, 0.0, fy, cy, 0.0, 0.0, 0.0, 1.0, 0.0};
}

}  // namespace

RosCameraInfo rosCameraInfoOf(const Camera& camera) {
  RosCameraInfo info;
  info.width = static_cast<uint32_t>(camera.width());
  info.height = static_cast<uint32_t>(camera.height());
  info.r = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  const auto* lens = dynamic_cast<const LensCamera*>(&camera);
  if (!lens) {
    const MeiIntrinsics k = centralModelOf(camera).intrinsics;
    info.distortionModel = "omnidirectional";
    info.d = {k.xi, k.lens.k1, k.lens.k2, k.lens.p1, k.lens.p2};
    setPinholeMatrices(info, k.gammaX, k.gammaY, k.cx, k.cy);
    return info;
  }
  const LensModel& model = lens->lens().model;
  if (const auto kb = asKannalaBrandt(model)) {
    info.distortionModel = "equidistant";
    info.d = {kb->k[0], kb->k[1], kb->k[2], kb->k[3]};
    setPinholeMatrices(info, kb->fx, kb->fy, kb->cx, kb->cy);
  } else if (const auto* p = std::get_if<PinholeRadTan>(&model)) {
    info.distortionModel = "plumb_bob";
    info.d = {p->distortion.k1, p->distortion.k2, p->distortion.p1, p->distortion.p2, p->distortion.k3};
    setPinholeMatrices(info, p->fx, p->fy, p->cx, p->cy);
  } else {
    info.distortionModel = std::string("omnicam/") + camera.model();
    info.r = {};
    info.intrinsicsJson = camera.describe().dump();
  }
  return info;
}

}  // namespace omnicam
