#include "make_camera.h"

#include <deque>
#include <mutex>

#include "central_camera.h"
#include "errors.h"
#include "lens_camera.h"
#include "physical_camera.h"

namespace omnicam {

std::shared_ptr<const Camera> makeCamera(const RigSpec& rig, bool traced) {
  return std::visit(Overloaded{[&](const LensCameraSpec&) -> std::shared_ptr<const Camera> { return std::make_shared<LensCamera>(rig); },
                               [&](const MirrorRig& mirror) -> std::shared_ptr<const Camera> {
                                 if (mirror.ideal() && !traced) return std::make_shared<CentralCamera>(rig);
                                 return std::make_shared<PhysicalCamera>(rig);
                               }},
                    rig.kind);
}

nlohmann::json describeCamera(const RigSpec& rig) {
  static std::mutex mutex;
  static std::deque<std::pair<RigSpec, nlohmann::json>> recent;  // guarded by mutex
  constexpr size_t kRemembered = 8;
  const std::lock_guard<std::mutex> lock(mutex);
  for (const auto& [known, description] : recent)
    if (known == rig) return description;
  nlohmann::json description = makeCamera(rig)->describe();
  recent.emplace_front(rig, description);
  if (recent.size() > kRemembered) recent.pop_back();
  return description;
}

Rigid CentralModel::cameraFromViewpoint() const {
  return approximation ? approximation->cameraFromViewpoint : unifiedCameraFromViewpoint();
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
  const auto* traced = dynamic_cast<const PhysicalCamera*>(&camera);
  if (!traced) throw InputError(std::string("rig.lens: a ") + camera.model() + " lens camera has no unified (Mei) model");
  const PhysicalCamera& physical = *traced;
  if (const auto mei = physical.meiEquivalent()) {
    model.intrinsics = *mei;
    const MirrorRig& rig = camera.rig().mirrorRig();
    if (std::holds_alternative<HyperboloidMirror>(rig.shape) && physical.pinhole().distortion.none())
      model.rimRadiusPx = rig.idealCamera().rimRadius();
    return model;
  }
  model.approximation = physical.centralApproximation();
  model.intrinsics = model.approximation->intrinsics;
  return model;
}

}  // namespace omnicam
