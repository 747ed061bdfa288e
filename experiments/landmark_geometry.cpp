#include "landmark_geometry.h"

#include <cmath>

namespace omnicam {

std::optional<RangeBearing> rangeBearingFromRaster(const RigSpec& rig, const Vec2& raster, double pointHeight) {
  const OmniCamera camera = rig.camera();
  // viewpointFromCamera: the robot's axes (x forward, y left, z up) at F'.
  const Vec3 direction = unifiedCameraFromViewpoint().inverse().linear() * camera.cameraFromRaster(raster);
  const double rise = pointHeight - rig.height;  // from F' to the point's height
  if (std::abs(direction.z()) < 1e-12 || rise / direction.z() <= 0.0) return std::nullopt;
  const double t = rise / direction.z();
  return RangeBearing(t * std::hypot(direction.x(), direction.y()), std::atan2(direction.y(), direction.x()));
}

}  // namespace omnicam
