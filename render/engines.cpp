#include "engines.h"

#include "input_limits.h"
#include "number_format.h"

#include <cstdlib>
#include <optional>

#include "blender_renderer.h"
#include "cubemap_renderer.h"
#include "errors.h"
#include "fast_renderer.h"
#include "povray_exporter.h"
#include "povray_renderer.h"

namespace omnicam {

std::vector<ImageRGBA> Engine::renderMany(const std::vector<RobotPose>& poses, const RenderSettings& settings) {
  std::vector<ImageRGBA> images;
  images.reserve(poses.size());
  for (const RobotPose& pose : poses) images.push_back(render(pose, settings));
  return images;
}

namespace {
// Engines that have no model of time refuse a moving frame rather than render it still.
void refuseMotion(const RenderSettings& settings, const std::string& engine) {
  if (moving(settings))
    throw InputError("the " + engine + " engine does not render motion yet: a moving robot needs an instantaneous global shutter "
                     "there (rig.shutter; docs/motion.md lists what each engine renders)");
}
}  // namespace

void Engine::checkMotion(const RenderSettings& settings) const { refuseMotion(settings, name()); }

ImageRGBA Engine::render(const RobotPose&, const RenderSettings&, AovFrame&) {
  throw std::logic_error("engine " + name() + " has no AOVs");
}

namespace {

class FastEngine : public Engine {
 public:
  FastEngine(const Scene& scene, const CubeMapOptions* mode) : renderer_(scene), cubemap_(renderer_) {
    if (mode) mode_ = *mode;
  }
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) override {
    if (!mode_) return renderer_.render(pose, settings);
    checkMotion(settings);
    return cubemap_.render(pose, settings, *mode_);
  }
  bool hasAovs() const override { return true; }
  void checkMotion(const RenderSettings& settings) const override {
    if (mode_) refuseMotion(settings, "fast engine's " + mode());
  }
  // Exact mode is a pure function of the pose; the cube-map modes keep per-render state.
  bool concurrent() const override { return !mode_; }
  // AOVs are geometric truth: always from the exact pixel → ray map, whatever the RGB mode.
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings, AovFrame& aovs) override {
    if (!mode_) return renderer_.render(pose, settings, aovs);
    checkMotion(settings);
    renderer_.renderAovsOnly(pose, settings, aovs);
    return cubemap_.render(pose, settings, *mode_);
  }
  void checkCamera(const RigSpec& rig) const override {
    if (mode_) checkCubeMapCamera(rig, *mode_);
  }
  std::string name() const override { return "fast"; }
  std::string version() const override { return fastRendererVersion(); }
  std::string mode() const override {
    if (!mode_) return "exact";
    return mode_->mode == OmniMode::ThesisMesh ? "thesis-mesh" : "cubemap";
  }
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
  PovrayEngine(const Scene& scene, double timeoutSeconds, int threads) : scene_(scene) {
    options_.timeoutSeconds = timeoutSeconds;
    options_.threads = threads;
    // OMNICAM_POVRAY names another POV-Ray binary (tests use it to simulate failures).
    if (const char* exe = std::getenv("OMNICAM_POVRAY")) options_.executable = exe;
  }
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) override {
    return renderWithPovray(scene_, pose, settings, options_);
  }
  void checkCamera(const RigSpec& rig) const override { checkPovrayCamera(rig); }
  void checkMotion(const RenderSettings&) const override {}  // every shutter (docs/motion.md)
  std::string name() const override { return "povray"; }
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
  BlenderEngine(const Scene& scene, double timeoutSeconds, int threads) : scene_(scene) {
    options_.timeoutSeconds = timeoutSeconds;
    options_.threads = threads;
  }
  ImageRGBA render(const RobotPose& pose, const RenderSettings& settings) override {
    return std::move(renderWithBlender(scene_, {pose}, settings, options_).front());
  }
  std::vector<ImageRGBA> renderMany(const std::vector<RobotPose>& poses, const RenderSettings& settings) override {
    if (poses.empty()) return {};
    return renderWithBlender(scene_, poses, settings, options_);
  }
  bool batches() const override { return true; }
  void checkCamera(const RigSpec& rig) const override { checkBlenderCamera(rig); }
  void checkMotion(const RenderSettings& settings) const override { checkBlenderMotion(settings); }
  std::string name() const override { return "blender"; }
  std::string version() const override {
    if (version_.empty()) version_ = blenderVersion(options_.executable) + " Cycles (CPU)";
    return version_;
  }

 private:
  const Scene& scene_;
  BlenderOptions options_;
  mutable std::string version_;
};

}  // namespace

std::unique_ptr<CubeMapOptions> parseMode(const std::string& mode, int faces, int faceSize, int polygons,
                                          const std::string& flag) {
  if (mode == "exact") return nullptr;
  auto options = std::make_unique<CubeMapOptions>();
  options->faces = faces;
  options->faceSize = faceSize;
  options->polygons = polygons;
  if (mode == "cubemap") options->mode = OmniMode::CubeMap;
  else if (mode == "thesis-mesh") options->mode = OmniMode::ThesisMesh;
  else throw InputError(flag + ": must be exact, cubemap or thesis-mesh (got " + quote(mode) + ")");
  checkCubeMapOptions(*options);  // when the engine is made, not at its first frame
  return options;
}

std::unique_ptr<Engine> makeEngine(const std::string& name, const Scene& scene, double timeoutSeconds,
                                   const CubeMapOptions* mode, const std::string& flag, int threads) {
  checkThreads(threads, "threads");
  if (!(timeoutSeconds > 0.0 && timeoutSeconds <= limits::kMaxTimeoutSeconds))
    throw InputError("timeout: must be in (0, " + shortNumber(limits::kMaxTimeoutSeconds) + "] s (got " + shortNumber(timeoutSeconds) + ")");
  if (name == "fast") return std::make_unique<FastEngine>(scene, mode);
  if (mode) throw InputError((flag == "--engine" ? std::string("--mode") : flag + ": mode") +
                             ": only the fast engine has modes other than exact");
  if (name == "povray") return std::make_unique<PovrayEngine>(scene, timeoutSeconds, threads);
  if (name == "blender") return std::make_unique<BlenderEngine>(scene, timeoutSeconds, threads);
  throw InputError(flag + ": " + quote(name) + " is not available (fast, povray, blender)");
}

}  // namespace omnicam
