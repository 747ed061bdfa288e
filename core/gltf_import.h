#pragma once
// Reads a glTF 2.0 arena (.glb or .gltf, e.g. authored in Blender) into omnicam meshes and
// materials: triangle primitives of the default scene's nodes with their transforms, base
// colour factor × base colour texture (8-bit textures sRGB-decoded), TEXCOORD_0. glTF's +Y-up
// axes become omnicam's +Z-up: (X, Y, Z)_glTF → (X, −Z, Y). Nodes named omnicam_* (an
// exported rig) are skipped.
#include <string>
#include <vector>

#include "scene.h"

namespace omnicam {

struct GltfArena {
  std::vector<Material> materials;
  std::vector<SceneObject> objects;  // SceneObject::material indexes `materials`
};

// Throws InputError("<file>: <what>") for unreadable files and unsupported content.
GltfArena importGltf(const std::string& path);

}  // namespace omnicam
