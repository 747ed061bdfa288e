// omnicam rings [SCENE] [--engine fast] [--size N] [--spp N] -o OUT [--json] [--per-azimuth]
// omnicam rings [SCENE] --measure IMAGE [--json] [--per-azimuth]
// Renders the incidence-ring scene (thesis Fig. 3.11), measures every ring's radius in the
// image and scores it against the exact model and the thesis' Eq. 3.2. --per-azimuth measures
// rings that need not be circles (e.g. a --mode thesis-mesh render) sector by sector instead.
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <memory>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "make_camera.h"
#include "number_format.h"
#include "render_output.h"
#include "rings.h"
#include "scene_loader.h"
#include "sidecar.h"

namespace omnicam::cli {

namespace {

struct RingsArgs {
  std::string engine = "fast", scene, sceneArgument, out, measure;
  int size = 0, spp = 16;
  bool json = false, perAzimuth = false;
  SceneLoadOptions load;
};

// What may hide a ring: a render of few samples misses one thinner than a pixel (this rig's rings
// are circles: it is the ideal one); an image of one's own may hold rings that are not circles.
std::string ringHint(const RingsArgs& a) {
  if (a.measure.empty() && a.spp < 16) return " (a ring thinner than a pixel can fall between few samples: render with --spp 16)";
  return " (for rings that are not circles: --per-azimuth)";
}

// Measures `image` as asked, prints the result and returns it as JSON (for a sidecar). A camera
// other than the ideal one images the rings as curves, not circles: they are measured per azimuth
// against its own projection.
nlohmann::json measureAndPrint(const ImageRGBA& image, const RigSpec& rig, const std::string& what,
                               const RingsArgs& a) {
  if (a.perAzimuth || !rig.ideal() || rig.tilted()) {
    if (!a.perAzimuth && !a.json)
      std::printf("rings: the camera is %s, so its rings are not circles: measured per azimuth\n",
                  rig.tilted() ? "tilted on its mount" : "not the ideal one");
    const RingProfileReport p = measureRingProfiles(image, *makeCamera(rig), defaultRingThetasDeg(), 36, ringsFrameOf(rig));
    const nlohmann::json j = {{"per_azimuth", {{"rms_px_exact", p.rmsPx},
                                               {"max_abs_px_exact", p.maxAbsPx},
                                               {"sectors_measured", p.sectorsMeasured},
                                               {"sectors_total", p.sectorsTotal}}}};
    if (a.json) {
      std::printf("%s\n", j.dump(2).c_str());
    } else {
      std::printf("rings per azimuth in %s: %d of %d sectors lit\n", what.c_str(), p.sectorsMeasured, p.sectorsTotal);
      std::printf("rms_px_exact %.4f  max_abs_px_exact %.4f\n", p.rmsPx, p.maxAbsPx);
    }
    return j;
  }
  RingReport report;
  try {
    report = measureRings(image, rig.camera(), defaultRingThetasDeg());
  } catch (const RingCountError& e) {
    if (e.tooSmall()) throw;  // the message says how large an image resolves them
    throw InputError(std::string(e.what()) + ringHint(a));
  } catch (const InputError& e) {
    throw InputError(std::string(e.what()) + ringHint(a));
  }
  const nlohmann::json j = ringReportToJson(report);
  if (a.json) {
    std::printf("%s\n", j.dump(2).c_str());
  } else {
    std::printf("rings: %zu measured in %s\n", report.rings.size(), what.c_str());
    std::printf("rms_px_exact %.4f  max_abs_px_exact %.4f  mse_px2_eq32 %.4f  h_px %.4f (model %.4f)\n",
                report.rmsPxExact, report.maxAbsPxExact, report.msePx2Eq32, report.hPx, report.hPxExact);
  }
  return j;
}

// The text of a sidecar's field, "" if it is not a string (sidecars are untrusted input).
std::string sidecarText(const nlohmann::json& object, const char* key) {
  return object.is_object() && object.contains(key) && object[key].is_string() ? object[key].get<std::string>() : "";
}

// An image whose sidecar says it was rendered from another scene, or from the ring scene away
// from its start position, is not of these rings about that position (a render of the field, or
// of the rings 2 cm off, would still yield numbers).
void checkRenderedFromRingScene(const std::string& image, const nlohmann::json& sidecar, const Scene& scene,
                                const std::string& sceneFile) {
  const nlohmann::json from = sidecar.contains("scene") ? sidecar["scene"] : nlohmann::json();
  if (from.is_object() && sidecarText(from, "sha256") != scene.sha256) {
    const std::string path = sidecarText(from, "path");
    std::error_code ec;
    if (!path.empty() && std::filesystem::equivalent(path, sceneFile, ec))
      throw InputError(showPath(image) + ": its ring scene " + showPath(sceneFile) +
                       " changed since it was rendered (its sidecar's SHA-256 differs): render the rings again");
    throw InputError(showPath(image) + ": rendered from " + (path.empty() ? std::string("another scene") : quote(path)) +
                     " (its sidecar), not from the ring scene " + showPath(sceneFile) +
                     ": measure a ring image, or give the scene it was rendered from with --scene");
  }
  const nlohmann::json pose = sidecar.contains("pose") ? sidecar["pose"] : nlohmann::json();
  if (pose.is_object() && pose.contains("x") && pose.contains("y") && pose["x"].is_number() && pose["y"].is_number()) {
    const double x = pose["x"].get<double>(), y = pose["y"].get<double>();
    if (std::hypot(x - scene.startPose.x, y - scene.startPose.y) > 1e-6)
      throw InputError(showPath(image) + ": rendered with the robot at (" + shortNumber(x) + ", " + shortNumber(y) +
                       ") m (its sidecar), not at the ring scene's start position (" + shortNumber(scene.startPose.x) + ", " +
                       shortNumber(scene.startPose.y) + ") m, about which its rings lie");
  }
}

// Measures an existing ring image; the model it is scored against comes from its sidecar when
// there is one, else from the ring scene's rig at the image's size.
void measureExisting(const RingsArgs& a) {
  const ImageRGBA image = readImage(a.measure);
  const std::string sceneFile = a.scene.empty() ? scenesDir() + "/incidence-rings.json" : a.scene;
  const Scene scene = loadScene(sceneFile, a.load);
  checkScene(sceneFile, [&] { checkRingScene(scene, defaultRingThetasDeg()); });
  if (const auto sidecar = readSidecar(a.measure)) checkRenderedFromRingScene(a.measure, sidecar->json, scene, sceneFile);
  RigSpec rig = rigFromSidecar(a.measure, scene.rig);
  // Rings are incidence angles about a mirror's axis (docs/lens-cameras.md: rings are the mirror's alone).
  rig.mirrorRig(showPath(a.measure) + ": rings measure a mirror camera's image; its rig");
  if (image.width != image.height) throw InputError(showPath(a.measure) + ": ring images must be square");
  checkImageSize(image.width, showPath(a.measure) + ": its size");
  rig = rig.resized(image.width);  // scales a principal point offset with the image
  measureAndPrint(image, rig, a.measure, a);
}

void runRings(RingsArgs a, const CLI::App& cmd) {
  // The scene as every other command takes it, or as --scene.
  if (!a.sceneArgument.empty()) {
    if (!a.scene.empty()) throw InputError("--scene: give the ring scene once (as --scene or as the first argument)");
    a.scene = a.sceneArgument;
  }
  for (const char* flag : {"--engine", "--size", "--spp"})
    refuseUnless(cmd, flag, a.measure.empty(), "a render (not with --measure)");
  if (!a.measure.empty()) {
    if (!a.out.empty()) throw InputError("--measure and -o: give one, not both");
    measureExisting(a);
    return;
  }
  if (a.out.empty()) throw InputError("-o: required (or --measure FILE)");
  if (!isSupportedImageOutput(a.out)) throw InputError("-o: " + showPath(a.out) + ": must end in .png or .exr");
  // Rings default to 16 spp, more than a single render's default.
  const RequestFields fields{{RequestField::Engine, a.engine}, {RequestField::Spp, int64_t{a.spp}}};
  const RenderRequest request = readRenderRequest(fields, RequestFieldNames::cli());
  const std::string sceneFile = a.scene.empty() ? scenesDir() + "/incidence-rings.json" : a.scene;
  const Scene scene = loadScene(sceneFile, a.load);
  scene.rig.mirrorRig(showPath(sceneFile) + ": rings measure a mirror camera; its rig");
  RenderSettings settings = request.settings(a.size ? scene.rig.resized(a.size, "--size") : scene.rig);
  checkRenderSettings(settings, kSettingFlags);
  checkImageOutput(a.out, "-o");
  checkOutputsSpareScene(scene, {a.out}, "-o");
  checkScene(sceneFile, [&] { checkRingScene(scene, defaultRingThetasDeg()); });
  // Too small an image to tell the rings apart is refused before it is rendered.
  if (settings.rig.ideal())
    if (const std::string note = ringSpacingNote(settings.rig.imageWidth(), settings.rig.camera(), defaultRingThetasDeg()); !note.empty())
      throw InputError("--size" + note);
  const auto engine = makeEngine(request, scene);
  checkScene(sceneFile, [&] { checkEngineRenders(engine->kind(), settings.rig, CameraPlacement(scene.startPose)); });
  RenderedFile rendered = renderPose(scene, *engine, scene.startPose, settings);
  rendered.sidecar["rings"] = measureAndPrint(rendered.image, settings.rig, a.out, a);
  writeRendered(a.out, rendered);
}

}  // namespace

void addRingsCommand(CLI::App& app) {
  auto args = std::make_shared<RingsArgs>();
  CLI::App* cmd = app.add_subcommand("rings", "Render and measure the incidence-angle rings (thesis Fig. 3.11/3.12)");
  cmd->add_option("--engine", args->engine, "fast (default), povray or blender");
  cmd->add_option("scene", args->sceneArgument, "Ring scene (default: scenes/incidence-rings.json)");
  cmd->add_option("--scene", args->scene, "The same, as a flag");
  cmd->add_option("--size", args->size,
                  "Image size in pixels (default: the scene's); one too small to tell the rings apart is refused "
                  "(the default ring scene's need 224 or more)")
      ->check(integerIn(32, limits::kMaxImageSize));
  addSppOption(*cmd, args->spp, "Samples per pixel, n*n (default 16)");
  cmd->add_option("-o,--output", args->out, "Ring image OUT.png / OUT.exr");
  cmd->add_option("--measure", args->measure, "Measure an existing ring image instead of rendering one");
  cmd->add_flag("--json", args->json, "Print per-ring radii and the summary as JSON");
  cmd->add_flag("--per-azimuth", args->perAzimuth,
                "Measure each ring in 36 azimuth sectors (for rings that are not circles, e.g. thesis-mesh renders)");
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runRings(*args, *cmd); });
}

}  // namespace omnicam::cli
