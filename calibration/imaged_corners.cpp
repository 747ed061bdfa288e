#include "imaged_corners.h"

namespace omnicam {

const char* cornerSightName(CornerSight sight) {
  switch (sight) {
    case CornerSight::Seen: return "seen";
    case CornerSight::BeyondRim: return "beyond_rim";
    case CornerSight::OutsideImage: return "outside_image";
    case CornerSight::BackFacing: return "back_facing";
    case CornerSight::Occluded: return "occluded";
  }
  return "unknown";
}

namespace {

CornerSight sightOf(const Camera& camera, const Rigid& worldFromViewpoint, const RayScene* rays,
                    const CalibrationTarget& target, const Vec3& cornerWorld, const Vec2& raster) {
  if (raster.x() < 0.0 || raster.y() < 0.0 || raster.x() >= camera.width() || raster.y() >= camera.height())
    return CornerSight::OutsideImage;
  if (!camera.images(raster)) return CornerSight::BeyondRim;
  const std::optional<CameraRay> ray = camera.generateRay({raster});
  if (!ray) return CornerSight::BeyondRim;
  const Vec3 origin = worldFromViewpoint * ray->origin, direction = worldFromViewpoint.linear() * ray->direction;
  // The printed face looks along the target's z.
  if (!(target.worldFromTarget.linear().col(2).dot(direction) < 0.0)) return CornerSight::BackFacing;
  if (!rays) return CornerSight::Seen;
  const std::optional<SurfaceHit> hit = rays->intersect(origin, direction);
  if (!hit || hit->object != target.object || (hit->point - cornerWorld).norm() > kCornerHitTolerance)
    return CornerSight::Occluded;
  return CornerSight::Seen;
}

}  // namespace

std::vector<ImagedCorner> imagedCorners(const Camera& camera, const Rigid& worldFromViewpoint, const RayScene* rays,
                                        const CalibrationTarget& target) {
  const Rigid viewpointFromWorld = worldFromViewpoint.inverse();
  const std::vector<Vec3> corners = worldCorners(target);
  std::vector<ImagedCorner> out;
  out.reserve(corners.size());
  for (size_t k = 0; k < corners.size(); ++k) {
    ImagedCorner c;
    c.index = static_cast<int>(k);
    const std::optional<Vec2> raster = camera.project(viewpointFromWorld * corners[k]);
    if (raster) {
      c.raster = *raster;
      c.sight = sightOf(camera, worldFromViewpoint, rays, target, corners[k], *raster);
    }
    out.push_back(c);
  }
  return out;
}

}  // namespace omnicam
