#include "pinhole.h"

#include <cmath>

#include "lens_distortion.h"
#include "mirror_surface.h"

namespace omnicam {

std::optional<CameraRay> Pinhole::ray(const Vec2& rasterPoint) const {
  const Vec2 normalised = (rasterPoint - principalPoint) / focalPx;
  if (orthographic)
    return CameraRay{position + viewpointFromPinhole * Vec3(normalised.x(), normalised.y(), 0.0), viewpointFromPinhole.col(2)};
  const auto undistorted = undistort(distortion, normalised);
  if (!undistorted) return std::nullopt;
  return CameraRay{position, (viewpointFromPinhole * Vec3(undistorted->x(), undistorted->y(), 1.0)).normalized()};
}

std::optional<Vec2> Pinhole::raster(const Vec3& pointViewpoint) const {
  const Vec3 q = viewpointFromPinhole.transpose() * (pointViewpoint - position);
  if (!(q.z() > 0.0)) return std::nullopt;
  if (orthographic) return principalPoint + focalPx * q.head<2>();
  const auto distorted = distortImaged(distortion, Vec2(q.x() / q.z(), q.y() / q.z()));
  if (!distorted) return std::nullopt;  // beyond the lens' fold (ray() refuses the same raster points)
  return principalPoint + focalPx * *distorted;
}

CameraRay Pinhole::rayTo(const Vec3& pointViewpoint) const {
  if (!orthographic) return {position, (pointViewpoint - position).normalized()};
  const Vec3 q = viewpointFromPinhole.transpose() * (pointViewpoint - position);
  return {position + viewpointFromPinhole * Vec3(q.x(), q.y(), 0.0), viewpointFromPinhole.col(2)};
}

Pinhole pinholeOf(const MirrorRig& rig) {
  const CameraMount& m = rig.mount;
  Pinhole p;
  const double half = 0.5 * rig.imageSize;
  Vec3 idealPosition;
  std::visit(Overloaded{[&](const HyperboloidMirror&) {
                          const OmniCamera ideal = rig.idealCamera();
                          idealPosition = ideal.mirror().pinholeInViewpoint();
                          p.focalPx = ideal.physicalFocalLength();
                        },
                        [&](const auto& other) {  // paraboloid, sphere, cone: on the axis, framed on the rim
                          const auto mirror = mirrorSurfaceOf(rig);
                          const double d = other.cameraDistance;
                          p.orthographic = d == 0.0;
                          if (p.orthographic) {
                            // The image plane well below the vertex: where it sits along the axis changes nothing.
                            idealPosition = Vec3(0.0, 0.0, mirror->heightAt(0.0, 0.0) - mirror->rimRadius());
                            p.focalPx = half / mirror->rimRadius();
                          } else {
                            idealPosition = Vec3(0.0, 0.0, -d);
                            p.focalPx = half * (mirror->rimZ() + d) / mirror->rimRadius();
                          }
                        }},
             rig.shape);
  p.position = idealPosition + 1e-3 * Vec3(m.offsetMm[0], m.offsetMm[1], m.offsetMm[2]);
  // An orthographic camera's image does not depend on where along its axis it sits: keep its
  // image plane below the mirror whatever offset_mm's z says.
  if (p.orthographic) p.position.z() = idealPosition.z();
  p.viewpointFromPinhole = (Eigen::AngleAxisd(radians(m.rotationDeg[0]), Vec3::UnitX()) *
                            Eigen::AngleAxisd(radians(m.rotationDeg[1]), Vec3::UnitY()) *
                            Eigen::AngleAxisd(radians(m.rotationDeg[2]), Vec3::UnitZ()))
                               .toRotationMatrix();
  p.principalPoint = Vec2(half, half) + Vec2(m.principalPointOffsetPx[0], m.principalPointOffsetPx[1]);
  p.distortion = m.distortion;
  return p;
}

}  // namespace omnicam
