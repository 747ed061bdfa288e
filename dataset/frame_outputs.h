#pragma once
// One frame of one camera as the files the dataset layout asks for, encoded in memory:
// rgb (PNG/EXR), depth (float EXR, metres along the ray from F'), instance and semantic ids
// (16-bit PNG), normals (float EXR, world frame), landmark annotations (JSON) and the frame's
// part of the camera's COCO file (JSON: coco.h's annotations; gathered by gatherCocoFile).
#include <optional>
#include <set>
#include <string>
#include <vector>

#include "dataset_spec.h"
#include "engines.h"
#include "ray_scene.h"

namespace omnicam {

struct EncodedFile {
  std::string kind;          // "rgb", "depth", "instance", "semantic", "normal", "landmarks", "coco"
  std::string relativePath;  // "<camera>/<kind>/NNNNNN.<ext>"
  std::string bytes;
};

struct FrameOutputPlan {
  std::string rgbFormat = "png";
  bool depth = false, instance = false, semantic = false, normal = false, landmarks = false, coco = false;
  std::set<uint16_t> cocoClasses;  // class ids the COCO annotations cover
  bool anyAov() const { return depth || instance || semantic || normal || coco; }
};

// The kinds of file each camera's frame has under `plan`: "rgb", then the AOVs and "landmarks"
// it asks for, in this order.
std::vector<std::string> frameFileKinds(const FrameOutputPlan& plan);
// "<camera>/<kind>/NNNNNN.<ext>" for frame `index`.
std::string frameFilePath(const std::string& camera, const std::string& kind, int index, const FrameOutputPlan& plan);

// Encodes the outputs of one camera's frame: `rgb` and `aovs` as the engine rendered them (aovs
// may be null when the plan asks for none); landmarks from `rays` when the plan asks.
// `classOfInstance[i]` is the semantic class id of instance id i.
std::vector<EncodedFile> encodeFrameOutputs(const Scene& scene, const RayScene* rays, const RenderSettings& settings,
                                            const std::string& camera, int index, const RobotPose& pose,
                                            const ImageRGBA& rgb, const AovFrame* aovs, const FrameOutputPlan& plan,
                                            const std::vector<uint16_t>& classOfInstance);

}  // namespace omnicam
