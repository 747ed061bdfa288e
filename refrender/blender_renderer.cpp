#include "blender_renderer.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "errors.h"
#include "external_process.h"
#include "gltf_exporter.h"
#include "job_folder.h"

namespace omnicam {

namespace fs = std::filesystem;

namespace {

std::string defaultDriver() {
  if (const char* env = std::getenv("OMNICAM_BLENDER_DRIVER")) return env;
  return OMNICAM_BLENDER_DRIVER;
}

// docs/conventions.md §2's lights have no fall-off; Blender's are physical. A point light of P watts gives a
// Lambertian surface at distance d the radiance ρ·P/(4π²d²): match I at a typical distance.
constexpr double kLightMatchDistance = 3.0;

}  // namespace

std::string blenderExecutable() {
  const char* exe = std::getenv("OMNICAM_BLENDER");
  return exe ? exe : "blender";
}

nlohmann::json PathTracing::toJson() const {
  return {{"diffuse_bounces", diffuseBounces},
          {"glossy_bounces", glossyBounces},
          {"clamp_indirect", clampIndirect},
          {"mirror_seen_by_indirect_rays", mirrorSeenByIndirectRays}};
}

std::string blenderVersion(const std::string& executable) {
  JobFolder job("omnicam-blender", false);
  const ProcessResult r = runProcess({executable, "--version"}, job.path(), job.path() + "/version.log", 60.0);
  if (r.exitCode != 0) return "";
  const std::string tail = tailOfFile(job.path() + "/version.log", 200);
  const size_t at = tail.find("Blender ");
  return at == std::string::npos ? "blender" : tail.substr(at, tail.find('\n', at) - at);
}

std::vector<ImageRGBA> renderWithBlender(const Scene& scene, const std::vector<RobotPose>& poses,
                                         const RenderSettings& settings, const BlenderOptions& options) {
  if (poses.empty()) return {};
  checkRenderSettings(settings);
  const PathTracing& tracing = options.pathTracing;
  if (tracing.diffuseBounces < 0 || tracing.diffuseBounces > 16 || tracing.glossyBounces < 1 ||
      tracing.glossyBounces > 16 || !(tracing.clampIndirect >= 0.0 && tracing.clampIndirect < 1e6))
    throw InputError("blender: path tracing needs 0-16 diffuse and 1-16 glossy bounces and a clamp >= 0");
  for (const RobotPose& pose : poses) checkPose(pose, "--pose");
  const OmniCamera camera = settings.rig.camera();
  JobFolder folder("omnicam-blender", options.keepJobFolder);
  const std::string glb = folder.path() + "/scene.glb";
  GltfExportOptions exportOptions;
  exportOptions.pose = poses.front();
  exportOptions.rig = settings.rig;
  exportGltf(scene, exportOptions, glb);

  nlohmann::json frames = nlohmann::json::array();
  for (size_t f = 0; f < poses.size(); ++f) {
    const Rigid worldFromViewpoint = worldFromRobot(poses[f]) * robotFromViewpoint(settings.rig);
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 4; ++i) {
      nlohmann::json row = nlohmann::json::array();
      for (int j = 0; j < 4; ++j) row.push_back(worldFromViewpoint.matrix()(i, j));
      rows.push_back(row);
    }
    frames.push_back({{"world_from_viewpoint", rows}, {"output", folder.path() + "/frame_" + std::to_string(f) + ".exr"}});
  }
  double ambient = 0.0;
  for (const Material& m : scene.materials) ambient += m.ambient / scene.materials.size();
  nlohmann::json lights = nlohmann::json::array();
  for (const PointLight& l : scene.lights)
    lights.push_back({{"watts", 4.0 * kPi * kPi * kLightMatchDistance * kLightMatchDistance * l.intensity.maxCoeff()},
                      {"diameter", l.diameter}});
  const nlohmann::json job = {{"glb", glb},
                              {"shading", shadingName(settings.shading)},
                              {"samples", settings.spp},
                              {"seed", options.seed},
                              {"width", camera.width()},
                              {"height", camera.height()},
                              {"focal_length_px", camera.physicalFocalLength()},
                              {"ambient", ambient},
                              {"lights", lights},
                              {"path_tracing", options.pathTracing.toJson()},
                              {"frames", frames}};
  writeTextAtomically(folder.path() + "/job.json", job.dump(2));

  const std::string log = folder.path() + "/blender.log";
  const std::string driver = options.driver.empty() ? defaultDriver() : options.driver;
  std::vector<std::string> argv{options.executable, "-b", "--factory-startup", "-noaudio"};
  if (options.threads > 0) argv.insert(argv.end(), {"-t", std::to_string(options.threads)});
  argv.insert(argv.end(), {"--python-exit-code", "1", "-P", driver, "--", folder.path() + "/job.json"});
  const ProcessResult r = runProcess(argv, folder.path(), log, options.timeoutSeconds);
  if (r.notFound) throw ExternalError("blender: not found (install it with `make deps`): " + showPath(options.executable));
  if (r.timedOut)
    throw ExternalError("blender: timed out after " + std::to_string(static_cast<int>(options.timeoutSeconds)) +
                        " s; last output:\n" + r.logTail);
  if (r.exitCode != 0) throw ExternalError("blender: failed (exit " + std::to_string(r.exitCode) + "); last output:\n" + r.logTail);

  // Cycles samples randomly inside the pixel; alpha is the rim geometry on the spp grid.
  const int n = std::max(1, static_cast<int>(std::lround(std::sqrt(static_cast<double>(settings.spp)))));
  std::vector<ImageRGBA> images;
  for (const auto& frame : frames) {
    const std::string output = frame["output"];
    if (!fs::exists(output)) throw ExternalError("blender: no output " + showPath(output) + "; last output:\n" + r.logTail);
    ImageRGBA image;
    try {
      image = readImage(output);
    } catch (const InputError& e) {
      throw ExternalError(std::string("blender: unreadable output: ") + e.what());
    }
    if (image.width != camera.width() || image.height != camera.height())
      throw ExternalError("blender: output has the wrong size");
    for (int j = 0; j < image.height; ++j)
      for (int i = 0; i < image.width; ++i) image.at(i, j)[3] = camera.rimCoverage(i, j, n);
    images.push_back(std::move(image));
  }
  return images;
}

}  // namespace omnicam
