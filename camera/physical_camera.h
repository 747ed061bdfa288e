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
#include "mirror_surface.h"
#include "omni_camera.h"
#include "pinhole.h"

namespace omnicam {

class PhysicalCamera final : public Camera {
 public:
  explicit PhysicalCamera(const RigSpec& rig);

  const char* model() const override { return "physical"; }
  bool central() const override { return false; }
  std::optional<CameraRay> generateRay(const CameraSample& sample) const override;
  // Solves for the mirror point whose reflection sees the point (Newton's method on the
  // reflection law, from the central model's mirror point; see docs/physical-camera.md).
  std::optional<Vec2> project(const Vec3& pointViewpoint) const override;
  // project's guaranteed route alone: Newton's method from the minimum of the path length over
  // the mirror's body (fermat_path.h), found by a search that always converges. project takes it
  // when the shape's quick starts fail.
  std::optional<Vec2> projectFromFermatMinimum(const Vec3& pointViewpoint) const;
  bool images(const Vec2& raster) const override { return generateRay({raster}).has_value(); }
  nlohmann::json describe() const override;

  // The exact Mei model of this camera when it has one: the pinhole at F, unturned, with k3 = 0
  // (its lens is then Mei's distortion with rescaled coefficients; docs/physical-camera.md).
  std::optional<MeiIntrinsics> meiEquivalent() const;
  // The best-fit central model and its residuals (central_fit.h); fitted once, on first use.
  const CentralApproximation& centralApproximation() const;

  const Pinhole& pinhole() const { return pinhole_; }
  const MirrorSurface& mirror() const { return *mirror_; }

 private:
  // InputError (naming rig.camera) if the camera sees far less of the mirror than the ideal one.
  void checkMirrorInView() const;
  // Newton's method on the reflection law from the mirror point above `start`; the physical
  // reflection point of p, or nullopt if it does not converge to one.
  std::optional<Vec3> reflectionPoint(const Vec3& p, Vec2 start) const;
  // Whether mirror point m physically reflects p to the camera: inside the rim, camera and p on
  // the mirror's outer side, and m the first thing the camera sees along its ray to it.
  bool physicalReflection(const Vec3& p, const Vec3& m) const;
  // Whether the straight segment from a perspective pinhole to p meets the mirror's body (p lies
  // behind the mirror, or inside it): then no mirror point reflects p (fermat_path.h).
  bool straightPathMeetsBody(const Vec3& p) const;
  // Whether the path length's minimum over the mirror's body provably lies at a corner (the rim's
  // edge, the cone's apex) where nothing reflects: then p is not seen (a perspective pinhole).
  bool minimumAtACorner(const Vec3& p) const;
  // The mirror point a camera ray sees, inside the rim.
  std::optional<Vec3> mirrorPointSeen(const CameraRay& ray) const;
  std::shared_ptr<const MirrorSurface> mirror_;
  Pinhole pinhole_;
  mutable std::once_flag fitOnce_;
  mutable std::unique_ptr<CentralApproximation> fit_;
};

}  // namespace omnicam
