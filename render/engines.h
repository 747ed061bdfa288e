#pragma once
// The renderer interface behind --engine and every verb that renders (render, dataset, study,
// demo): omnicam's fast renderer and the two ground truths, POV-Ray and Blender.
#include <functional>
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
  explicit Engine(EngineKind kind) : kind_(kind) {}
  virtual ~Engine() = default;
  // Which engine (and mode) this is, and so its names and what it can render
  // (engine_capabilities.h: one row each).
  EngineKind kind() const { return kind_; }
  const EngineCapabilities& capabilities() const { return capabilitiesOf(kind_); }
  std::string name() const { return capabilities().engine; }
  // The rendering mode and its options, as sidecars and manifests record them.
  std::string mode() const { return omniModeName(capabilities().mode); }
  virtual nlohmann::json modeOptions() const { return nlohmann::json::object(); }
  virtual std::string version() const = 0;

  // Exposes `film` (filmFor(settings, …)) to the rig's camera at `placement`: its colour, and its
  // AOVs when the film wants them (asked only of an engine whose capabilities have them).
  // InputError for what checkEngineRenders or checkEngineShading refuse, checked here for every
  // engine; std::invalid_argument for a film that does not fit the settings.
  void render(const CameraPlacement& placement, const RenderSettings& settings, Film& film);
  // The colour alone.
  ImageRGBA render(const CameraPlacement& placement, const RenderSettings& settings);
  // The colour of every placement with the same settings. Engines that batch render them all in
  // one session; the default renders them one by one.
  virtual std::vector<ImageRGBA> renderMany(const std::vector<CameraPlacement>& placements, const RenderSettings& settings);
  // For an engine that renders one frame in many parts (POV-Ray's moving frame: one still render
  // per readout line and instant), `onPart(0, total)` before the first and `onPart(done, total)`
  // after each; the others never call it.
  virtual void reportPartsTo(std::function<void(int done, int total)> onPart) { (void)onPart; }

 protected:
  // render() once the request is known to be one this engine renders.
  virtual void renderChecked(const CameraPlacement& placement, const RenderSettings& settings, Film& film) = 0;

 private:
  EngineKind kind_;
};

// The engine a request asks for (render_request.h: read and checked there), rendering `scene`,
// which must outlive it. The fast engine runs on TBB's threads (the caller limits them with
// tbb::global_control); request.threads > 0 caps a ground truth's render threads.
std::unique_ptr<Engine> makeEngine(const RenderRequest& request, const Scene& scene);

}  // namespace omnicam
