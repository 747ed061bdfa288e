#pragma once
// Reads a glTF 2.0 arena (.glb or .gltf, e.g. authored in Blender) into omnicam meshes and
// materials: triangle primitives of the default scene's nodes with their transforms, base
// colour factor × base colour texture (decoded by colour space, as every image), TEXCOORD_0.
// glTF's +Y-up axes become omnicam's +Z-up: (X, Y, Z)_glTF → (X, −Z, Y). A node that an
// omnicam export marked as its camera rig (extras.omnicam.role = "rig") is skipped; names play
// no part in that, so a user's object may be called anything.
//
// Hostile files are expected: every buffer and image the file names must lie inside
// `confineTo` (symlinks resolved; `data:` URIs are fine); accessors are validated in full
// (bufferView present, type and component type per attribute, normalized flags, bounds, UV count
// = vertex count) before a byte is read; node graphs must be trees; sizes are bounded.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "scene.h"

namespace omnicam {

struct GltfArena {
  std::vector<Material> materials;
  std::vector<SceneObject> objects;  // SceneObject::material indexes `materials`
  // The files it refers to (buffers and images, not itself): each as read, its URI as the glTF
  // writes it, and the SHA-256 of the bytes read.
  struct FileRead {
    std::string file, uri, sha256;
  };
  std::vector<FileRead> filesRead;
};

struct GltfImportOptions {
  std::filesystem::path confineTo;  // empty: no confinement (the user allowed outside files)
  // Triangles the scene holds already: limits::kMaxTriangles bounds the scene, this file included.
  int64_t trianglesBefore = 0;
};

// Throws InputError("<file>: <what>") for unreadable files and unsupported or invalid content.
GltfArena importGltf(const std::string& path, const GltfImportOptions& options = {});
// The same from bytes in memory (`path` names the file in errors and anchors relative URIs).
GltfArena importGltfFromMemory(const std::string& bytes, const std::string& path, const GltfImportOptions& options = {});

}  // namespace omnicam
