#pragma once
// The renderer interface behind --engine and every verb that renders (render, dataset, study,
// demo): omnicam's fast renderer and the two ground truths, POV-Ray and Blender.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "image.h"
#include "omni_mode.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

// Poses a caller hands a batching engine at once: one Blender start and one export per batch,
// a bounded number of images in memory.
inline constexpr int kFramesPerBatch = 50;

class Engine {
 public:
  virtual ~Engine() = default;
  virtual ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) = 0;
  // Every pose with the same settings. Engines with a costly start (Blender) render them all in
  // one session; the default renders them one by one.
  virtual std::vector<ImageRGBA> renderMany(const std::vector<RobotPose>& poses, const RenderSettings& settings);
  // Whether renderMany is cheaper than one render per pose (the caller then batches frames).
  virtual bool batches() const { return false; }
  // Whether render and renderAovs may run for several poses at once (from different threads).
  virtual bool concurrent() const { return false; }
  // Per-pixel ground truth (depth, instances, normals) with the image, in one pass. Only the
  // fast engine has it; ground truths write RGB only.
  virtual bool hasAovs() const { return false; }
  // InputError unless this engine renders a frame whose robot moves while the shutter is open as
  // `settings` ask (docs/motion.md, "What each engine renders"); a still frame always passes.
  // Every render checks it too; callers that write files first (datasets) ask before.
  virtual void checkMotion(const RenderSettings& settings) const;
  virtual ImageRGBA render(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs);
  // InputError unless this engine renders the rig's camera (a moved, turned or distorted one
  // needs an engine that models it; docs/physical-camera.md's table). Every render checks it too;
  // callers that write files first (datasets) ask before.
  virtual void checkCamera(const RigSpec& rig) const = 0;
  virtual std::string name() const = 0;
  virtual std::string version() const = 0;
  // The rendering mode and its options, as sidecars and manifests record them.
  virtual std::string mode() const { return "exact"; }
  virtual nlohmann::json modeOptions() const { return nlohmann::json::object(); }
};

// Throws InputError for an unknown engine name, or a mode other than exact for an engine other
// than fast. `scene` must outlive the engine. `flag` names the option in messages. `threads` > 0
// caps a ground-truth engine's render threads (the fast engine runs on TBB's threads, which the
// caller limits with tbb::global_control).
std::unique_ptr<Engine> makeEngine(const std::string& name, const Scene& scene, double timeoutSeconds = 600.0,
                                   const CubeMapOptions* mode = nullptr, const std::string& flag = "--engine",
                                   int threads = 0);
// "exact", "cubemap" or "thesis-mesh" → options (InputError naming `flag` otherwise); nullptr
// for exact.
std::unique_ptr<CubeMapOptions> parseMode(const std::string& mode, int faces, int faceSize, int polygons,
                                          const std::string& flag = "--mode");

}  // namespace omnicam
