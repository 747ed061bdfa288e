#pragma once
// The render engines behind --engine: the fast renderer and POV-Ray (Blender follows).
#include <memory>
#include <string>

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
};

// Throws InputError for an unknown engine name. `scene` must outlive the engine.
std::unique_ptr<Engine> makeEngine(const std::string& name, const Scene& scene, double timeoutSeconds = 600.0);

}  // namespace omnicam::cli
