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
#include "render_request.h"
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

// The engine a request asks for (render_request.h: read and checked there), rendering `scene`,
// which must outlive it. The fast engine runs on TBB's threads (the caller limits them with
// tbb::global_control); request.threads > 0 caps a ground truth's render threads.
std::unique_ptr<Engine> makeEngine(const RenderRequest& request, const Scene& scene);

}  // namespace omnicam
