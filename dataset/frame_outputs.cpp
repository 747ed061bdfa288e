#include "frame_outputs.h"

#include <cstdio>
#include <stdexcept>
#include <tbb/parallel_for.h>

#include "coco.h"
#include "landmark_annotations.h"

namespace omnicam {

namespace {

std::string asString(const std::vector<unsigned char>& bytes) { return {bytes.begin(), bytes.end()}; }

const char* extensionOf(const std::string& kind, const FrameOutputPlan& plan) {
  if (kind == "rgb") return plan.rgbFormat == "exr" ? "exr" : "png";
  if (kind == "depth" || kind == "normal") return "exr";
  if (kind == "landmarks" || kind == "coco") return "json";
  return "png";
}

}  // namespace

std::string frameFilePath(const std::string& camera, const std::string& kind, int index, const FrameOutputPlan& plan) {
  char name[32];
  std::snprintf(name, sizeof name, "%06d.%s", index, extensionOf(kind, plan));
  return camera + "/" + kind + "/" + name;
}

std::vector<std::string> frameFileKinds(const FrameOutputPlan& plan) {
  std::vector<std::string> kinds{"rgb"};
  for (const auto& [kind, on] : {std::pair<const char*, bool>{"depth", plan.depth}, {"instance", plan.instance},
                                 {"semantic", plan.semantic}, {"normal", plan.normal}, {"landmarks", plan.landmarks},
                                 {"coco", plan.coco}})
    if (on) kinds.push_back(kind);
  return kinds;
}

std::vector<EncodedFile> encodeFrameOutputs(const Scene& scene, const RayScene* rays, const RenderSettings& settings,
                                            const std::string& camera, int index, const RobotPose& pose,
                                            const ImageRGBA& rgb, const AovFrame* aov, const FrameOutputPlan& plan,
                                            const std::vector<uint16_t>& classOfInstance) {
  if (plan.anyAov() && !aov) throw std::logic_error("encodeFrameOutputs: AOVs asked for but not rendered");
  std::vector<EncodedFile> files;
  for (const std::string& kind : frameFileKinds(plan)) files.push_back({kind, frameFilePath(camera, kind, index, plan), {}});
  // Each file is encoded on its own task: PNG and EXR compression dominate at 1 spp.
  tbb::parallel_for(size_t{0}, files.size(), [&](size_t k) {
    EncodedFile& file = files[k];
    if (file.kind == "rgb") {
      file.bytes = asString(encodeImage(file.relativePath, rgb));
    } else if (file.kind == "depth") {
      file.bytes = asString(encodeDataExr(file.relativePath, aov->width, aov->height, 1, aov->depth.data()));
    } else if (file.kind == "normal") {
      file.bytes = asString(encodeDataExr(file.relativePath, aov->width, aov->height, 3, aov->normal.data(),
                                              ExrPrecision::Half));
    } else if (file.kind == "instance") {
      file.bytes = asString(encodeUint16Png(file.relativePath, aov->width, aov->height, aov->instance));
    } else if (file.kind == "semantic") {
      std::vector<uint16_t> semantic(aov->instance.size());
      for (size_t p = 0; p < semantic.size(); ++p) semantic[p] = classOfInstance[aov->instance[p]];
      file.bytes = asString(encodeUint16Png(file.relativePath, aov->width, aov->height, semantic));
    } else if (file.kind == "landmarks") {
      nlohmann::json doc = landmarksToJson(annotateLandmarks(scene, *rays, settings.rig, pose));
      doc["frame"] = index;
      doc["camera"] = camera;
      file.bytes = doc.dump(1) + "\n";
    } else if (file.kind == "coco") {
      nlohmann::json doc = {{"frame", index}, {"camera", camera}, {"width", aov->width}, {"height", aov->height},
                            {"annotations", cocoInstanceAnnotations(aov->instance, aov->width, aov->height, classOfInstance,
                                                                    plan.cocoClasses)}};
      if (!scene.landmarks.empty())
        doc["landmarks"] = cocoLandmarkKeypoints(annotateLandmarks(scene, *rays, settings.rig, pose), aov->width, aov->height);
      file.bytes = doc.dump() + "\n";
    }
  });
  // Inside a cancelled parallel_for (a neighbouring frame failed) the loop above ends early
  // without an error: a file left unencoded must never reach a writer as an empty success.
  for (const EncodedFile& file : files)
    if (file.bytes.empty()) throw std::runtime_error(file.relativePath + ": encoding was cancelled");
  return files;
}

}  // namespace omnicam
