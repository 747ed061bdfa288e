#include "blender_renderer.h"

#include "engine_capabilities.h"
#include "film.h"

#include <chrono>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iterator>
#include <numeric>
#include <optional>
#include <nlohmann/json.hpp>

#include "atomic_file.h"
#include "errors.h"
#include "exr_channels.h"
#include "file_confinement.h"
#include "image.h"
#include "make_camera.h"
#include "external_process.h"
#include "gltf_exporter.h"
#include "physical_camera.h"
#include "indirect_filter.h"
#include "data_files.h"
#include "job_folder.h"
#include "motion.h"
#include "number_format.h"
#include "scene_translation.h"
#include "sha256.h"
#include "texture_image.h"


namespace omnicam {

namespace fs = std::filesystem;

std::string blenderDriverFile(const BlenderOptions& options) {
  if (!options.driver.empty()) return options.driver;
  if (const char* env = std::getenv("OMNICAM_BLENDER_DRIVER")) return env;
  return dataFile("refrender/blender_driver.py").string();
}

namespace {

// docs/conventions.md §2's lights have no fall-off; Blender's are physical. A point light of P watts gives a
// Lambertian surface at distance d the radiance ρ·P/(4π²d²): match I at a typical distance.
constexpr double kLightMatchDistance = 3.0;

// An OpenEXR Cycles wrote (into omnicam's own job folder), every float channel read once.
struct PassChannels {
  std::vector<std::string> names;
  std::vector<float> data;  // interleaved per pixel
};

constexpr size_t kMaxPassChannels = 64;

PassChannels readExr(const std::string& path, int width, int height) {
  std::ifstream in(path, std::ios::binary);
  const std::string bytes((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  ExrChannels decoded;
  try {
    decoded = decodeExrChannels(bytes, showPath(path));
  } catch (const InputError& e) {
    throw ExternalError("blender: unreadable output " + showPath(path) + ": " + oneLine(e.what()));
  }
  if (decoded.width != width || decoded.height != height || decoded.floats.empty() || decoded.floats.size() > kMaxPassChannels)
    throw ExternalError("blender: output " + showPath(path) + " is not " + std::to_string(width) + "×" +
                        std::to_string(height) + " px with 1-" + std::to_string(kMaxPassChannels) + " float channels");
  const size_t pixels = static_cast<size_t>(width) * height, count = decoded.floats.size();
  PassChannels exr{{}, std::vector<float>(pixels * count)};
  for (const auto& [name, values] : decoded.floats) {
    const size_t c = exr.names.size();
    exr.names.push_back(name);
    for (size_t p = 0; p < pixels; ++p) exr.data[p * count + c] = values[p];
  }
  return exr;
}

// The channels named `suffixes` ("Combined.R": any view layer's), interleaved per pixel.
std::vector<float> channels(const PassChannels& exr, const std::vector<std::string>& suffixes, const std::string& path) {
  const size_t count = exr.names.size(), pixels = exr.data.size() / count;
  std::vector<float> out(pixels * suffixes.size());
  for (size_t c = 0; c < suffixes.size(); ++c) {
    std::vector<size_t> matches;
    for (size_t k = 0; k < count; ++k) {
      const std::string& name = exr.names[k];
      if (name == suffixes[c] || (name.size() > suffixes[c].size() && name.compare(name.size() - suffixes[c].size() - 1,
                                                                                    std::string::npos, "." + suffixes[c]) == 0))
        matches.push_back(k);
    }
    if (matches.size() != 1)
      throw ExternalError("blender: output " + showPath(path) + " has " + std::to_string(matches.size()) + " channels named " +
                          quote(suffixes[c]) + ", not one");
    for (size_t p = 0; p < pixels; ++p) out[p * suffixes.size() + c] = exr.data[p * count + matches.front()];
  }
  return out;
}

ImageRGBA rgbaFrom(const std::vector<float>& rgb, int width, int height) {
  ImageRGBA image(width, height);
  for (size_t k = 0; k < static_cast<size_t>(width) * height; ++k)
    for (size_t c = 0; c < 3; ++c) image.pixels[4 * k + c] = rgb[3 * k + c];
  return image;
}

}  // namespace

ImageRGBA readFilteredBlenderFrame(const std::string& full, const std::string& direct, int width, int height) {
  const PassChannels passes = readExr(full, width, height), twin = readExr(direct, width, height);
  IndirectFilterInputs in;
  in.full = rgbaFrom(channels(passes, {"Combined.R", "Combined.G", "Combined.B"}, full), width, height);
  in.direct = rgbaFrom(channels(twin, {"R", "G", "B"}, direct), width, height);
  in.albedo = channels(passes, {"Denoising Albedo.R", "Denoising Albedo.G", "Denoising Albedo.B"}, full);
  in.normal = channels(passes, {"Denoising Normal.X", "Denoising Normal.Y", "Denoising Normal.Z"}, full);
  in.depth = channels(passes, {"Denoising Depth.Z"}, full);
  return filterIndirectLight(in);
}

static bool blenderChosenByEnvironment() {
  const char* exe = std::getenv("OMNICAM_BLENDER");
  return exe && *exe;
}

std::string blenderExecutable() { return blenderChosenByEnvironment() ? std::getenv("OMNICAM_BLENDER") : "blender"; }

nlohmann::json PathTracing::toJson() const {
  return {{"diffuse_bounces", diffuseBounces},
          {"glossy_bounces", glossyBounces},
          {"clamp_indirect", clampIndirect},
          {"mirror_seen_by_indirect_rays", mirrorSeenByIndirectRays},
          {"direct_pass", filterIndirect}};
}

std::string blenderVersion(const std::string& executable) {
  JobFolder job("omnicam-blender", false);
  const ProcessResult r = runRenderer({executable, "--version"}, job.path(), job.path() + "/version.log", 60.0);
  if (r.exitCode != 0) return "";
  const std::string tail = tailOfFile(job.path() + "/version.log", 200);
  const size_t at = tail.find("Blender ");
  return at == std::string::npos ? "blender" : tail.substr(at, tail.find('\n', at) - at);
}

namespace {

// Cycles' motion steps for the moving rig: 2^6 intervals over the exposure.
constexpr int kBlenderMotionSteps = 7;

// A rigid transform as the job's 4×4 rows.
nlohmann::json matrixRows(const Rigid& transform) {
  nlohmann::json rows = nlohmann::json::array();
  for (int i = 0; i < 4; ++i) {
    nlohmann::json row = nlohmann::json::array();
    for (int j = 0; j < 4; ++j) row.push_back(transform.matrix()(i, j));
    rows.push_back(row);
  }
  return rows;
}

// The rig's placements over a moving frame's exposure, for Cycles' transform motion blur: the
// exact arc at 2^(steps − 1) + 1 evenly spaced instants, the instants at which Cycles samples
// an object's motion with `steps` motion steps, so that its interpolation runs between exact
// poses (docs/motion.md, "How the ground truth is built").
nlohmann::json blenderMotion(const RenderSettings& settings, const CameraPlacement& placement) {
  const int intervals = 1 << (kBlenderMotionSteps - 1);
  nlohmann::json placements = nlohmann::json::array();
  for (int k = 0; k <= intervals; ++k) {
    const double t = settings.rig.shutter.exposureS * k / intervals;
    placements.push_back(matrixRows(placement.worldFromViewpoint(settings.rig, t)));
  }
  return {{"exposure_s", settings.rig.shutter.exposureS}, {"motion_steps", kBlenderMotionSteps},
          {"world_from_viewpoint", placements}};
}

// The job's camera: the pinhole's focal length and principal point (a mirror rig's physical camera,
// or a lens camera's pinhole), or a lens camera as Cycles' panoramic camera (docs/blender.md,
// "Lens cameras"; Cycles 3.4 kernel/camera/projection.h). Cycles' panoramic image coordinates
// run over [0, 1] across the image, v up, pixel centres at ½; the sensor is 36 mm wide.
nlohmann::json cyclesLensCamera(const LensCameraSpec& lens) {
  if (const auto* p = std::get_if<PinholeRadTan>(&lens.model))
    return {{"lens_camera", true}, {"focal_length_px", p->fx}, {"principal_point_px", {p->cx + 0.5, p->cy + 0.5}}};
  constexpr double kSensorWidthMm = 36.0;
  const double w = lens.width, h = lens.height, mmPerPixel = kSensorWidthMm / w;
  nlohmann::json panorama = {{"sensor_width_mm", kSensorWidthMm}, {"shift_x", 0.0}, {"shift_y", 0.0}};
  if (const auto* e = std::get_if<Equirectangular>(&lens.model)) {
    panorama.update({{"type", "EQUIRECTANGULAR"}, {"longitude_min", e->lonMinRad}, {"longitude_max", e->lonMaxRad},
                     {"latitude_min", e->latMinRad}, {"latitude_max", e->latMaxRad}});
    return {{"lens_camera", true}, {"panorama", panorama}};
  }
  const auto& f = std::get<FThetaLens>(lens.model);
  // The principal point (OpenCV's, centres at integers) as a shift of the image's [0, 1] square.
  panorama["shift_x"] = (0.5 * w - (f.cx + 0.5)) / w;
  panorama["shift_y"] = (f.cy + 0.5 - 0.5 * h) / h;
  panorama["fov"] = 2.0 * f.maxThetaRad;
  // Cycles' equidistant fisheye spans the image's [0, 1] square with its circle (θ = r·fov/2):
  // exactly ours when the circle touches the sides of a square image; any other is θ = r/f, a
  // lens polynomial θ(r_mm) = −(k0 + k1 r + …) in Cycles' sign.
  std::array<double, 5> k = f.k;
  switch (f.kind) {
    case FThetaLens::Kind::Equidistant:
      if (lens.width == lens.height && std::abs(2.0 * f.maxThetaRad * f.f - w) <= 1e-12 * w && panorama["shift_x"] == 0.0 &&
          panorama["shift_y"] == 0.0) {
        panorama["type"] = "FISHEYE_EQUIDISTANT";
        return {{"lens_camera", true}, {"panorama", panorama}};
      }
      k = {0.0, 1.0 / f.f, 0.0, 0.0, 0.0};
      break;
    case FThetaLens::Kind::Equisolid:
      panorama.update({{"type", "FISHEYE_EQUISOLID"}, {"lens_mm", f.f * mmPerPixel}});
      return {{"lens_camera", true}, {"panorama", panorama}};
    case FThetaLens::Kind::Polynomial: break;
  }
  nlohmann::json coefficients = nlohmann::json::array();
  for (size_t i = 0; i < k.size(); ++i) coefficients.push_back(-k[i] / std::pow(mmPerPixel, static_cast<double>(i)));
  panorama.update({{"type", "FISHEYE_LENS_POLYNOMIAL"}, {"polynomial", coefficients}});
  return {{"lens_camera", true}, {"panorama", panorama}};
}

nlohmann::json cyclesCamera(const RigSpec& rig) {
  return std::visit(Overloaded{[](const MirrorRig& mirror) {
                                 const Pinhole pinhole = pinholeOf(mirror);
                                 return nlohmann::json{{"focal_length_px", pinhole.focalPx},
                                                       {"principal_point_px", {pinhole.principalPoint.x(), pinhole.principalPoint.y()}}};
                               },
                               [](const LensCameraSpec& lens) { return cyclesLensCamera(lens); }},
                    rig.kind);
}

}  // namespace

namespace {

// One entry per frame for the driver: where the viewpoint stands (and moves), where its
// image goes, and with `filtered` where its direct-light pass goes.
nlohmann::json jobFrames(const std::vector<CameraPlacement>& placements, const RenderSettings& settings,
                         const std::string& dir, bool filtered) {
  nlohmann::json frames = nlohmann::json::array();
  for (size_t f = 0; f < placements.size(); ++f) {
    nlohmann::json frame = {{"world_from_viewpoint", matrixRows(placements[f].worldFromViewpoint(settings.rig))},
                            {"output", dir + "/frame_" + std::to_string(f) + ".exr"}};
    if (moving(placements[f], settings.rig)) frame["motion"] = blenderMotion(settings, placements[f]);
    if (filtered) frame["direct_output"] = dir + "/frame_" + std::to_string(f) + "_direct.exr";
    frames.push_back(frame);
  }
  return frames;
}

// Where the driver says how its session spent its time: beside the glTF, in the job folder.
std::string timingsFile(const std::string& glb) { return (fs::path(glb).parent_path() / "timings.json").string(); }

// The driver's frame times, one per frame; nullopt when the file is missing or says otherwise
// (another driver, OMNICAM_BLENDER_DRIVER, need not write it).
std::optional<std::vector<double>> readFrameSeconds(const std::string& path, size_t frames) {
  try {
    std::ifstream in(path);
    const nlohmann::json timings = nlohmann::json::parse(in);
    std::vector<double> seconds = timings.at("frame_seconds").get<std::vector<double>>();
    if (seconds.size() == frames) return seconds;
  } catch (const std::exception&) {
    // Missing or not the driver's: no frame times.
  }
  return std::nullopt;
}

// The driver's job (refrender/blender_driver.py): the glTF, the shading, the lights as lamps
// of matching power, path tracing and the camera.
// `worldOrigin`: omnicam's world point at the job's origin (scene_translation.h), recorded in it.
nlohmann::json blenderJob(const Scene& scene, const Vec3& worldOrigin, const RenderSettings& settings,
                          const BlenderOptions& options, const std::string& glb, bool filtered, const nlohmann::json& frames) {
  const PathTracing& tracing = options.pathTracing;
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  double ambient = 0.0;
  for (const Material& m : scene.materials) ambient += m.ambient / scene.materials.size();
  nlohmann::json lights = nlohmann::json::array();
  for (const PointLight& l : scene.lights)
    lights.push_back({{"watts", 4.0 * kPi * kPi * kLightMatchDistance * kLightMatchDistance * l.intensity.maxCoeff()},
                      {"diameter", l.diameter}});
  nlohmann::json job = {{"glb", glb},
                              {"shading", shadingName(settings.shading)},
                              {"samples", settings.spp},
                              {"seed", options.seed + static_cast<int64_t>(settings.seed % (uint64_t{1} << 31))},
                              {"width", width},
                              {"height", height},
                              {"ambient", ambient},
                              {"background", {scene.background.x(), scene.background.y(), scene.background.z()}},
                              {"lights", lights},
                              {"path_tracing", [&] {
                                 nlohmann::json t = tracing.toJson();
                                 if (settings.shading == Shading::Path) t["diffuse_bounces"] = settings.bounces;
                                 t["direct_pass"] = filtered;
                                 return t;
                               }()},  // the driver ignores direct_pass when unlit, as `filtered` does
                              {"frames", frames},
                              {"timings_output", timingsFile(glb)}};
  job.update(cyclesCamera(settings.rig));
  job["world_origin"] = {worldOrigin.x(), worldOrigin.y(), worldOrigin.z()};
  return job;
}

// An image omnicam holds in linear floats, as an opaque float OpenEXR's bytes: Cycles reads the
// same numbers, whatever the scene's file was.
std::vector<unsigned char> linearExrBytes(const Texture& image) { return encodeImage("linear.exr", opaqueImage(image)); }

std::string textureFileName(size_t material) { return "texture_" + std::to_string(material) + ".exr"; }

bool writesEnvironment(const Scene& scene, const RenderSettings& settings) {
  return settings.shading == Shading::Path && scene.environment;
}

// Every file of a job in memory, ready to be written together (nothing half-written): scene.glb,
// each material's texture as a linear float EXR, the environment when path traced, the driver
// when `driver` is given, and job.json last. The glTF embeds its textures as 8-bit sRGB PNGs, as
// glTF must; Cycles would interpolate those before linearising them, averaging a magnified
// texture in the wrong space, so the driver swaps in the EXRs (job "textures": material index →
// file). `place` names a file of the job folder as job.json gives it.
std::vector<FileBytes> blenderJobBytes(const Scene& scene, const RenderSettings& settings,
                                       const GltfExportOptions& exportOptions, nlohmann::json job,
                                       const std::string& folder, const std::function<std::string(const std::string&)>& place,
                                       const std::optional<std::string>& driver) {
  std::vector<FileBytes> files;
  const auto add = [&](const std::string& name, auto&& bytes) {
    files.push_back({folder + "/" + name, std::vector<unsigned char>(bytes.begin(), bytes.end())});
  };
  add("scene.glb", gltfBytes(scene, exportOptions));
  job["glb"] = place("scene.glb");
  nlohmann::json textures = nlohmann::json::object();
  for (size_t m = 0; m < scene.materials.size(); ++m) {
    if (!scene.materials[m].texture) continue;
    add(textureFileName(m), linearExrBytes(*scene.materials[m].texture));
    textures[std::to_string(m)] = place(textureFileName(m));
  }
  job["textures"] = textures;
  if (writesEnvironment(scene, settings)) {
    const Environment& environment = *scene.environment;
    add("environment.exr", linearExrBytes(*environment.image));
    job["environment"] = {{"image", place("environment.exr")}, {"strength", environment.strength},
                          {"rotation_deg", environment.rotationDeg}};
  }
  if (driver) add("blender_driver.py", *driver);
  add("job.json", job.dump(2));
  return files;
}

// Runs Blender on the job in `dir`; its output's last lines (for the messages of later failures).
std::string runBlenderJob(const BlenderOptions& options, const std::string& dir) {
  const std::string log = dir + "/blender.log";
  const std::string driver = blenderDriverFile(options);
  std::vector<std::string> argv{options.executable, "-b", "--factory-startup", "-noaudio"};
  if (options.threads > 0) argv.insert(argv.end(), {"-t", std::to_string(options.threads)});
  argv.insert(argv.end(), {"--python-exit-code", "1", "-P", driver, "--", dir + "/job.json"});
  const ProcessResult r = runRenderer(argv, dir, log, options.timeoutSeconds);
  if (r.notFound)
    throw ExternalError("blender: not found: " + showPath(options.executable) +
                        (blenderChosenByEnvironment() ? " (as OMNICAM_BLENDER names it)" : " (install it with `make deps`)"));
  if (r.timedOut)
    throw ExternalError("blender: timed out after " + shortNumber(options.timeoutSeconds) +
                        " s; last output:\n" + r.logTail);
  if (r.exitCode != 0) throw ExternalError("blender: failed (exit " + std::to_string(r.exitCode) + "); last output:\n" + r.logTail);
  return r.logTail;
}

// The frames Blender wrote, each with its rim's alpha on the film's grid.
std::vector<ImageRGBA> readBlenderFrames(const nlohmann::json& frames, const RenderSettings& settings, bool filtered,
                                         const Camera& imaging, const std::string& logTail) {
  const int width = settings.rig.imageWidth(), height = settings.rig.imageHeight();
  std::vector<ImageRGBA> images;
  for (const auto& frame : frames) {
    const std::string output = frame["output"];
    for (const char* key : {"output", "direct_output"})
      if (frame.contains(key) && !fs::exists(frame[key].get<std::string>()))
        throw ExternalError("blender: no output " + showPath(frame[key].get<std::string>()) + "; last output:\n" + logTail);
    ImageRGBA image;
    try {
      image = filtered ? readFilteredBlenderFrame(output, frame["direct_output"], width, height) : readImage(output);
    } catch (const InputError& e) {
      throw ExternalError(std::string("blender: unreadable output: ") + e.what());
    }
    if (image.width != width || image.height != height)
      throw ExternalError("blender: output has the wrong size");
    // Cycles samples randomly inside the pixel; the alpha is the rim on the film's grid.
    Film film = filmFor(settings);
    film.setResolvedColour(std::move(image));
    film.setRimAlpha(imaging);
    images.push_back(film.takeImage());
  }
  return images;
}

}  // namespace

double BlenderTimings::startupSeconds() const {
  return sessionSeconds - std::accumulate(frameSeconds.begin(), frameSeconds.end(), 0.0);
}

double BlenderTimings::batchedFrameSeconds() const {
  if (frameSeconds.size() < 2) return frameSeconds.empty() ? 0.0 : frameSeconds.front();
  return std::accumulate(frameSeconds.begin() + 1, frameSeconds.end(), 0.0) / static_cast<double>(frameSeconds.size() - 1);
}

namespace {

// One Blender session; its frame times when the driver wrote them.
struct BlenderSession {
  std::vector<ImageRGBA> images;
  double seconds = 0.0;
  std::optional<std::vector<double>> frameSeconds;
  std::string logTail;
};

// InputError for what Blender cannot render, before anything is written.
void checkBlenderRenders(const std::vector<CameraPlacement>& placements, const RenderSettings& settings, const BlenderOptions& options) {
  checkRenderSettings(settings);
  const PathTracing& tracing = options.pathTracing;
  if (tracing.diffuseBounces < 0 || tracing.diffuseBounces > 16 || tracing.glossyBounces < 1 ||
      tracing.glossyBounces > 16 || !(tracing.clampIndirect >= 0.0 && tracing.clampIndirect < 1e6))
    throw InputError("blender: path tracing needs 0-16 diffuse and 1-16 glossy bounces and a clamp >= 0");
  for (const CameraPlacement& placement : placements) {
    checkPlacement(placement);
    checkEngineRenders(EngineKind::Blender, settings.rig, placement);
  }
  checkEngineShading(EngineKind::Blender, settings.shading);
}

// Cycles renders a direct-light twin of each frame, and omnicam filters the indirect light.
bool filtersIndirect(const RenderSettings& settings, const BlenderOptions& options) {
  return (options.pathTracing.filterIndirect || settings.denoise) && settings.shading != Shading::Unlit;
}

// A session's job in `folder`: every file (nothing written yet) and the frames it renders there.
struct SessionJob {
  std::vector<FileBytes> files;
  nlohmann::json frames;
  bool filtered = false;
};

SessionJob sessionJob(const Scene& worldScene, const std::vector<CameraPlacement>& worldPlacements, const RenderSettings& settings,
                      const BlenderOptions& options, const std::string& folder) {
  // glTF's 32-bit floats: the session's world has its origin near the first frame's robot.
  const EngineFrame frame = engineFrameNear(worldScene, worldPlacements);
  const Scene& scene = frame.sceneOr(worldScene);
  SessionJob job;
  job.filtered = filtersIndirect(settings, options);
  GltfExportOptions exportOptions;
  exportOptions.placement = frame.placements.front();
  exportOptions.rig = settings.rig;
  job.frames = jobFrames(frame.placements, settings, folder, job.filtered);
  job.files = blenderJobBytes(scene, settings, exportOptions,
                              blenderJob(scene, frame.worldOrigin, settings, options, folder + "/scene.glb", job.filtered, job.frames),
                              folder, [&](const std::string& name) { return folder + "/" + name; }, std::nullopt);
  return job;
}

BlenderSession runBlenderSession(const Scene& worldScene, const std::vector<CameraPlacement>& worldPlacements,
                                 const RenderSettings& settings, const BlenderOptions& options) {
  if (worldPlacements.empty()) return {};
  checkBlenderRenders(worldPlacements, settings, options);
  const std::shared_ptr<const Camera> imaging = makeCamera(settings.rig);
  JobFolder folder("omnicam-blender", options.keepJobFolder);
  const SessionJob job = sessionJob(worldScene, worldPlacements, settings, options, folder.path());
  writeFilesTogether(job.files);
  const auto started = std::chrono::steady_clock::now();
  BlenderSession session;
  session.logTail = runBlenderJob(options, folder.path());
  session.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  session.images = readBlenderFrames(job.frames, settings, job.filtered, *imaging, session.logTail);
  session.frameSeconds = readFrameSeconds(timingsFile(folder.path() + "/scene.glb"), job.frames.size());
  return session;
}

}  // namespace

std::string blenderJobDigest(const Scene& worldScene, const CameraPlacement& worldPlacement, const RenderSettings& settings,
                             const BlenderOptions& options) {
  Sha256 digest;
  for (const FileBytes& file : sessionJob(worldScene, {worldPlacement}, settings, options, ".").files) {
    digest.update(file.path + "\n" + std::to_string(file.bytes.size()) + "\n");
    digest.update(std::string_view(reinterpret_cast<const char*>(file.bytes.data()), file.bytes.size()));
  }
  digest.update(sha256OfFile(blenderDriverFile(options)));
  return digest.hex();
}

std::vector<std::string> blenderJobFiles(const Scene& scene, const RenderSettings& settings) {
  std::vector<std::string> files{"scene.glb", "job.json", "blender_driver.py"};
  for (size_t m = 0; m < scene.materials.size(); ++m)
    if (scene.materials[m].texture) files.push_back(textureFileName(m));
  if (writesEnvironment(scene, settings)) files.push_back("environment.exr");
  return files;
}

std::string blenderJobCommand() {
  return "blender -b --factory-startup -noaudio --python-exit-code 1 -P blender_driver.py -- job.json";
}

void writeBlenderJob(const Scene& worldScene, const CameraPlacement& worldPlacement, const RenderSettings& settings,
                     const std::string& dir) {
  const BlenderOptions options;
  checkBlenderRenders({worldPlacement}, settings, options);
  const EngineFrame frame = engineFrameNear(worldScene, {worldPlacement});
  const Scene& scene = frame.sceneOr(worldScene);
  const CameraPlacement& placement = frame.placements.front();
  std::string why;
  const std::optional<std::string> driver = readWholeFile(blenderDriverFile(), why);
  if (!driver) throw ExternalError(showPath(blenderDriverFile()) + ": " + why);
  GltfExportOptions exportOptions;
  exportOptions.placement = placement;
  exportOptions.rig = settings.rig;
  // Paths relative to the job's folder, where it is run; no frame-time file (omnicam's own).
  nlohmann::json frames = jobFrames({placement}, settings, ".", false);
  frames[0]["output"] = "render.exr";
  nlohmann::json job = blenderJob(scene, frame.worldOrigin, settings, options, "scene.glb", false, frames);
  job.erase("timings_output");
  writeFilesTogether(blenderJobBytes(scene, settings, exportOptions, job, dir, [](const std::string& name) { return name; }, driver));
}

std::vector<ImageRGBA> renderWithBlender(const Scene& scene, const std::vector<CameraPlacement>& placements,
                                         const RenderSettings& settings, const BlenderOptions& options) {
  return runBlenderSession(scene, placements, settings, options).images;
}

BlenderFrames renderWithBlenderTimed(const Scene& scene, const std::vector<CameraPlacement>& placements,
                                     const RenderSettings& settings, const BlenderOptions& options) {
  BlenderSession session = runBlenderSession(scene, placements, settings, options);
  if (placements.empty()) return {};
  if (!session.frameSeconds)
    throw ExternalError("blender: the driver wrote no frame times (timings.json); last output:\n" + session.logTail);
  return {std::move(session.images), {session.seconds, std::move(*session.frameSeconds)}};
}

}  // namespace omnicam
