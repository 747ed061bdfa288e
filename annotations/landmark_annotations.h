#pragma once
// Ground truth for landmark detection, computed instead of labelled by hand (the thesis marked
// beacons in 100 frames by hand): where each landmark of the scene appears in one camera's image,
// whether another object hides it, and its pixel bounding box. Landmarks are vertical cylinders
// (Scene::landmarks: centre, diameter, height).
#include <array>
#include <nlohmann/json.hpp>
#include <optional>
#include <string>
#include <vector>

#include "placement.h"
#include "ray_scene.h"
#include "rig.h"
#include "scene.h"

namespace omnicam {

struct LandmarkAnnotation {
  const Landmark* landmark = nullptr;
  // Raster position (continuous, pixel centres at +0.5) of the landmark's centre; nullopt when
  // the centre lies beyond the mirror rim.
  std::optional<Vec2> centre;
  // Of 15 points on the side facing the camera (5 around × 3 heights): the fraction imaged
  // inside the rim with nothing in between.
  double visibleFraction = 0.0;
  // In view, and the facing point at the centre's height is imaged but hidden by another object
  // (a facing point beyond the rim or the image's edge is not occluded).
  bool occluded = false;
  // Bounds [u_min, v_min, u_max, v_max] of the imaged part of the band's outline, clipped to the
  // image; nullopt when none of it is imaged.
  std::optional<std::array<double, 4>> bbox;
  // From the camera's foot (the robot's origin below its mount; below F' on a level rig) to the
  // landmark's axis, horizontally: metres, and degrees CCW from the camera's forward axis, in
  // (−180, 180] (what the thesis' EKF measures, rangeBearingOnFloor).
  double rangeM = 0.0, bearingDeg = 0.0;

  bool inView() const { return centre.has_value(); }
  bool visible() const { return inView() && !occluded; }
};

// Every landmark of `scene` for a camera with `rig` at `placement`: each point at the time its
// own line sees it (timed_projection.h); range and bearing at the centre's time, the bearing from
// the camera's heading (its foot's, placement.h). `rays` must be built from the same scene.
std::vector<LandmarkAnnotation> annotateLandmarks(const Scene& scene, const RayScene& rays, const RigSpec& rig,
                                                  const CameraPlacement& placement);
nlohmann::json landmarksToJson(const std::vector<LandmarkAnnotation>& annotations);

}  // namespace omnicam
