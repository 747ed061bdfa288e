#pragma once
// A scene and its cameras moved together, for the ground-truth engines: POV-Ray's intersection
// tolerances and glTF's 32-bit floats lose the mirror's micrometres a kilometre from the origin
// (fast vs POV-Ray fell from 83 dB to 30 dB at 2 km), while omnicam's own numbers hold across the
// ±10 km scenes may span. Each engine is given a world whose origin is the whole metre nearest the
// robot; moving everything alike changes no image.
#include <optional>
#include <vector>

#include "placement.h"
#include "scene.h"

namespace omnicam {

// The scene moved by `offset`: every position (objects, lights, landmarks, poses, targets);
// sizes, directions, materials and the environment (light from infinitely far) as they were.
Scene translatedScene(const Scene& scene, const Vec3& offset);

// The whole metre nearest the robot, on the floor: a round origin, so that an exported file's
// numbers read as distances from it.
Vec3 wholeMetreNear(const RobotPose& pose);

// A world for the engines, its origin at omnicam's world point `worldOrigin`.
struct EngineFrame {
  Vec3 worldOrigin;
  std::optional<Scene> movedScene;  // empty where the world's origin serves: no copy of its meshes
  std::vector<CameraPlacement> placements;
  const Scene& sceneOr(const Scene& worldScene) const { return movedScene ? *movedScene : worldScene; }
};
// The engine's world near the first placement's robot (unmoved when that is the origin already).
EngineFrame engineFrameNear(const Scene& scene, const std::vector<CameraPlacement>& placements);

}  // namespace omnicam
