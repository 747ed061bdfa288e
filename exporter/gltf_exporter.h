#pragma once
// Scene → glTF 2.0 binary (.glb), with tinygltf.
//
// Axes: omnicam's world is right-handed +Z up, glTF's right-handed +Y up; every position,
// normal and node transform is converted with (X, Y, Z) → (X, Z, −Y). Units: metres.
// Contents: one node per scene object (curved primitives tessellated within a chord tolerance),
// PBR materials (base colour, metallic 0, roughness 1, double-sided) with embedded textures
// (8-bit sRGB PNGs) and their scene index in extras.omnicam.material_index,
// KHR_lights_punctual point lights, landmark nodes, and the camera rig — a node at the pose
// holding the certified mirror mesh (analytic normals), a black rim mask and the physical
// pinhole camera — with omnicam's parameters in `extras`.
#include <string>
#include <vector>

#include "render_settings.h"
#include "placement.h"
#include "scene.h"

namespace omnicam {

struct GltfExportOptions {
  CameraPlacement placement;          // where the rig node stands (at its exposure start)
  RigSpec rig;                        // mirror and image of the rig node
  double chordTolerance = 0.2e-3;     // curved primitives (m)
  double mirrorDeviation = 0.5e-6;    // certified bound of the mirror mesh (m)
  bool includeRig = true;
};

// Node names of the rig, for people reading the file. Programs (the Blender driver, omnicam's
// importer) find the rig's nodes by extras.omnicam.role, lights by extras.omnicam.light_index:
// a user's object may have any name, "omnicam_rig" included.
inline constexpr const char* kGltfRigNode = "omnicam_rig";
inline constexpr const char* kGltfMirrorNode = "omnicam_mirror";
inline constexpr const char* kGltfRimMaskNode = "omnicam_rim_mask";
inline constexpr const char* kGltfCameraNode = "omnicam_camera";

// The scene as a binary glTF (.glb). Throws InputError if a texture cannot be embedded.
std::string gltfBytes(const Scene& scene, const GltfExportOptions& options);
// gltfBytes, written to `path` atomically.
void exportGltf(const Scene& scene, const GltfExportOptions& options, const std::string& path);
// InputError unless a glTF camera can be the rig's: moved and turned pinholes and principal points
// are exported; lens distortion is not (glTF has none).
void checkGltfCamera(const RigSpec& rig);

}  // namespace omnicam
