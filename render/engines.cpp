#include "engines.h"

#include <cstdlib>
#include <optional>

#include "blender_renderer.h"
#include "cubemap_renderer.h"
#include "errors.h"
#include "fast_renderer.h"
#include "povray_exporter.h"
#include "povray_renderer.h"

namespace omnicam {

std::vector<ImageRGBA> Engine::renderMany(const std::vector<CameraPlacement>& placements, const RenderSettings& settings) {
  std::vector<ImageRGBA> images;
  images.reserve(placements.size());
  for (const CameraPlacement& placement : placements) images.push_back(render(placement, settings));
  return images;
}

void Engine::render(const CameraPlacement& placement, const RenderSettings& settings, Film& film) {
  checkEngineRenders(kind_, settings.rig, placement, film.wantsAovs());
  checkEngineShading(kind_, settings.shading);
  film.requireFits(settings, capabilities().shownName);
  renderChecked(placement, settings, film);
}

ImageRGBA Engine::render(const CameraPlacement& placement, const RenderSettings& settings) {
  Film film = filmFor(settings);
  render(placement, settings, film);
  return film.takeImage();
}

namespace {

class FastEngine : public Engine {
 public:
  FastEngine(const Scene& scene, const CubeMapOptions* mode)
      : Engine(mode ? fastEngineKind(mode->mode) : EngineKind::FastExact), renderer_(scene), cubemap_(renderer_) {
    if (mode) mode_ = *mode;
  }
  void renderChecked(const CameraPlacement& placement, const RenderSettings& settings, Film& film) override {
    if (!mode_) return renderer_.render(placement, settings, film);
    // AOVs are geometric truth: always from the exact pixel → ray map, whatever the colour's mode.
    if (film.wantsAovs()) renderer_.renderAovsOnly(placement, settings, film);
    cubemap_.render(placement, settings, *mode_, film);
  }
  std::string version() const override { return fastRendererVersion(); }
  nlohmann::json modeOptions() const override {
    if (!mode_) return nlohmann::json::object();
    nlohmann::json options = {{"faces", mode_->faces}, {"face_size", mode_->faceSize}};
    if (mode_->mode == OmniMode::ThesisMesh) options["polygons"] = mode_->polygons;
    return options;
  }

 private:
  FastRenderer renderer_;
  CubeMapRenderer cubemap_;
  std::optional<CubeMapOptions> mode_;
};

class PovrayEngine : public Engine {
 public:
  PovrayEngine(const Scene& scene, double timeoutSeconds, int threads) : Engine(EngineKind::Povray), scene_(scene) {
    options_.timeoutSeconds = timeoutSeconds;
    options_.threads = threads;
    // OMNICAM_POVRAY names another POV-Ray binary (tests use it to simulate failures).
    if (const char* exe = std::getenv("OMNICAM_POVRAY")) options_.executable = exe;
  }
  void renderChecked(const CameraPlacement& placement, const RenderSettings& settings, Film& film) override {
    renderWithPovray(scene_, placement, settings, options_, film);
  }
  void reportPartsTo(std::function<void(int done, int total)> onPart) override { options_.onRenderSummed = std::move(onPart); }
  std::string version() const override {
    if (version_.empty()) version_ = povrayVersion(options_.executable);
    return version_;
  }

 private:
  const Scene& scene_;
  PovrayOptions options_;
  mutable std::string version_;
};

class BlenderEngine : public Engine {
 public:
  BlenderEngine(const Scene& scene, double timeoutSeconds, int threads) : Engine(EngineKind::Blender), scene_(scene) {
    options_.timeoutSeconds = timeoutSeconds;
    options_.threads = threads;
  }
  void renderChecked(const CameraPlacement& placement, const RenderSettings& settings, Film& film) override {
    film.setResolvedColour(std::move(renderWithBlender(scene_, {placement}, settings, options_).front()));
  }
  std::vector<ImageRGBA> renderMany(const std::vector<CameraPlacement>& placements, const RenderSettings& settings) override {
    if (placements.empty()) return {};
    return renderWithBlender(scene_, placements, settings, options_);
  }
  std::string version() const override {
    if (version_.empty()) version_ = blenderVersion(options_.executable) + " Cycles (CPU)";
    return version_;
  }

 private:
  const Scene& scene_;
  BlenderOptions options_;
  mutable std::string version_;
};

std::unique_ptr<Engine> makeEngineOf(const RenderRequest& request, const Scene& scene) {
  const std::optional<CubeMapOptions> cube = request.cubeMap();
  const std::optional<EngineKind> kind = request.engineKind();
  if (!kind) throw std::invalid_argument("makeEngine: no engine " + request.engine + " in mode " + request.mode + " (readRenderRequest checks both)");
  switch (*kind) {
    case EngineKind::FastExact:
    case EngineKind::FastCubeMap:
    case EngineKind::FastThesisMesh:
      if (cube) checkModeOptions(*cube);  // when the engine is made, not at its first frame
      return std::make_unique<FastEngine>(scene, cube ? &*cube : nullptr);
    case EngineKind::Povray: return std::make_unique<PovrayEngine>(scene, request.timeoutSeconds, request.threads);
    case EngineKind::Blender: return std::make_unique<BlenderEngine>(scene, request.timeoutSeconds, request.threads);
  }
  throw std::invalid_argument("makeEngine: an engine without a maker");
}

}  // namespace

std::unique_ptr<Engine> makeEngine(const RenderRequest& request, const Scene& scene) {
  std::unique_ptr<Engine> engine = makeEngineOf(request, scene);
  checkEngineShading(engine->kind(), request.shading);  // when the engine is made, not at its first frame
  return engine;
}

}  // namespace omnicam
