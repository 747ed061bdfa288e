#pragma once
// The render engines behind --engine: the fast renderer and POV-Ray (Blender follows).
#include <memory>
#include <nlohmann/json.hpp>
#include <string>

#include "cubemap_renderer.h"
#include "image.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam::cli {

class Engine {
 public:
  virtual ~Engine() = default;
  virtual ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) = 0;
  virtual std::string name() const = 0;
  virtual std::string version() const = 0;
  // The rendering mode and its options, as the sidecar records them.
  virtual std::string mode() const { return "exact"; }
  virtual nlohmann::json modeOptions() const { return nlohmann::json::object(); }
};

// Throws InputError for an unknown engine name, or a mode other than exact for an engine other
// than fast. `scene` must outlive the engine.
std::unique_ptr<Engine> makeEngine(const std::string& name, const Scene& scene, double timeoutSeconds = 600.0,
                                   const CubeMapOptions* mode = nullptr);
// "exact", "cubemap" or "thesis-mesh" → options (InputError otherwise); nullptr for exact.
std::unique_ptr<CubeMapOptions> parseMode(const std::string& mode, int faces, int faceSize, int polygons);

}  // namespace omnicam::cli
