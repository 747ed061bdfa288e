#include "landmark_annotations.h"

#include <algorithm>
#include <cmath>

#include "make_camera.h"
#include "timed_projection.h"

namespace omnicam {

namespace {

constexpr int kOutlinePoints = 32;      // per circle (top and bottom) for the bounding box
constexpr double kSurfaceGap = 1e-3;    // metres short of a surface point when testing occlusion
const double kFacingAnglesDeg[] = {-60.0, -30.0, 0.0, 30.0, 60.0};
const double kFacingHeights[] = {-0.4, 0.0, 0.4};  // × the band's height, about its centre

}  // namespace

std::vector<LandmarkAnnotation> annotateLandmarks(const Scene& scene, const RayScene& rays, const RigSpec& rig,
                                                  const CameraPlacement& placement) {
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  // Where p lands, on the image or off it (a lens camera projects beyond its rectangle), and
  // where it is imaged: on the image.
  auto projected = [&](const Vec3& p) { return projectAtReadout(*camera, placement, p); };
  auto imaged = [&](const Vec3& p) -> std::optional<TimedProjection> {
    const auto at = projected(p);
    const bool onImage = at && at->raster.x() >= 0.0 && at->raster.x() < camera->width() && at->raster.y() >= 0.0 &&
                         at->raster.y() < camera->height();
    return onImage ? at : std::nullopt;
  };
  // Is world point p imaged with nothing in front of it? Seen from where its ray leaves the mirror
  // when its line sees it: F' for the central model, its own mirror point for a non-central rig.
  auto seen = [&](const Vec3& p) {
    const auto at = imaged(p);
    if (!at) return false;
    const Rigid worldFromView = placement.worldFromViewpoint(rig, at->seconds);
    Vec3 from = worldFromView.translation();
    if (!camera->central()) {
      const auto ray = camera->generateRay({at->raster});
      if (!ray) return false;
      from = worldFromView * ray->origin;
    }
    const Vec3 toPoint = p - from;
    const double distance = toPoint.norm();
    return distance <= kSurfaceGap || !rays.occluded(from, toPoint / distance, 0.0, distance - kSurfaceGap);
  };
  std::vector<LandmarkAnnotation> result;
  for (const Landmark& lm : scene.landmarks) {
    LandmarkAnnotation a;
    a.landmark = &lm;
    const auto centre = imaged(lm.position);
    // Range and bearing when the centre is imaged (mid-exposure of the middle line if it is not).
    const double seconds =
        centre ? centre->seconds : pixelTime(rig.shutter, rig.imageWidth() / 2, rig.imageHeight() / 2, rig.imageWidth(), rig.imageHeight());
    // From the camera's foot and along its heading, as the detector's inversion and the EKF have
    // it: a tilted rig's F' stands off the foot.
    const RobotPose foot = placement.footAt(seconds);
    const Vec2 rangeBearing = rangeBearingOnFloor(Vec2(foot.x, foot.y), radians(foot.yawDeg), lm.position.head<2>());
    a.rangeM = rangeBearing(0);
    a.bearingDeg = degrees(rangeBearing(1));
    if (centre) a.centre = centre->raster;
    // The side facing F', where the camera looks from.
    const Vec3 viewpoint = placement.worldFromViewpoint(rig, seconds).translation();
    const double radius = 0.5 * lm.diameter;
    Vec2 toCamera = (viewpoint - lm.position).head<2>();
    toCamera = toCamera.norm() > 1e-9 ? Vec2(toCamera.normalized()) : Vec2(1.0, 0.0);

    int seenCount = 0, total = 0;
    for (double angleDeg : kFacingAnglesDeg)
      for (double height : kFacingHeights) {
        const double angle = radians(angleDeg);
        const Vec2 around(std::cos(angle) * toCamera.x() - std::sin(angle) * toCamera.y(),
                          std::sin(angle) * toCamera.x() + std::cos(angle) * toCamera.y());
        const Vec3 p = lm.position + Vec3(radius * around.x(), radius * around.y(), height * lm.height);
        ++total;
        const bool pointSeen = seen(p);
        seenCount += pointSeen;
        // Hidden, not merely beyond the rim or the image's edge (near them, the facing point may
        // fall outside while the centre is imaged): only another object occludes.
        if (angleDeg == 0.0 && height == 0.0 && a.centre && !pointSeen && imaged(p)) a.occluded = true;
      }
    a.visibleFraction = static_cast<double>(seenCount) / total;

    Eigen::AlignedBox2d box;
    for (int ring = 0; ring < 2; ++ring)
      for (int k = 0; k < kOutlinePoints; ++k) {
        const double angle = 2.0 * kPi * k / kOutlinePoints;
        const Vec3 p = lm.position + Vec3(radius * std::cos(angle), radius * std::sin(angle),
                                          (ring == 0 ? -0.5 : 0.5) * lm.height);
        if (const auto at = projected(p)) box.extend(at->raster);
      }
    // The outline's box clipped to the image; none when it lies wholly off the image.
    box.clamp(Eigen::AlignedBox2d(Vec2(0.0, 0.0), Vec2(camera->width(), camera->height())));
    if (!box.isEmpty() && box.volume() > 0.0)  // a box on the image's edge alone holds no pixel
      a.bbox = std::array<double, 4>{box.min().x(), box.min().y(), box.max().x(), box.max().y()};
    result.push_back(a);
  }
  return result;
}

nlohmann::json landmarksToJson(const std::vector<LandmarkAnnotation>& annotations) {
  nlohmann::json list = nlohmann::json::array();
  for (const LandmarkAnnotation& a : annotations) {
    nlohmann::json entry = {{"name", a.landmark->name},
                            {"colour_class", a.landmark->colourClass},
                            {"position", {a.landmark->position.x(), a.landmark->position.y(), a.landmark->position.z()}},
                            {"in_view", a.inView()},
                            {"visible", a.visible()},
                            {"occluded", a.occluded},
                            {"visible_fraction", a.visibleFraction},
                            {"range_m", a.rangeM},
                            {"bearing_deg", a.bearingDeg}};
    entry["centre"] = a.centre ? nlohmann::json{a.centre->x(), a.centre->y()} : nlohmann::json(nullptr);
    entry["bbox"] = a.bbox ? nlohmann::json{(*a.bbox)[0], (*a.bbox)[1], (*a.bbox)[2], (*a.bbox)[3]}
                           : nlohmann::json(nullptr);
    list.push_back(std::move(entry));
  }
  return {{"pixel_centre", "half-integer: pixel (i, j) covers [i, i+1) x [j, j+1), like `omnicam project`"},
          {"landmarks", list}};
}

}  // namespace omnicam
