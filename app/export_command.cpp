// omnicam export SCENE --to povray|blender|gltf -o DIR [--pose X,Y,YAW] [--size N] [--spp N] [--shading S]
// povray:  a self-contained job — scene.pov (exact mirror + physical camera), textures,
//          render.ini; render it with `cd DIR && povray render.ini`.
// blender: a self-contained job — scene.glb, job.json and blender_driver.py; render it with
//          `cd DIR && blender -b … -P blender_driver.py -- job.json` (it writes render.exr).
// gltf:    DIR/scene.glb — the arena plus the rig (certified mirror mesh, camera) at the pose;
//          with --no-rig the arena alone (for a camera glTF cannot hold).
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "markup.h"
#include "blender_renderer.h"
#include "engine_capabilities.h"
#include "gltf_exporter.h"
#include "povray_exporter.h"
#include "scene_loader.h"

namespace omnicam::cli {

namespace {

struct ExportArgs {
  std::string scene, to, out, pose;
  int size = 0;
  bool noRig = false;
  RequestFlags request;  // --spp and --shading, for POV-Ray's job
  SceneLoadOptions load;
};

// The folder's files, each checked against the scene's own before anything is written.
std::vector<std::string> filesIn(const std::string& folder, const std::vector<std::string>& names) {
  std::vector<std::string> files;
  for (const std::string& name : names) files.push_back((std::filesystem::path(folder) / name).string());
  return files;
}

// A render.exr already in the folder is an earlier job's (the renderer wrote it, not omnicam, so
// omnicam leaves it): said, so that it is not taken for this job's.
void noteEarlierRender(const std::string& folder) {
  std::error_code ec;
  const std::filesystem::path render = std::filesystem::path(folder) / "render.exr";
  if (std::filesystem::exists(std::filesystem::symlink_status(render, ec)))
    std::printf("note: %s is an earlier job's render; rendering this job replaces it\n", showPath(render.string()).c_str());
}

void exportBlenderJob(const ExportArgs& a, const Scene& scene, const RobotPose& pose, const RenderSettings& settings) {
  checkScene(a.scene, [&] { checkEngineRenders(EngineKind::Blender, settings.rig, CameraPlacement(pose)); });
  checkEngineShading(EngineKind::Blender, settings.shading);
  checkOutputsSpareScene(scene, filesIn(a.out, blenderJobFiles(scene, settings)), "-o");
  const std::vector<std::string> made = ensureDirectory(a.out, "-o");
  try {
    writeBlenderJob(scene, CameraPlacement(pose), settings, a.out);
  } catch (...) {
    removeMadeFolders(made);
    throw;
  }
  std::printf("wrote %s, job.json and blender_driver.py (render with: cd %s && %s; it writes render.exr)\n",
              showPath(a.out + "/scene.glb").c_str(), shellPath(a.out).c_str(), blenderJobCommand().c_str());
  noteEarlierRender(a.out);
}

void runExport(const ExportArgs& a, const CLI::App& cmd) {
  if (a.to != "povray" && a.to != "blender" && a.to != "gltf")
    throw InputError("--to: " + quote(a.to) + " is not available (povray, blender, gltf)");
  refuseUnless(cmd, "--spp", a.to != "gltf", "--to povray or blender (glTF holds no sampling)");
  refuseUnless(cmd, "--shading", a.to != "gltf", "--to povray or blender (glTF holds no shading mode)");
  refuseUnless(cmd, "--no-rig", a.to == "gltf", "--to gltf (a POV-Ray or Blender job renders through the rig)");
  const RenderRequest request = readRequestFlags(cmd, a.request);
  std::optional<RobotPose> requested;
  if (!a.pose.empty()) requested = parsePose(a.pose, "--pose");
  checkOutputFolder(a.out, "-o");
  const Scene scene = loadScene(a.scene, a.load);
  const RobotPose pose = requested ? *requested : scene.startPose;
  RenderSettings settings = request.settings(a.size ? scene.rig.resized(a.size, "--size") : scene.rig);
  checkRenderSettings(settings, kSettingFlags);
  checkScene(a.scene, [&] {
    if (a.to == "povray") checkPovrayCamera(settings.rig);
    else if (a.to == "blender" || !a.noRig) {
      try {
        checkGltfCamera(settings.rig);
      } catch (const InputError& e) {
        if (a.to != "gltf") throw;
        throw InputError(std::string(e.what()) + " (glTF holds the cameras Blender renders; --no-rig exports the arena alone)");
      }
    }
  });
  if (a.to == "blender") {
    exportBlenderJob(a, scene, pose, settings);
    return;
  }
  if (a.to == "gltf") {
    GltfExportOptions options;
    options.placement = pose;
    options.rig = settings.rig;
    options.includeRig = !a.noRig;
    const std::string file = a.out + "/scene.glb";
    checkOutputsSpareScene(scene, {file}, "-o");
    const std::vector<std::string> made = ensureDirectory(a.out, "-o");
    try {
      exportGltf(scene, options, file);
    } catch (...) {
      removeMadeFolders(made);  // the folders it made, empty: nothing written
      throw;
    }
    std::printf("wrote %s\n", showPath(file).c_str());
    return;
  }
  const PovrayJob job = exportPovray(scene, pose, settings);  // validates before anything is written
  checkOutputsSpareScene(scene, filesIn(a.out, povrayJobFiles(job)), "-o");
  const std::vector<std::string> made = ensureDirectory(a.out, "-o");
  try {
    writePovrayJob(job, a.out);  // all its files, or none
  } catch (...) {
    removeMadeFolders(made);
    throw;
  }
  const std::string folder = shellPath(a.out);
  std::printf("wrote %s and render.ini (render with: cd %s && povray render.ini)\n", showPath(a.out + "/scene.pov").c_str(), folder.c_str());
  if (job.samplesPerAxis > 1)
    std::printf("its render.exr is %dx%d, %dx the image for %d spp: omnicam compare --box-downsample averages it to the image's grid\n",
                job.width, job.height, job.samplesPerAxis, job.samplesPerAxis * job.samplesPerAxis);
  noteEarlierRender(a.out);
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand("export", "Export a scene with the exact mirror and physical camera");
  cmd->add_option("scene", args->scene, "Scene JSON file")->required();
  cmd->add_option("--to", args->to, "povray (a POV-Ray job), blender (a Blender job) or gltf (the scene and its rig at the pose)")->required();
  cmd->add_flag("--no-rig", args->noRig, "gltf: the arena alone, without the camera rig (for a camera glTF cannot hold)");
  cmd->add_option("--pose", args->pose, "X,Y,YAW of the robot (default: the scene's start_pose)");
  cmd->add_option("--size", args->size, "Image size in pixels")->check(integerIn(limits::kMinImageSize, limits::kMaxImageSize));
  addRequestFlags(*cmd, args->request, kSppFlag | kShadingFlag);  // no path-shading flags: the jobs' own defaults
  cmd->add_option("-o,--output", args->out, "Output folder")->required();
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runExport(*args, *cmd); });
}

}  // namespace omnicam::cli
