#pragma once
// The ideal rig's camera: the closed-form unified (Mei) model of omni_camera.h behind the camera
// interface. Every ray leaves F'.
#include "camera.h"
#include "omni_camera.h"

namespace omnicam {

class CentralCamera final : public Camera {
 public:
  // InputError for a rig whose camera is not ideal (rig.h: RigSpec::camera).
  explicit CentralCamera(const RigSpec& rig);

  const char* model() const override { return "mei_unified"; }
  bool central() const override { return true; }
  std::optional<CameraRay> generateRay(const CameraSample& sample) const override;
  std::optional<Vec2> project(const Vec3& pointViewpoint) const override;
  bool images(const Vec2& raster) const override { return model_.insideRim(raster); }
  nlohmann::json describe() const override;

  const OmniCamera& unified() const { return model_; }

 private:
  OmniCamera model_;
};

// The unified model's intrinsics as sidecars and intrinsics files state them.
nlohmann::json unifiedIntrinsicsJson(const OmniCamera& camera);

}  // namespace omnicam
