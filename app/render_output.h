#pragma once
#include <nlohmann/json.hpp>
#include <string>

#include "atomic_file.h"
#include "engines.h"
#include "image.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam::cli {

struct RenderedFile {
  ImageRGBA image;
  nlohmann::json sidecar;
};

// The sidecar of a render at `placement` that took `seconds`.
nlohmann::json renderSidecar(const Scene& scene, const Engine& engine, const CameraPlacement& placement,
                             const RenderSettings& settings, double seconds);
// Renders one placement with `engine`; the sidecar describes it.
RenderedFile renderPose(const Scene& scene, Engine& engine, const CameraPlacement& placement,
                        const RenderSettings& settings);
// The image OUT and its sidecar OUT + ".json" (out.png.json), encoded, added to `files` (for
// writeFilesTogether: they appear together, or neither).
void addImageFiles(std::vector<FileBytes>& files, const std::string& out, const ImageRGBA& image, const nlohmann::json& sidecar);
// `rendered` and its sidecar, together.
void writeRendered(const std::string& out, const RenderedFile& rendered);
// Both, with `extra` merged into the sidecar.
RenderedFile renderToFile(const Scene& scene, Engine& engine, const CameraPlacement& placement,
                          const RenderSettings& settings, const std::string& out,
                          const nlohmann::json& extra = nlohmann::json::object());

}  // namespace omnicam::cli
