// omnicam view IN --as birdseye|panorama|perspective [--variant thesis|exact] [--size WxH]
//              [--zw Z] [--yaw DEG] [--pitch DEG] [--fov DEG] [--scene SCENE | --rig RIG.json] -o OUT
// Works on any omni image: the camera model comes from IN's sidecar, or for a dataset's frame from
// its manifest; any other image (a real camera's, say) needs its mirror from --scene or --rig —
// assuming a default would give a wrong view without a word.
#include <cstdio>
#include <filesystem>
#include <memory>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "dataset_reader.h"
#include "errors.h"
#include "make_camera.h"
#include "placement.h"
#include "scene_loader.h"
#include "sidecar.h"
#include "render_output.h"
#include "views.h"

namespace omnicam::cli {

namespace {

struct ViewArgs {
  std::string in, as = "birdseye", variant = "exact", size, scene, rig, out;
  double zw = 40.0, yaw = 0.0, pitch = -20.0, fov = 90.0;
  SceneLoadOptions load;
};

// The image's sidecar if it is omnicam's (an object with a "rig"); a file of another tool, or one
// that does not parse, is none: with --scene or --rig it is not what gives the camera.
std::optional<nlohmann::json> omnicamSidecar(const std::string& image) {
  try {
    if (auto found = readSidecar(image)) return found->json;
  } catch (const InputError&) {
  }
  return std::nullopt;
}

// The rig and the sidecar the view's own sidecar starts from: the image's own sidecar's, or for an
// image without one the --scene or --rig file's. A view's output is refused, and so is a flag
// whose rig differs from the one the image's own sidecar states (which view would be right?).
std::pair<RigSpec, nlohmann::json> rigOf(const ViewArgs& a) {
  if (!a.scene.empty() && !a.rig.empty()) throw InputError("--scene and --rig: give one, not both");
  const bool fromFlag = !a.scene.empty() || !a.rig.empty();
  // Without a flag the sidecar must be read strictly: it is what gives the camera.
  const std::optional<SidecarInfo> strict = fromFlag ? std::nullopt : readSidecar(a.in);
  const std::optional<nlohmann::json> own = fromFlag ? omnicamSidecar(a.in) : strict ? std::optional(strict->json) : std::nullopt;
  if (own && own->contains("view"))
    throw InputError(showPath(a.in) + ": is a view (its sidecar's \"view\"), not an omni image: view its source image (\"source_image\")");
  if (!fromFlag && strict) return {strict->rig, strict->json};
  // A dataset's frame has no sidecar: its manifest gives the camera (the frame's own rig, when
  // the robot vibrates).
  std::optional<DatasetImageLocation> inDataset;
  try {
    if (!own) inDataset = locateInDataset(a.in);
  } catch (const InputError& e) {
    // A flag gives the camera all the same; without one, the manifest was the last place to ask.
    if (!fromFlag)
      throw InputError(showPath(a.in) + ": has no sidecar, and the manifest of the dataset it lies in cannot be read: " + e.what());
  }
  std::optional<std::pair<RigSpec, nlohmann::json>> datasetCamera;
  if (inDataset)
    datasetCamera = {inDataset->rig,
                     {{"rig_from", {{"dataset", inDataset->dir}, {"camera", inDataset->camera}, {"frame", inDataset->frame}}}}};
  if (!fromFlag) {
    if (!datasetCamera)
      throw InputError(showPath(a.in) + ": has no sidecar (" + showPath(sidecarPath(a.in)) +
                       ") and is no frame a dataset's manifest lists, so its mirror is unknown: give --scene SCENE or --rig RIG.json");
    return *datasetCamera;
  }
  RigSpec rig;
  nlohmann::json sidecar = nlohmann::json::object();
  if (!a.scene.empty()) {
    const Scene scene = loadScene(a.scene, a.load);
    checkOutputsSpareScene(scene, {a.out}, "-o");  // its textures and glTF files too
    rig = scene.rig;
    sidecar["rig_from"] = {{"scene", a.scene}};
  } else {
    rig = readRigFlag(a.rig, "--scene");
    sidecar["rig_from"] = {{"rig_file", a.rig}};
  }
  const std::string flag = a.scene.empty() ? "--rig" : "--scene";
  if (own) {
    // Compared at the sidecar's own size, as the render that wrote it resized the same rig.
    const RigSpec stated = sidecarFromText(own->dump(), sidecarPath(a.in)).rig;
    if (!(rig.resized(stated.imageWidth()) == stated))
      throw InputError(flag + ": " + showPath(a.in) + "'s sidecar (" + showPath(sidecarPath(a.in)) +
                       ") states another camera; leave the flag out to use it");
    return {stated, *own};  // the same camera: the image's own sidecar, with its pose and source
  }
  if (datasetCamera) {
    if (!(rig.resized(datasetCamera->first.imageWidth()) == datasetCamera->first))
      throw InputError(flag + ": " + showPath(a.in) + " is frame " + std::to_string(inDataset->frame) + " of camera " +
                       quote(inDataset->camera) + " of the dataset " + showPath(inDataset->dir) +
                       ", whose manifest states another camera; leave the flag out to use it");
    return *datasetCamera;
  }
  return {rig, sidecar};
}

void runView(const ViewArgs& a, const CLI::App& cmd) {
  ViewSpec spec;
  spec.kind = parseViewKind(a.as, "--as");
  spec.variant = parseViewVariant(a.variant, "--variant");
  refuseUnless(cmd, "--zw", spec.kind == ViewKind::BirdsEye, "--as birdseye");
  for (const char* flag : {"--yaw", "--pitch", "--fov"}) refuseUnless(cmd, flag, spec.kind == ViewKind::Perspective, "--as perspective");
  refuseUnless(cmd, "--allow-outside-files", !a.scene.empty(), "--scene");
  if (!a.size.empty()) {
    const size_t x = a.size.find('x');
    const std::string_view text(a.size);
    const auto width = x == std::string::npos ? std::nullopt : parseIntegerIn(text.substr(0, x), 0, limits::kMaxImageDimension);
    const auto height = x == std::string::npos ? std::nullopt : parseIntegerIn(text.substr(x + 1), 0, limits::kMaxImageDimension);
    if (!width || !height)
      throw InputError("--size: must be WIDTHxHEIGHT, each an integer in [1, " + std::to_string(limits::kMaxImageDimension) +
                       "], e.g. 400x400 (got " + quote(a.size) + ")");
    spec.width = static_cast<int>(*width), spec.height = static_cast<int>(*height);
    if (spec.width < 1 || spec.height < 1) throw InputError("--size: width and height must be at least 1");
  }
  spec.groundDistance = a.zw, spec.yawDeg = a.yaw, spec.pitchDeg = a.pitch, spec.fovDeg = a.fov;
  const ViewSpecNames flags{"--variant", "--size", "--zw", "--yaw/--pitch", "--fov"};
  checkViewSpec(spec, flags);
  if (!isSupportedImageOutput(a.out)) throw InputError("-o: " + showPath(a.out) + ": must end in .png or .exr");
  checkImageOutput(a.out, "-o");
  checkOutputIsNotInput(a.out, "-o", a.in, "the input image");
  for (const auto& [file, what] : {std::pair{a.scene, "the --scene file"}, std::pair{a.rig, "the --rig file"}})
    if (!file.empty()) checkOutputIsNotInput(sidecarPath(a.out), "-o (its sidecar)", file, what);
  // The header and the camera's source first: an image that is no omni image is refused before
  // it is decoded.
  ImageRowReader reader = ImageRowReader::openFile(a.in);
  reader.requireColour();
  auto [rig, sidecar] = rigOf(a);
  const ImageRGBA omni = reader.readRemaining();
  checkImageSize(omni.width, showPath(a.in) + ": its size");
  rig = rig.resized(omni.width);
  sidecar["rig"] = rigToJson(rig);
  // A mirror camera's image is square; a lens camera's has its own aspect, which its rig states.
  if (omni.height != rig.imageHeight())
    throw InputError(showPath(a.in) + ": is " + std::to_string(omni.width) + "x" + std::to_string(omni.height) + "; its camera images " +
                     std::to_string(rig.imageWidth()) + "x" + std::to_string(rig.imageHeight()) + " at that width");
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const ViewMap map = buildViewMap(spec, *camera, robotFromViewpoint(rig), flags);
  std::vector<FileBytes> files;  // the view and its sidecar together, or neither
  addImageFiles(files, a.out, applyViewMap(map, omni), viewSidecar(sidecar, viewToJson(spec, map, *camera, robotFromViewpoint(rig)), a.in));
  writeFilesTogether(files);
  std::printf("wrote %s (%dx%d %s, %s)\n", showPath(a.out).c_str(), map.width, map.height, a.as.c_str(), a.variant.c_str());
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand("view", "Bird's-eye, panorama or perspective view of an omni image");
  cmd->add_option("in", args->in, "Omni image (PNG/EXR; its sidecar gives the camera)")->required();
  cmd->add_option("--as", args->as, "birdseye (default), panorama or perspective");
  cmd->add_option("--variant", args->variant, "exact (default) or thesis (Eq. 3.4 / Eqs. 3.6-3.7)");
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (defaults 400x400, 1080x300, 400x300)");
  cmd->add_option("--zw", args->zw, "birdseye: ground plane, pixel units below the viewpoint (default 40): the floor at the viewpoint's height / Z "
                  "metres per pixel")
      ->check(numberIn(0, 1e6, true));
  cmd->add_option("--yaw", args->yaw, "perspective: view direction, degrees CCW from forward")->check(numberIn(-1e6, 1e6));
  cmd->add_option("--pitch", args->pitch, "perspective: degrees above the horizon (default -20)")->check(numberIn(-1e6, 1e6));
  cmd->add_option("--fov", args->fov, "perspective: horizontal field of view, degrees (default 90)")->check(numberIn(0, 179, true));
  cmd->add_option("--scene", args->scene, "Take the camera rig from this scene (images without a sidecar)");
  cmd->add_option("--rig", args->rig, "Take the camera rig from this JSON file (a scene's \"rig\" object)");
  addSceneLoadFlags(*cmd, args->load);
  cmd->add_option("-o,--output", args->out, "OUT.png or OUT.exr")->required();
  cmd->callback([args, cmd] { runView(*args, *cmd); });
}

}  // namespace omnicam::cli
