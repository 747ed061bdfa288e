#include "central_camera.h"

#include "central_fit.h"

namespace omnicam {

CentralCamera::CentralCamera(const RigSpec& rig) : Camera(rig), model_(rig.camera()) {}

std::optional<CameraRay> CentralCamera::generateRay(const CameraSample& sample) const {
  if (!model_.insideRim(sample.raster)) return std::nullopt;
  const Eigen::Matrix3d viewpointFromCamera = unifiedCameraFromViewpoint().inverse().linear();
  return CameraRay{Vec3::Zero(), viewpointFromCamera * model_.cameraFromRaster(sample.raster)};
}

std::optional<Vec2> CentralCamera::project(const Vec3& pointViewpoint) const {
  return model_.rasterFromCamera(unifiedCameraFromViewpoint().linear() * pointViewpoint);
}

nlohmann::json CentralCamera::describe() const { return unifiedIntrinsicsJson(model_); }

nlohmann::json unifiedIntrinsicsJson(const OmniCamera& camera) {
  const OpenCvIntrinsics k = camera.openCvIntrinsics();
  nlohmann::json j = MeiIntrinsics{k.xi, k.gamma_x, k.gamma_y, k.cx, k.cy, {}}.toJson();
  j.update({{"width", camera.width()},
            {"height", camera.height()},
            {"rim_radius_px", camera.rimRadius()},
            {"horizon_radius_px", camera.horizonRadius()},
            {"note",
             "camera frame at the effective viewpoint: X forward, Y right (-robot y), Z down; "
             "gamma_y < 0 because the catadioptric image is a mirror image of a top-down map"}});
  return j;
}

}  // namespace omnicam
