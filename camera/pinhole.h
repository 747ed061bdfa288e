#pragma once
#include <optional>

#include "camera.h"
#include "rig.h"

namespace omnicam {

// The physical camera below the mirror, modelled once for every engine and exporter: a pinhole,
// or for the paraboloid's orthographic build a telecentric camera whose rays all run along its
// optical axis (then `position` is the centre of its image plane and focalPx is pixels per metre).
struct Pinhole {
  Vec3 position;                          // viewpoint frame, metres
  Eigen::Matrix3d viewpointFromPinhole;   // columns: image u axis, image v axis, optical axis
  double focalPx = 0.0;
  Vec2 principalPoint;                    // raster coordinates (continuous; W/2 + offset)
  LensDistortion distortion;              // perspective cameras only
  bool orthographic = false;

  // The viewpoint-frame ray (unit direction) through a raster point; nullopt where the lens
  // images nothing.
  std::optional<CameraRay> ray(const Vec2& raster) const;
  // Raster point of a viewpoint-frame point in front of the camera (nullopt behind it, or beyond
  // the lens' fold).
  std::optional<Vec2> raster(const Vec3& pointViewpoint) const;
  // The camera's ray that reaches a point: from the pinhole toward it, or along the axis.
  CameraRay rayTo(const Vec3& pointViewpoint) const;
};

// The camera of a rig: the ideal one moved by rig.mount. The ideal one: for the hyperboloid at F,
// framed as the ideal rig's image; for the other shapes on the axis at their cameraDistance
// below the design point (the paraboloid with 0: orthographic), framed so that the rim touches
// the image border.
Pinhole pinholeOf(const MirrorRig& rig);

}  // namespace omnicam
