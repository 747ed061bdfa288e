#include "render_output.h"

#include <chrono>

#include "path_tracing_record.h"
#include "sidecar.h"

namespace omnicam::cli {

nlohmann::json renderSidecar(const Scene& scene, const Engine& engine, const CameraPlacement& placement,
                             const RenderSettings& settings, double seconds) {
  RenderRecord record;
  record.engine = engine.name();
  record.engineVersion = engine.version();
  record.scenePath = scene.path;
  record.sceneSha256 = scene.sha256;
  record.sceneInputs = scene.inputDigests;
  record.placement = placement;
  record.rig = settings.rig;
  record.spp = settings.spp;
  record.shading = shadingName(settings.shading);
  record.pathTracing = randomSamplingRecord(record.engine, settings);
  record.mode = engine.mode();
  record.modeOptions = engine.modeOptions();
  record.seconds = seconds;
  return sidecarJson(record);
}

RenderedFile renderPose(const Scene& scene, Engine& engine, const CameraPlacement& placement,
                        const RenderSettings& settings) {
  const auto start = std::chrono::steady_clock::now();
  RenderedFile result{engine.render(placement, settings), {}};
  const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  result.sidecar = renderSidecar(scene, engine, placement, settings, seconds);
  return result;
}

void addImageFiles(std::vector<FileBytes>& files, const std::string& out, const ImageRGBA& image, const nlohmann::json& sidecar) {
  files.push_back({out, encodeImage(out, image)});
  const std::string text = sidecarText(sidecar);
  files.push_back({sidecarPath(out), std::vector<unsigned char>(text.begin(), text.end())});
}

void writeRendered(const std::string& out, const RenderedFile& rendered) {
  std::vector<FileBytes> files;
  addImageFiles(files, out, rendered.image, rendered.sidecar);
  writeFilesTogether(files);
}

RenderedFile renderToFile(const Scene& scene, Engine& engine, const CameraPlacement& placement,
                          const RenderSettings& settings, const std::string& out, const nlohmann::json& extra) {
  RenderedFile rendered = renderPose(scene, engine, placement, settings);
  rendered.sidecar.update(extra);
  writeRendered(out, rendered);
  return rendered;
}

}  // namespace omnicam::cli
