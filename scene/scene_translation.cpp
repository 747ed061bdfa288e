#include "scene_translation.h"

#include <cmath>

#include "overloaded.h"

namespace omnicam {

namespace {

void translateShape(Shape& shape, const Vec3& offset) {
  std::visit(Overloaded{[&](Box& b) { b.center += offset; }, [&](Cylinder& c) {
                          c.base += offset;
                          c.top += offset;
                        },
                        [&](Sphere& s) { s.center += offset; }, [&](Quad& q) { q.origin += offset; },
                        [&](Disc& d) { d.center += offset; },
                        [&](Mesh& m) {
                          for (Vec3& v : m.vertices) v += offset;
                        }},
             shape);
}

RobotPose translatedPose(RobotPose pose, const Vec3& offset) {
  pose.x += offset.x();
  pose.y += offset.y();
  return pose;
}

}  // namespace

Scene translatedScene(const Scene& scene, const Vec3& offset) {
  Scene moved = scene;
  for (SceneObject& object : moved.objects) translateShape(object.shape, offset);
  for (PointLight& light : moved.lights) light.position += offset;
  for (Landmark& landmark : moved.landmarks) landmark.position += offset;
  for (CameraPath& path : moved.paths)
    for (RobotPose& pose : path.poses) pose = translatedPose(pose, offset);
  moved.startPose = translatedPose(moved.startPose, offset);
  for (CalibrationTarget& target : moved.calibrationTargets) target.worldFromTarget.pretranslate(offset);
  return moved;
}

// (+ 0.0 turns round(-0.4) = -0 into 0, which prints as it reads.)
Vec3 wholeMetreNear(const RobotPose& pose) { return {std::round(pose.x) + 0.0, std::round(pose.y) + 0.0, 0.0}; }

EngineFrame engineFrameNear(const Scene& scene, const std::vector<CameraPlacement>& placements) {
  const Vec3 origin = placements.empty() ? Vec3::Zero() : wholeMetreNear(placements.front().robot());
  EngineFrame frame{origin, std::nullopt, {}};
  if (!origin.isZero()) frame.movedScene = translatedScene(scene, -origin);
  for (const CameraPlacement& placement : placements) frame.placements.push_back(placement.translated(-origin.x(), -origin.y()));
  return frame;
}

}  // namespace omnicam
