#pragma once
// In-memory scene: what every engine renders. Loaded and validated by scene_loader.h; the JSON
// format is documented in docs/scene-format.md.
#include <memory>
#include <optional>
#include <string>
#include <variant>
#include <vector>

#include "calibration_target.h"
#include "environment.h"
#include "geometry.h"
#include "rig.h"
#include "robot_pose.h"
#include "texture.h"

namespace omnicam {

struct Material {
  std::string name;
  Vec3f color{1.0f, 1.0f, 1.0f};  // linear RGB albedo
  std::shared_ptr<const Texture> texture;  // multiplies color; null if none
  std::string texturePath;                 // as given in the scene (relative to it)
  Eigen::Vector2d textureScale{1.0, 1.0};  // UV repeats
  float ambient = 0.2f;
  float diffuse = 0.8f;
  std::string semanticClass;  // "class" in the scene; empty = none
  // Emitted radiance (linear RGB, the image's units), from both sides; light for `path` shading
  // and Blender only (docs/conventions.md §3).
  Vec3f emission{0.0f, 0.0f, 0.0f};
};

// Axis-aligned in its own frame, rotated by yaw about +Z around its centre.
struct Box {
  Vec3 center, size;
  double yawDeg = 0.0;
};
// Finite cylinder from base to top (open or capped).
struct Cylinder {
  Vec3 base, top;
  double radius;
  bool caps = true;
};
struct Sphere {
  Vec3 center;
  double radius;
};
// Parallelogram origin + s·edgeU + t·edgeV, s, t ∈ [0, 1]; UV = (s, t).
struct Quad {
  Vec3 origin, edgeU, edgeV;
};
// Flat disc, optionally with a concentric hole (an annulus).
struct Disc {
  Vec3 center, normal;
  double radius, innerRadius = 0.0;
};
struct Mesh {
  std::vector<Vec3> vertices;
  std::vector<Eigen::Vector3i> triangles;
  std::vector<Eigen::Vector2d> uvs;  // empty or one per vertex
};

using Shape = std::variant<Box, Cylinder, Sphere, Quad, Disc, Mesh>;

struct SceneObject {
  std::string name;
  int material = 0;  // index into Scene::materials
  Shape shape;
  std::string semanticClass;  // "class" in the scene; empty = the material's
};

struct PointLight {
  std::string name;
  Vec3 position;
  Vec3f intensity{1.0f, 1.0f, 1.0f};
  // 0: a point. > 0: a luminaire of real size, a disc of this diameter (metres) at `position`
  // facing straight down with the point's power. Only the path tracer (Blender) renders the disc;
  // the fast renderer and POV-Ray light from its centre (docs/conventions.md §3).
  double diameter = 0.0;
};

// A known landmark (one colour band of a beacon, say): ground truth for detection.
struct Landmark {
  std::string name;
  Vec3 position;  // centre
  double diameter, height;
  std::string colourClass;
};

struct CameraPath {
  std::string name;
  std::vector<RobotPose> poses;
};

// A file the scene reads beyond its own text (a texture, an environment map, a glTF file and its
// buffers and images): its path as the scene writes it, from the scene's folder ('/'-separated,
// lexically normal: the same on every machine; an absolute one, or Blender's named world, by its
// full path) and the SHA-256 of its bytes. A dataset compares them on resume and merge, a sidecar records them: a scene whose
// texture changed is another scene although its own bytes did not.
struct SceneInputFile {
  std::string path;
  std::string sha256;
  bool operator==(const SceneInputFile&) const = default;
};

struct Scene {
  std::string path;    // file it was loaded from
  std::string sha256;  // of that file's bytes
  // Every file the scene was read from: itself, its textures, environment and glTF files and
  // theirs. An output must be none of them (writing one would destroy what is read).
  std::vector<std::string> inputFiles;
  // The files it reads beyond its own text, each once, by path (SceneInputFile).
  std::vector<SceneInputFile> inputDigests;
  std::string name;
  Vec3f background{0.0f, 0.0f, 0.0f};
  // Light from every direction for `path` shading and Blender (docs/conventions.md §3); it
  // replaces the background there. The unlit and lit modes keep `background`.
  std::optional<Environment> environment;
  RigSpec rig;
  RobotPose startPose;
  std::vector<Material> materials;
  std::vector<SceneObject> objects;
  std::vector<PointLight> lights;
  std::vector<Landmark> landmarks;
  std::vector<CameraPath> paths;
  // Each target's board is also one of `objects` (a textured quad) with a material of its own.
  std::vector<CalibrationTarget> calibrationTargets;

  const CameraPath* findPath(const std::string& pathName) const;
  // For a name findPath does not know: "has no path "x"", then the paths it has or a likely typo.
  std::string noPathText(const std::string& pathName) const;
};

// An object's semantic class: its own, else its material's, else empty (none).
const std::string& semanticClassOf(const Scene& scene, const SceneObject& object);

}  // namespace omnicam
