// omnicam export SCENE --to povray|gltf -o DIR [--pose X,Y,YAW] [--size N] [--spp N] [--shading S]
// povray: a self-contained job — scene.pov (exact mirror + physical camera), textures,
//         render.ini; render it with `cd DIR && povray render.ini`.
// gltf:   DIR/scene.glb — the arena plus the rig (certified mirror mesh, camera) at the pose.
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>

#include "atomic_file.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "markup.h"
#include "gltf_exporter.h"
#include "povray_exporter.h"
#include "scene_loader.h"

namespace omnicam::cli {

namespace {

struct ExportArgs {
  std::string scene, to, out, pose;
  int size = 0;
  RequestFlags request;  // --spp and --shading, for POV-Ray's job
  SceneLoadOptions load;
};

void runExport(const ExportArgs& a, const CLI::App& cmd) {
  if (a.to != "povray" && a.to != "gltf")
    throw InputError("--to: " + quote(a.to) + " is not available (povray, gltf)");
  refuseUnless(cmd, "--spp", a.to == "povray", "--to povray (glTF holds no sampling)");
  refuseUnless(cmd, "--shading", a.to == "povray", "--to povray (glTF holds no shading mode)");
  const RenderRequest request = readRequestFlags(cmd, a.request);
  std::optional<RobotPose> requested;
  if (!a.pose.empty()) requested = parsePose(a.pose, "--pose");
  checkOutputFolder(a.out, "-o");
  const Scene scene = loadScene(a.scene, a.load);
  const RobotPose pose = requested ? *requested : scene.startPose;
  RenderSettings settings = request.settings(a.size ? scene.rig.resized(a.size, "--size") : scene.rig);
  checkRenderSettings(settings, kSettingFlags);
  checkScene(a.scene, [&] { a.to == "gltf" ? checkGltfCamera(settings.rig) : checkPovrayCamera(settings.rig); });
  if (a.to == "gltf") {
    GltfExportOptions options;
    options.placement = pose;
    options.rig = settings.rig;
    const std::string file = a.out + "/scene.glb";
    checkOutputsSpareScene(scene, {file}, "-o");
    const std::vector<std::string> made = ensureDirectory(a.out, "-o");
    try {
      exportGltf(scene, options, file);
    } catch (...) {
      removeMadeFolders(made);  // the folders it made, empty: nothing written
      throw;
    }
    std::printf("wrote %s\n", file.c_str());
    return;
  }
  const PovrayJob job = exportPovray(scene, pose, settings);  // validates before anything is written
  std::vector<std::string> files;
  for (const std::string& name : povrayJobFiles(job)) files.push_back((std::filesystem::path(a.out) / name).string());
  checkOutputsSpareScene(scene, files, "-o");
  ensureDirectory(a.out, "-o");
  writePovrayJob(job, a.out);
  const std::string folder = shellWord(a.out[0] == '-' ? "./" + a.out : a.out);
  std::printf("wrote %s/scene.pov and render.ini (render with: cd %s && povray render.ini)\n", a.out.c_str(), folder.c_str());
  if (job.samplesPerAxis > 1)
    std::printf("its render.exr is %dx%d, %dx the image for %d spp: omnicam compare --box-downsample averages it to the image's grid\n",
                job.width, job.height, job.samplesPerAxis, job.samplesPerAxis * job.samplesPerAxis);
}

}  // namespace

void addExportCommand(CLI::App& app) {
  auto args = std::make_shared<ExportArgs>();
  CLI::App* cmd = app.add_subcommand("export", "Export a scene with the exact mirror and physical camera");
  cmd->add_option("scene", args->scene, "Scene JSON file")->required();
  cmd->add_option("--to", args->to, "povray or gltf")->required();
  cmd->add_option("--pose", args->pose, "X,Y,YAW of the robot (default: the scene's start_pose)");
  cmd->add_option("--size", args->size, "Image size in pixels")->check(integerIn(limits::kMinImageSize, limits::kMaxImageSize));
  addRequestFlags(*cmd, args->request, kSppFlag | kShadingFlag);  // POV-Ray renders its job n x larger; no path shading
  cmd->add_option("-o,--output", args->out, "Output folder")->required();
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runExport(*args, *cmd); });
}

}  // namespace omnicam::cli
