#pragma once
// A camera without a mirror (issue #37): one central lens model of lens_models.h — fisheye,
// double sphere, EUCM, f-θ, equirectangular panorama or distorted pinhole — behind the camera
// interface. Every ray leaves F'; the lens is turned on the robot as rig.lens says (rig.h).
#include <Eigen/Core>

#include "camera.h"

namespace omnicam {

class LensCamera final : public Camera {
 public:
  // std::bad_variant_access for a mirror rig (makeCamera builds one for lens rigs only).
  explicit LensCamera(const RigSpec& rig);

  const char* model() const override { return modelName_.c_str(); }
  bool central() const override { return true; }
  std::optional<CameraRay> generateRay(const CameraSample& sample) const override;
  std::optional<Vec2> project(const Vec3& pointViewpoint) const override;
  bool images(const Vec2& raster) const override;
  nlohmann::json describe() const override;

  const LensCameraSpec& lens() const { return lens_; }
  const Eigen::Matrix3d& viewpointFromLensMatrix() const { return viewpointFromLens_; }

 private:
  LensCameraSpec lens_;  // rig().lensCamera(), resolved once rather than per ray
  std::string modelName_;
  Eigen::Matrix3d viewpointFromLens_;
};

// The lens' intrinsics as sidecars state them (OpenCV's pixel convention: centres at integers).
nlohmann::json lensIntrinsicsJson(const LensCameraSpec& lens);

}  // namespace omnicam
