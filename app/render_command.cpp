// omnicam render SCENE [--engine fast|povray|blender] [--pose X,Y,YAW | --path NAME [--frames N]]
//                      [--size N] [--spp N] [--shading unlit|lit] [--mode exact|cubemap|thesis-mesh]
//                      [--view birdseye|panorama|perspective ...] -o OUT
#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <set>
#include <chrono>
#include <future>
#include <memory>
#include <optional>
#include <regex>

#include "cli_util.h"
#include "number_format.h"
#include "commands.h"
#include "errors.h"
#include "image.h"
#include "make_camera.h"
#include "placement.h"
#include "frame_sequence.h"
#include "recording_camera.h"
#include "recording_camera_spec.h"
#include "render_output.h"
#include "atomic_file.h"
#include "sidecar.h"
#include "safe_files.h"
#include "scene_loader.h"
#include "views.h"

namespace omnicam::cli {

namespace {

struct RenderArgs {
  std::string scene, pose, velocity, path, size, out, format = "png", recording;
  int frames = 0, imageSize = 0;
  RequestFlags request;
  std::vector<std::string> views;
  SceneLoadOptions load;
};

// Views written next to each rendered image (OUT's stem + ".KIND" + its extension), from lookup
// tables built once for the render's camera and reused for every frame. Each gets a sidecar:
// the omni image's, plus what the view is.
class FrameViews {
 public:
  FrameViews(const std::vector<std::string>& kinds, const RigSpec& rig) {
    const std::shared_ptr<const Camera> camera = makeCamera(rig);
    for (size_t k = 0; k < kinds.size(); ++k) {
      const std::string& kind = kinds[k];
      if (std::find(kinds.begin(), kinds.begin() + static_cast<std::ptrdiff_t>(k), kind) != kinds.begin() + static_cast<std::ptrdiff_t>(k))
        throw InputError("--view: " + quote(kind) + " given twice (each view is written once)");
      ViewSpec spec;
      spec.kind = parseViewKind(kind, "--view");
      ViewMap map = buildViewMap(spec, *camera, robotFromViewpoint(rig));
      nlohmann::json description = viewToJson(spec, map, *camera, robotFromViewpoint(rig));
      maps_.push_back({kind, std::move(map), std::move(description)});
    }
  }
  std::vector<std::string> files(const std::string& imageFile) const {
    std::vector<std::string> out;
    const std::filesystem::path file(imageFile);
    for (const auto& view : maps_) {
      std::filesystem::path viewFile = file;
      viewFile.replace_filename(file.stem().string() + "." + view.kind + file.extension().string());
      out.push_back(viewFile.string());
    }
    return out;
  }
  void addFiles(std::vector<FileBytes>& out, const std::string& imageFile, const RenderedFile& omni) const {
    const std::vector<std::string> outputs = files(imageFile);
    for (size_t k = 0; k < maps_.size(); ++k)
      addImageFiles(out, outputs[k], applyViewMap(maps_[k].map, omni.image),
                    viewSidecar(omni.sidecar, maps_[k].description, std::filesystem::path(imageFile).filename().string()));
  }

 private:
  struct View {
    std::string kind;
    ViewMap map;
    nlohmann::json description;
  };
  std::vector<View> maps_;
};

// The image, its views and all their sidecars: together, or none of them (a full disk).
void writeWithViews(const std::string& imageFile, const RenderedFile& rendered, const FrameViews& views) {
  std::vector<FileBytes> files;
  addImageFiles(files, imageFile, rendered.image, rendered.sidecar);
  views.addFiles(files, imageFile, rendered);
  writeFilesTogether(files);
}

// --recording: a preset's name, or a file holding one `recording` object (docs/experiments.md).
std::optional<RecordingCameraSpec> readRecordingFlag(const std::string& text, const CLI::App& cmd) {
  if (cmd.count("--recording") == 0) return std::nullopt;
  return recordingCameraSpecFromNameOrFile(text, "--recording");
}

// Frame `frame` (0 for a single image) through the recording camera drawn for it, which its
// sidecar records, as a dataset's manifest does.
void record(RenderedFile& rendered, const std::optional<RecordingCameraSpec>& recording, uint64_t frame) {
  if (!recording) return;
  const RecordingCamera camera = recording->draw(frame);
  rendered.image = recordFrame(camera, rendered.image, frame);
  rendered.sidecar["recording"] = recordingCameraToJson(camera);
}

// A folder of frames is one run's: frames of an earlier run that this one would not replace (more
// of them, another format or view) are refused, never mixed in, and never deleted. Only names a
// run writes count (frame_NNNN.png, frame_NNNN.KIND.exr, their sidecars); the user's own files stay.
void checkNoOtherFrames(const std::string& folder, const std::set<std::string>& written) {
  static const std::regex frameFile(R"(frame_\d{4,}(\.[a-z]+)?\.(png|exr)(\.json)?)");
  std::error_code ec;
  for (auto it = std::filesystem::directory_iterator(folder, ec); !ec && it != std::filesystem::directory_iterator();
       it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (std::regex_match(name, frameFile) && !written.count(name))
      throw InputError("-o: " + showPath(folder) + " holds " + quote(name) +
                       " of another run, which this one would not replace: give an empty folder, or remove that run's frames");
  }
}

// The first frames of `path` (all, or --frames) into the folder OUT: frame_NNNN.<format>, each
// with its views and sidecars.
void renderPath(const RenderArgs& a, const std::string& engineName, const Scene& scene, Engine& engine,
                const RenderSettings& settings, const BodyVelocity& velocity, const FrameViews& views,
                const CameraPath& path, const std::optional<RecordingCameraSpec>& recording) {
  const int total = a.frames ? a.frames : static_cast<int>(path.poses.size());
  const auto frameFile = [&](int f) {
    char name[64];
    std::snprintf(name, sizeof name, "frame_%04d.%s", f, a.format.c_str());
    return (std::filesystem::path(a.out) / name).string();
  };
  // An existing folder may already hold a folder under a frame's name: refused before any frame.
  std::error_code ec;
  std::set<std::string> written;  // the names this run writes (and their sidecars)
  const bool existed = std::filesystem::is_directory(a.out, ec);
  for (int f = 0; f < total; ++f) {
    std::vector<std::string> files = views.files(frameFile(f));
    if (existed) {
      checkImageOutput(frameFile(f), "-o");
      for (const std::string& file : files) checkImageOutput(file, "--view");
      checkOutputsSpareScene(scene, files, "--view");
      checkOutputsSpareScene(scene, {frameFile(f)}, "-o");
    }
    files.push_back(frameFile(f));
    for (const std::string& file : files) {
      const std::string name = std::filesystem::path(file).filename().string();
      written.insert(name), written.insert(name + ".json");
    }
  }
  if (existed) checkNoOtherFrames(a.out, written);
  // Every frame the engine cannot render is refused before the folder is made.
  checkScene(a.scene, [&] {
    for (const RobotPose& framePose : path.poses) checkEngineRenders(engine.kind(), settings.rig, CameraPlacement(framePose, velocity));
  });
  const std::vector<std::string> made = ensureDirectory(a.out, "-o");
  // One run at a time writes a folder of frames (as a dataset's folder): two would interleave
  // their frames and sidecars. The claim ends with the process however it ends.
  const SafeFolder claimed(a.out);
  if (!claimed.tryClaim(/*shared=*/false))
    throw InputError("-o: " + showPath(a.out) + ": another omnicam run is writing there now: wait for it to end, or give another folder");
  try {
    checkNoOtherFrames(a.out, written);  // again: another run may have made the folder or ended there since
    Progress progress("render " + a.path + " (" + engineName + ")", total);
    // Frame f is written while frame f + 1 renders (or its batch, for an engine that batches);
    // each file still appears atomically.
    std::future<void> writing;
    const auto placementOf = [&](size_t f) { return CameraPlacement(path.poses[f], velocity); };
    renderSequence(
        static_cast<size_t>(total), framesPerBatch(engine), placementOf,
        [&](const std::vector<CameraPlacement>& placements) { return engine.renderMany(placements, settings); },
        [&](size_t f, ImageRGBA&& image, double seconds) {
          RenderedFile rendered{std::move(image), renderSidecar(scene, engine, placementOf(f), settings, seconds)};
          rendered.sidecar["path"] = {{"name", a.path}, {"frame", f}};
          record(rendered, recording, f);
          if (writing.valid()) writing.get();
          writing = std::async(std::launch::async, [file = frameFile(static_cast<int>(f)), frame = std::move(rendered), &views] {
            writeWithViews(file, frame, views);
          });
          progress.step();
        });
    if (writing.valid()) writing.get();
    progress.finish();
  } catch (...) {
    removeMadeFolders(made);  // the folders this run made and left empty; frames written stay
    throw;
  }
  std::printf("wrote %s to %s\n", countOf(total, "frame").c_str(), showPath(a.out).c_str());
}

void runRender(const RenderArgs& a, const CLI::App& cmd) {
  // Validate everything before anything is written.
  const RenderRequest request = readRequestFlags(cmd, a.request);
  refuseUnless(cmd, "--format", !a.path.empty(), "--path (a single image's format comes from -o)");
  if (!a.pose.empty() && !a.path.empty()) throw InputError("--pose and --path: give one, not both");
  if (a.path.empty() && a.frames) throw InputError("--frames: only with --path");
  if (a.path.empty() && !isSupportedImageOutput(a.out)) throw InputError("-o: " + showPath(a.out) + ": must end in .png or .exr");
  if (a.format != "png" && a.format != "exr") throw InputError("--format: must be png or exr");
  std::optional<RobotPose> pose;
  if (!a.pose.empty()) pose = parsePose(a.pose, "--pose");
  const std::optional<RecordingCameraSpec> recording = readRecordingFlag(a.recording, cmd);
  RenderSettings settings = request.settings(RigSpec{});
  BodyVelocity velocity;
  if (!a.velocity.empty()) {
    const Vec3 v = parseTriple(a.velocity, "--velocity", "VX,VY,YAW_RATE");
    velocity = {v.x(), v.y(), v.z()};
  }
  checkPlacement(CameraPlacement(pose.value_or(RobotPose{}), velocity), kSettingFlags);
  if (a.imageSize) settings.rig = settings.rig.resized(a.imageSize, "--size");
  checkRenderSettings(settings, kSettingFlags);  // before the scene: a bad --spp needs no scene to be read
  const Scene scene = loadScene(a.scene, a.load);
  settings.rig = scene.rig;
  if (a.imageSize) settings.rig = settings.rig.resized(a.imageSize, "--size");
  checkRenderSettings(settings, kSettingFlags);
  checkMotionIsSeen(CameraPlacement(RobotPose{}, velocity), settings.rig, "--velocity");
  const FrameViews views(a.views, settings.rig);
  if (a.path.empty()) {
    checkImageOutput(a.out, "-o");
    for (const std::string& file : views.files(a.out)) checkImageOutput(file, "--view");
    checkOutputsSpareScene(scene, {a.out}, "-o");
    checkOutputsSpareScene(scene, views.files(a.out), "--view");
  }
  const CameraPath* path = nullptr;
  if (!a.path.empty()) {
    path = scene.findPath(a.path);
    if (!path) throw InputError("--path: scene " + showPath(a.scene) + " " + scene.noPathText(a.path));
    if (a.frames > static_cast<int>(path->poses.size()))
      throw InputError("--frames: path " + quote(a.path) + " has only " + std::to_string(path->poses.size()) + " poses");
    if (isSupportedImageOutput(a.out))
      throw InputError("-o: " + showPath(a.out) + ": with --path, -o names the folder for the frames, not an image");
    checkOutputFolder(a.out, "-o");
  }
  const auto engine = makeEngine(request, scene);

  if (!path) {
    const CameraPlacement at(pose ? *pose : scene.startPose, velocity);
    checkScene(a.scene, [&] { checkEngineRenders(engine->kind(), settings.rig, at); });
    // A frame rendered in parts (POV-Ray's moving frame) shows them; the others print nothing.
    std::unique_ptr<Progress> parts;
    engine->reportPartsTo([&](int done, int total) {
      if (!parts) parts = std::make_unique<Progress>("render " + a.out + " (" + request.engine + ")", total, 0, "renders");
      parts->advanceTo(done);
    });
    RenderedFile rendered = renderPose(scene, *engine, at, settings);
    if (parts) parts->finish();
    record(rendered, recording, 0);
    writeWithViews(a.out, rendered, views);
    std::string written = showPath(a.out);
    for (const std::string& file : views.files(a.out)) written += ", " + showPath(file);
    std::printf("wrote %s\n", written.c_str());
    return;
  }
  renderPath(a, request.engine, scene, *engine, settings, velocity, views, *path, recording);
}

}  // namespace

void addRenderCommand(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  CLI::App* cmd = app.add_subcommand("render", "Render a scene (single pose, or a camera path into a folder)");
  cmd->add_option("scene", args->scene, "Scene JSON file")->required();
  addRequestFlags(*cmd, args->request, kEngineFlag | kTimeoutFlag | kSppFlag | kShadingFlag | kPathFlags | kModeFlags);
  cmd->add_option("--pose", args->pose, "X,Y,YAW (metres, metres, degrees CCW); default: the scene's start_pose");
  cmd->add_option("--velocity", args->velocity,
                  "VX,VY,YAW_RATE: the robot's body velocity while the shutter is open (m/s forward, m/s left, "
                  "degrees/s CCW; docs/motion.md); the pose is the exposure start's. Default: still");
  cmd->add_option("--path", args->path, "Render the named camera path into folder OUT");
  cmd->add_option("--frames", args->frames, "With --path: render only the first N poses")->check(integerIn(1, INT32_MAX));
  cmd->add_option("--size", args->imageSize, "Image size in pixels (square; a lens camera's width, its height keeping the aspect); default: the scene's rig")
      ->check(integerIn(limits::kMinImageSize, limits::kMaxImageSize));
  cmd->add_option("--format", args->format, "With --path: png or exr frames");
  cmd->add_option("--view", args->views,
                  "Also write this view of each image (birdseye, panorama or perspective; repeatable): "
                  "OUT.KIND.png (.exr for an .exr OUT), frame_NNNN.KIND.png");
  cmd->add_option("--recording", args->recording,
                  "Record each image through a camera's faults: a preset (webcam, machine_vision, phone; drawn per frame "
                  "from its ranges) or a JSON file of one recording object (docs/experiments.md); the sidecar records the "
                  "drawn values");
  cmd->add_option("-o,--output", args->out, "OUT.png / OUT.exr, or a folder with --path")->required();
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runRender(*args, *cmd); });
}

}  // namespace omnicam::cli
