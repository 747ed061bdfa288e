#include "frame_outputs.h"

#include <map>
#include <stdexcept>
#include <tbb/parallel_for.h>

#include "coco.h"
#include "landmark_annotations.h"
#include "frame_planes.h"
#include "multilayer_frame.h"
#include "scene_ids.h"

namespace omnicam {

namespace {

std::string asString(const std::vector<unsigned char>& bytes) { return {bytes.begin(), bytes.end()}; }

// What encoding one camera's frame needs.
struct FrameToEncode {
  const Scene& scene;
  const RayScene* rays;
  const RenderSettings& settings;
  const std::string& camera;
  int index;
  const CameraPlacement& placement;
  const ImageRGBA& rgb;
  const AovFrame* aov;
  const FrameOutputPlan& plan;
  const std::vector<uint16_t>& classOfInstance;
  const std::vector<LandmarkAnnotation>& landmarks;  // for either annotation, found once
};

// An annotation's JSON text: the same document in both layouts, a file indented for reading
// (landmarks), an OpenEXR attribute compact.
std::string annotationText(const FrameToEncode& f, OutputKind kind) {
  const bool indented = f.plan.layout == DatasetLayout::Files;
  if (kind == OutputKind::Landmarks) {
    nlohmann::json doc = landmarksToJson(f.landmarks);
    doc["frame"] = f.index;
    doc["camera"] = f.camera;
    return doc.dump(indented ? 1 : -1) + "\n";
  }
  const AovFrame& aov = *f.aov;
  nlohmann::json doc = {{"frame", f.index}, {"camera", f.camera}, {"width", aov.width}, {"height", aov.height},
                        {"annotations", cocoInstanceAnnotations(aov.instance, aov.width, aov.height, f.classOfInstance,
                                                                f.plan.cocoClasses)}};
  if (!f.scene.landmarks.empty())
    doc["landmarks"] = cocoLandmarkKeypoints(f.landmarks, aov.width, aov.height);
  return doc.dump() + "\n";
}

// The files layout: one file per output, encoded as its row says.
std::string encodeOutputFile(const FrameToEncode& f, OutputKind kind, const std::string& path) {
  const OutputKindRow& row = outputRow(kind);
  const FramePlanes planes{f.rgb, f.aov, f.classOfInstance};
  const int width = planes.width(), height = planes.height(), channels = static_cast<int>(row.valuesPerPixel());
  switch (row.encoding) {
    case OutputEncoding::ColourImage: return asString(encodeImage(path, f.rgb));
    case OutputEncoding::FloatExr: return asString(encodeDataExr(path, width, height, channels, planes.floats(row.plane)));
    case OutputEncoding::HalfExr:
      return asString(encodeDataExr(path, width, height, channels, planes.floats(row.plane), ExrPrecision::Half));
    case OutputEncoding::Uint16Png: return asString(encodeUint16Png(path, width, height, planes.ids(row.plane)));
    case OutputEncoding::Json: return annotationText(f, kind);
    case OutputEncoding::MultilayerExr: break;
  }
  throw std::logic_error("encodeOutputFile: not an output of the files layout");
}

// The multilayer layout: the images as channels, the annotations in the header.
std::string encodeMultilayerFile(const FrameToEncode& f, const std::string& path) {
  std::map<OutputKind, std::string> annotations;
  for (OutputKind kind : f.plan.outputs)
    if (isAnnotation(kind)) annotations[kind] = annotationText(f, kind);
  return asString(encodeMultilayerFrame(path, FramePlanes{f.rgb, f.aov, f.classOfInstance}, f.plan.outputs, annotations,
                                        f.plan.compression));
}

}  // namespace

std::vector<EncodedFile> encodeFrameOutputs(const Scene& scene, const RayScene* rays, const RenderSettings& settings,
                                            const std::string& camera, int index, const CameraPlacement& placement,
                                            const ImageRGBA& rgb, const AovFrame* aov, const FrameOutputPlan& plan,
                                            const std::vector<uint16_t>& classOfInstance) {
  if (plan.anyAov() && !aov) throw std::logic_error("encodeFrameOutputs: AOVs asked for but not rendered");
  const bool landmarksUsed = plan.needsLandmarkAnnotations(!scene.landmarks.empty());
  const std::vector<LandmarkAnnotation> landmarks =
      landmarksUsed ? annotateLandmarks(scene, *rays, settings.rig, placement) : std::vector<LandmarkAnnotation>{};
  const FrameToEncode frame{scene, rays, settings, camera, index, placement, rgb, aov, plan, classOfInstance, landmarks};
  std::vector<EncodedFile> files;
  for (OutputKind kind : plan.fileKinds()) files.push_back({kind, plan.framePath(camera, kind, index), {}});
  // Each file is encoded on its own task: PNG and EXR compression dominate at 1 spp.
  tbb::parallel_for(size_t{0}, files.size(), [&](size_t k) {
    EncodedFile& file = files[k];
    file.bytes = outputRow(file.kind).encoding == OutputEncoding::MultilayerExr ? encodeMultilayerFile(frame, file.relativePath)
                                                     : encodeOutputFile(frame, file.kind, file.relativePath);
  });
  // Inside a cancelled parallel_for (a neighbouring frame failed) the loop above ends early
  // without an error: a file left unencoded must never reach a writer as an empty success.
  for (const EncodedFile& file : files)
    if (file.bytes.empty()) throw std::runtime_error(file.relativePath + ": encoding was cancelled");
  return files;
}

}  // namespace omnicam
