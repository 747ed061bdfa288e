#pragma once
// One frame of one camera as the files its plan asks for (output_kinds.h), encoded in memory.
// Files layout: rgb (PNG/EXR), depth (float EXR, metres along the ray from F'), instance and
// semantic ids (16-bit PNG), normals (float EXR, world frame), landmark annotations (JSON) and
// the frame's part of the camera's COCO file (JSON: coco.h's annotations). Multilayer layout:
// one OpenEXR holding them all (multilayer_frame.h).
#include <string>
#include <vector>

#include "engines.h"
#include "output_kinds.h"
#include "ray_scene.h"

namespace omnicam {

struct EncodedFile {
  OutputKind kind;
  std::string relativePath;  // FrameOutputPlan::framePath
  std::string bytes;
};

// Encodes the outputs of one camera's frame: `rgb` and `aovs` as the engine rendered them (aovs
// may be null when the plan asks for none); landmarks from `rays` when the plan asks.
// `classOfInstance[i]` is the semantic class id of instance id i.
std::vector<EncodedFile> encodeFrameOutputs(const Scene& scene, const RayScene* rays, const RenderSettings& settings,
                                            const std::string& camera, int index, const CameraPlacement& placement,
                                            const ImageRGBA& rgb, const AovFrame* aovs, const FrameOutputPlan& plan,
                                            const std::vector<uint16_t>& classOfInstance);

}  // namespace omnicam
