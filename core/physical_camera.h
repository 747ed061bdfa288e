#pragma once
// The rig as built: a pinhole camera, possibly moved, turned and with a distorting lens, looking up
// into the exact mirror. A ray is traced pixel → lens (distortion inverted exactly) → pinhole ray
// → exact ray–quadric intersection → reflection; it leaves the mirror from its own point, so the
// camera is non-central unless the pinhole sits exactly at the mirror's outer focus.
//
// Frames (rig.h): viewpoint (origin F', robot axes) and pinhole (origin at the pinhole; x = image
// u, y = image v, z = optical axis). The ideal pinhole is at F = (0, 0, −c) with its axes along
// robot x, y, z; its focal length and principal point are those of the ideal rig's image, so a
// zero mount reproduces the ideal image.
#include <memory>
#include <mutex>

#include "camera.h"
#include "central_fit.h"
#include "omni_camera.h"

namespace omnicam {

// The physical pinhole camera, modelled once for every engine and exporter.
struct Pinhole {
  Vec3 position;                          // viewpoint frame, metres
  Eigen::Matrix3d viewpointFromPinhole;   // columns: image u axis, image v axis, optical axis
  double focalPx = 0.0;
  Vec2 principalPoint;                    // raster coordinates (continuous; W/2 + offset)
  LensDistortion distortion;

  // Unit viewpoint-frame direction through a raster point; nullopt where the lens images nothing.
  std::optional<Vec3> direction(const Vec2& raster) const;
  // Raster point of a viewpoint-frame point in front of the camera (nullopt behind it).
  std::optional<Vec2> raster(const Vec3& pointViewpoint) const;
};

// The pinhole of a rig: the ideal one moved by rig.mount.
Pinhole pinholeOf(const RigSpec& rig);

class PhysicalCamera final : public Camera {
 public:
  explicit PhysicalCamera(const RigSpec& rig);

  const char* model() const override { return "physical"; }
  bool central() const override { return false; }
  std::optional<CameraRay> generateRay(const CameraSample& sample) const override;
  // Solves for the mirror point whose reflection sees the point (Newton's method on the
  // reflection law, from the central model's mirror point; see docs/physical-camera.md).
  std::optional<Vec2> project(const Vec3& pointViewpoint) const override;
  bool images(const Vec2& raster) const override { return generateRay({raster}).has_value(); }
  nlohmann::json describe() const override;

  // The exact Mei model of this camera when it has one: the pinhole at F, unturned, with k3 = 0
  // (its lens is then Mei's distortion with rescaled coefficients; docs/physical-camera.md).
  std::optional<MeiIntrinsics> meiEquivalent() const;
  // The best-fit central model and its residuals (central_fit.h); fitted once, on first use.
  const CentralApproximation& centralApproximation() const;

  const Pinhole& pinhole() const { return pinhole_; }
  const HyperbolicMirror& mirror() const { return mirror_; }

 private:
  // InputError (naming rig.camera) if the camera sees far less of the mirror than the ideal one.
  void checkMirrorInView() const;
  // The mirror point the pinhole sees along a viewpoint-frame direction, inside the rim.
  std::optional<Vec3> mirrorPointSeen(const Vec3& direction) const;
  HyperbolicMirror mirror_;
  Pinhole pinhole_;
  double rimZ_;  // the mirror ends at the rim plane z = rimZ_ (viewpoint frame)
  mutable std::once_flag fitOnce_;
  mutable std::unique_ptr<CentralApproximation> fit_;
};

}  // namespace omnicam
