// omnicam project SCENE --pose X,Y,YAW --point X,Y,Z [--point ...] [--size N]
// Prints "u v" per point: continuous pixel coordinates, pixel centres at +0.5. A point the
// mirror does not show (beyond the rim) prints "nan nan". Any rig: a physical one's reflection
// point is solved for (physical_camera.h).
#include <cstdio>
#include <memory>
#include <vector>

#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "make_camera.h"
#include "rig.h"
#include "scene_loader.h"

namespace omnicam::cli {

namespace {

struct ProjectArgs {
  std::string scene, pose;
  std::vector<std::string> points;
  int size = 0;
  SceneLoadOptions load;
};

void runProject(const ProjectArgs& a) {
  const RobotPose pose = parsePose(a.pose, "--pose");
  std::vector<Vec3> points;
  for (const auto& text : a.points) points.push_back(parseTriple(text, "--point"));
  const Scene scene = loadScene(a.scene, a.load);
  RigSpec rig = scene.rig;
  if (a.size) rig.imageSize = a.size;
  const std::shared_ptr<const Camera> camera = makeCamera(rig);
  const Rigid viewpointFromWorld = worldFromViewpoint(rig, pose).inverse();
  for (const Vec3& world : points) {
    const auto raster = camera->project(viewpointFromWorld * world);
    if (raster) std::printf("%.6f %.6f\n", raster->x(), raster->y());
    else std::printf("nan nan\n");
  }
}

}  // namespace

void addProjectCommand(CLI::App& app) {
  auto args = std::make_shared<ProjectArgs>();
  CLI::App* cmd = app.add_subcommand("project", "Print the pixel (u v) where world points appear");
  cmd->add_option("scene", args->scene, "Scene JSON file (for its rig)")->required();
  cmd->add_option("--pose", args->pose, "X,Y,YAW of the robot")->required();
  cmd->add_option("--point", args->points, "X,Y,Z world point (repeatable)")->required();
  cmd->add_option("--size", args->size, "Image size in pixels")->check(CLI::Range(8, 16384));
  addSceneLoadFlags(*cmd, args->load);
  cmd->callback([args] { runProject(*args); });
}

}  // namespace omnicam::cli
