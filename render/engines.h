#pragma once
// The renderer interface behind --engine and every verb that renders (render, dataset, study,
// demo): omnicam's fast renderer and the two ground truths, POV-Ray and Blender.
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "aov_frame.h"
#include "engine_capabilities.h"
#include "film.h"
#include "image.h"
#include "omni_mode.h"
#include "render_settings.h"
#include "scene.h"

namespace omnicam {

// Frames a caller hands a batching engine at once: one Blender start and one export per batch,
// a bounded number of images in memory.
inline constexpr int kFramesPerBatch = 50;

class Engine {
 public:
  virtual ~Engine() = default;
  // Which engine (and mode) this is, and so what it can render (engine_capabilities.h).
  virtual EngineKind kind() const = 0;
  const EngineCapabilities& capabilities() const { return capabilitiesOf(kind()); }
  // Exposes `film` (filmFor(settings, …)) to the rig's camera at `placement`: its colour, and its
  // AOVs when the film wants them (asked only of an engine whose capabilities have them).
  // InputError for what checkEngineRenders refuses.
  virtual void render(const CameraPlacement& placement, const RenderSettings& settings, Film& film) = 0;
  // The colour alone.
  ImageRGBA render(const CameraPlacement& placement, const RenderSettings& settings);
  // The colour of every placement with the same settings. Engines that batch render them all in
  // one session; the default renders them one by one.
  virtual std::vector<ImageRGBA> renderMany(const std::vector<CameraPlacement>& placements, const RenderSettings& settings);
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
