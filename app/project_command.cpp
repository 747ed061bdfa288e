// omnicam project SCENE|--rig RIG.json [--pose X,Y,YAW] --point X,Y,Z [--point ...] [--size N]
// omnicam camera-rays SCENE|--rig RIG.json -o RAYS.exr [--size N]: the exact ray of every pixel centre.
// Prints "u v" per point: continuous pixel coordinates, pixel centres at +0.5. A point the
// mirror does not show (beyond the rim) prints "nan nan". Any rig: a physical one's reflection
// point is solved for (physical_camera.h).
#include <algorithm>
#include <cctype>
#include <cstdio>
#include <filesystem>
#include <memory>
#include <optional>
#include <vector>

#include "atomic_file.h"
#include "camera_rays.h"
#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "make_camera.h"
#include "number_format.h"
#include "rig.h"
#include "scene_loader.h"
#include "sidecar.h"

namespace omnicam::cli {

namespace {

struct ProjectArgs {
  std::string scene, rig, pose;
  std::vector<std::string> points;
  int size = 0;
  SceneLoadOptions load;
};

void runProject(const ProjectArgs& a, const CLI::App& cmd) {
  refuseUnless(cmd, "--allow-outside-files", !a.scene.empty(), "a scene");
  checkSceneOrRigFlag(a.scene, a.rig);
  std::optional<RobotPose> givenPose;
  if (!a.pose.empty()) givenPose = parsePose(a.pose, "--pose");
  if (!givenPose && !a.rig.empty()) throw InputError("--pose: required with --rig (a rig has no start_pose)");
  std::vector<Vec3> points;
  for (const auto& text : a.points) {
    const Vec3 point = parseTriple(text, "--point", "X,Y,Z");
    // World coordinates, as a scene's: beyond them float tracing loses the millimetre.
    if (!(point.cwiseAbs().maxCoeff() <= limits::kMaxWorldCoordinate))
      throw InputError("--point: each coordinate must be within ±" + shortNumber(limits::kMaxWorldCoordinate) + " m (got " + quote(text) + ")");
    points.push_back(point);
  }
  RigSpec rig;
  RobotPose pose;
  if (givenPose) {
    rig = rigOfSceneOrRigFlag(a.scene, a.rig, a.load);
    pose = *givenPose;
  } else {  // a scene without --pose: its start_pose, as render takes it
    const Scene scene = loadScene(a.scene, a.load);
    rig = scene.rig;
    pose = scene.startPose;
  }
  if (a.size) rig = rig.resized(a.size, "--size");
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const Rigid viewpointFromWorld = CameraPlacement(pose).worldFromViewpoint(rig).inverse();
  for (const Vec3& world : points) {
    const auto raster = camera->project(viewpointFromWorld * world);
    if (raster) std::printf("%.6f %.6f\n", raster->x(), raster->y());
    else std::printf("nan nan\n");
  }
}

struct CameraRaysArgs {
  std::string scene, rig, out;
  int size = 0;
  SceneLoadOptions load;
};

void runCameraRays(const CameraRaysArgs& a, const CLI::App& cmd) {
  refuseUnless(cmd, "--allow-outside-files", !a.scene.empty(), "a scene");
  checkImageOutput(a.out, "-o");
  std::string extension = std::filesystem::path(a.out).extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(), [](unsigned char c) { return std::tolower(c); });
  if (extension != ".exr") throw InputError("-o: the ray table is an OpenEXR: name it .exr (got " + showPath(a.out) + ")");
  RigSpec rig = rigOfSceneOrRigFlag(a.scene, a.rig, a.load, {a.out}, "-o");
  if (a.size) rig = rig.resized(a.size, "--size");
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  // Rows as the bars' steps: a large table takes minutes to trace (a physical camera) and to encode.
  const std::string size = std::to_string(camera->width()) + "x" + std::to_string(camera->height());
  Progress tracing("camera-rays " + size + ": tracing", camera->height(), 0, "rows");
  const CameraRayTable table = cameraRayTable(*camera, [&](int rowsDone, int) { tracing.advanceTo(rowsDone); });
  tracing.finish();
  Progress encoding("camera-rays " + size + ": writing", camera->height(), 0, "rows");
  const std::vector<unsigned char> exr = encodeCameraRayTable(a.out, table, [&](int rowsDone, int) { encoding.advanceTo(rowsDone); });
  const std::string sidecar = sidecarText({{"rig", rigToJson(rig)},
                                           {"intrinsics", camera->describe()},
                                           {"channels", kCameraRayChannels},
                                           {"frame", "viewpoint: origin F', robot axes (x forward, y left, z up) turned by the rig's tilt_deg; metres"},
                                           {"pixels", "each pixel centre's ray; NaN where the camera images nothing"}});
  // The table and its sidecar appear together, or neither (the table is not copied: it may be GBs).
  AtomicFileGroup group;
  group.stage(a.out, std::string_view(reinterpret_cast<const char*>(exr.data()), exr.size()));
  group.stage(sidecarPath(a.out), sidecar);
  group.commit();
  encoding.finish();
  std::printf("wrote %s\n", showPath(a.out).c_str());
}

}  // namespace

void addCameraRaysCommand(CLI::App& app) {
  auto args = std::make_shared<CameraRaysArgs>();
  CLI::App* cmd = app.add_subcommand("camera-rays", "Write the exact ray of every pixel centre (OpenEXR)");
  cmd->add_option("scene", args->scene, "Scene JSON file (for its rig), or give --rig");
  cmd->add_option("--rig", args->rig, "The camera's rig from this JSON file (a scene's \"rig\" object) instead of a scene");
  cmd->add_option("-o", args->out, "Output .exr (a .json sidecar is written beside it)")->required();
  cmd->add_option("--size", args->size, "Image size in pixels")->check(integerIn(limits::kMinImageSize, limits::kMaxImageSize));
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runCameraRays(*args, *cmd); });
}

void addProjectCommand(CLI::App& app) {
  auto args = std::make_shared<ProjectArgs>();
  CLI::App* cmd = app.add_subcommand("project", "Print the raster point (u v) where world points appear: nan nan if not imaged; not clipped to the image, so a point the mirror images outside the framing falls outside [0, W) x [0, H)");
  cmd->add_option("scene", args->scene, "Scene JSON file (for its rig), or give --rig");
  cmd->add_option("--rig", args->rig, "The camera's rig from this JSON file (a scene's \"rig\" object) instead of a scene");
  cmd->add_option("--pose", args->pose, "X,Y,YAW of the robot; default: the scene's start_pose (required with --rig)");
  cmd->add_option("--point", args->points, "X,Y,Z world point (repeatable)")->required();
  cmd->add_option("--size", args->size, "Image size in pixels")->check(integerIn(limits::kMinImageSize, limits::kMaxImageSize));
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args, cmd] { runProject(*args, *cmd); });
}

}  // namespace omnicam::cli
