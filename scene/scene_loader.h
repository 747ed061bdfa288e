#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "file_formats.h"
#include "input_limits.h"
#include "json_text.h"
#include "scene.h"

namespace omnicam {

struct SceneLoadOptions {
  // Files a scene pulls in (textures, glTF and the glTF's buffers and images) must resolve,
  // symlinks followed, to a place inside the scene file's folder; `data:` URIs are always fine.
  // Only an explicit user flag (--allow-outside-files) lifts this.
  bool allowOutsideFolder = false;
};

// A bundled scene's name given where no such file is (an installed package's user): "; omnicam
// comes with PATH" naming omnicam's own copy, else empty.
std::string bundledSceneHint(const std::string& name);

// Loads and validates a scene file. Anything wrong — unknown field, wrong type, out-of-range
// value, duplicate name or key, missing texture, a file outside the scene's folder — throws
// InputError with one line "<file>: <field>: <what is wrong>".
Scene loadScene(const std::string& path, const SceneLoadOptions& options = {});
// The same from the file's text (`path` names it in errors and anchors relative files).
Scene loadSceneFromText(const std::string& text, const std::string& path, const SceneLoadOptions& options = {});

// A rig object (the scene's "rig", a sidecar's "rig", a --rig file), validated against the
// documented ranges (input_limits.h). `where` is its field path for errors ("rig").
RigSpec rigFromJson(const nlohmann::json& rig, const std::string& file, const std::string& where);
// A robot pose [x, y, yaw_deg] as every input file writes it (scene paths, start_pose, dataset
// pose lists): x and y within the world's bounds, the yaw within ±kMaxYawDeg as --pose takes it.
RobotPose poseFromJson(const nlohmann::json& pose, const std::string& file, const std::string& where);


}  // namespace omnicam
