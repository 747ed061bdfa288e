#include "make_camera.h"

#include "central_camera.h"
#include "physical_camera.h"

namespace omnicam {

std::shared_ptr<const Camera> makeCamera(const RigSpec& rig, bool traced) {
  if (rig.ideal() && !traced) return std::make_shared<CentralCamera>(rig);
  return std::make_shared<PhysicalCamera>(rig);
}

CentralModel centralModelOf(const Camera& camera) {
  CentralModel model;
  if (const auto* central = dynamic_cast<const CentralCamera*>(&camera)) {
    const OpenCvIntrinsics k = central->unified().openCvIntrinsics();
    model.intrinsics.xi = k.xi, model.intrinsics.gammaX = k.gamma_x, model.intrinsics.gammaY = k.gamma_y;
    model.intrinsics.cx = k.cx, model.intrinsics.cy = k.cy;
    model.rimRadiusPx = central->unified().rimRadius();
    return model;
  }
  const auto& physical = dynamic_cast<const PhysicalCamera&>(camera);
  if (const auto mei = physical.meiEquivalent()) {
    model.intrinsics = *mei;
    if (camera.rig().shape.shape == MirrorShape::Hyperboloid && physical.pinhole().distortion.none())
      model.rimRadiusPx = camera.rig().idealCamera().rimRadius();
    return model;
  }
  model.approximation = physical.centralApproximation();
  model.intrinsics = model.approximation->intrinsics;
  return model;
}

}  // namespace omnicam
