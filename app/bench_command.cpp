// omnicam bench [--json] [--seconds S]: frames/s of every render mode and view on a 360×360
// robocup2006 frame at 1 spp, unlit, on all cores (lookup tables built before timing; the
// median of ~20 ms batches).
#include <cstdio>
#include <memory>
#include <nlohmann/json.hpp>

#include "cli_util.h"
#include "commands.h"
#include "cubemap_renderer.h"
#include "frame_rate.h"
#include "scene_loader.h"
#include "views.h"

namespace omnicam::cli {

namespace {

struct BenchArgs {
  bool json = false;
  double seconds = 1.0;
  int faceSize = CubeMapOptions{}.faceSize;
};

void runBench(const BenchArgs& a) {
  const Scene scene = loadScene(scenesDir() + "/robocup2006.json");
  RenderSettings settings;
  settings.rig = scene.rig;
  settings.rig.mirrorRig().imageSize = 360;
  const FastRenderer fast(scene);
  const CubeMapRenderer cube(fast);
  CubeMapOptions cubemap, mesh;
  mesh.mode = OmniMode::ThesisMesh;
  cubemap.faceSize = mesh.faceSize = a.faceSize;
  const ImageRGBA omni = fast.render(scene.startPose, settings);
  const OmniCamera camera = settings.rig.camera();
  std::vector<std::pair<std::string, double>> results;
  results.emplace_back("exact", framesPerSecond([&] { fast.render(scene.startPose, settings); }, a.seconds));
  Film frame = filmFor(settings);  // reused from frame to frame, as a video would
  results.emplace_back("cubemap", framesPerSecond([&] { cube.render(scene.startPose, settings, cubemap, frame); }, a.seconds));
  results.emplace_back("thesis_mesh_1024", framesPerSecond([&] { cube.render(scene.startPose, settings, mesh, frame); }, a.seconds));
  for (const auto& [name, kind, variant] :
       std::vector<std::tuple<std::string, ViewKind, ViewVariant>>{{"view_birdseye", ViewKind::BirdsEye, ViewVariant::Exact},
                                                                   {"view_panorama", ViewKind::Panorama, ViewVariant::Exact},
                                                                   {"view_perspective", ViewKind::Perspective, ViewVariant::Exact}}) {
    ViewSpec spec;
    spec.kind = kind;
    spec.variant = variant;
    const ViewMap map = buildViewMap(spec, camera);  // built once, reused for every frame
    ImageRGBA view;  // reused from frame to frame, as a video would
    results.emplace_back(name, framesPerSecond([&] { applyViewMap(map, omni, view); }, a.seconds));
  }
  if (a.json) {
    nlohmann::json j = {{"image", "robocup2006 360x360, 1 spp, unlit, thesis start pose"}, {"face_size", a.faceSize}};
    for (const auto& [name, fps] : results) j["frames_per_second"][name] = fps;
    std::printf("%s\n", j.dump(2).c_str());
    return;
  }
  for (const auto& [name, fps] : results) std::printf("%-18s %10.1f frames/s\n", name.c_str(), fps);
}

}  // namespace

void addBenchCommand(CLI::App& app) {
  auto args = std::make_shared<BenchArgs>();
  CLI::App* cmd = app.add_subcommand("bench", "Frames/s of each render mode and view (360x360, 1 spp)");
  cmd->add_flag("--json", args->json, "Print JSON");
  cmd->add_option("--seconds", args->seconds, "Seconds timed per item (default 1)")->check(numberIn(0, 3600, true));
  cmd->add_option("--face-size", args->faceSize, "Cube-face size for the cube-map modes")->check(integerIn(8, 8192));
  cmd->callback([args] { runBench(*args); });
}

}  // namespace omnicam::cli
