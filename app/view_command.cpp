// omnicam view IN --as birdseye|panorama|perspective [--variant thesis|exact] [--size WxH]
//              [--zw Z] [--yaw DEG] [--pitch DEG] [--fov DEG] -o OUT
// Works on any omni image: the camera model comes from IN's sidecar when there is one, else
// from the default rig at IN's size (a real camera's image: give its mirror with --scene).
#include <cstdio>
#include <fstream>
#include <memory>

#include "cli_util.h"
#include "commands.h"
#include "errors.h"
#include "scene_loader.h"
#include "sidecar.h"
#include "views.h"

namespace omnicam::cli {

namespace {

struct ViewArgs {
  std::string in, as = "birdseye", variant = "exact", size, scene, out;
  double zw = 40.0, yaw = 0.0, pitch = -20.0, fov = 90.0;
};

RigSpec rigOf(const std::string& image, const std::string& scenePath, int size) {
  RigSpec rig = scenePath.empty() ? rigFromSidecar(image, RigSpec{}) : loadScene(scenePath).rig;
  rig.imageSize = size;
  return rig;
}

void runView(const ViewArgs& a) {
  ViewSpec spec;
  spec.kind = parseViewKind(a.as);
  spec.variant = parseViewVariant(a.variant);
  if (spec.kind == ViewKind::Perspective && spec.variant == ViewVariant::Thesis)
    throw InputError("--variant: perspective views use the exact model only");
  if (!a.size.empty()) {
    const size_t x = a.size.find('x');
    try {
      if (x == std::string::npos) throw std::invalid_argument("no x");
      size_t used = 0;
      spec.width = std::stoi(a.size.substr(0, x), &used);
      if (used != x) throw std::invalid_argument("junk");
      spec.height = std::stoi(a.size.substr(x + 1), &used);
      if (used != a.size.size() - x - 1) throw std::invalid_argument("junk");
    } catch (const std::exception&) {
      throw InputError("--size: must be WIDTHxHEIGHT, e.g. 400x400 (got \"" + a.size + "\")");
    }
    if (spec.width < 1 || spec.height < 1) throw InputError("--size: width and height must be at least 1");
  }
  spec.groundDistance = a.zw, spec.yawDeg = a.yaw, spec.pitchDeg = a.pitch, spec.fovDeg = a.fov;
  if (!isSupportedImageOutput(a.out)) throw InputError("-o: " + a.out + ": must end in .png or .exr");
  const ImageRGBA omni = readImage(a.in);
  if (omni.width != omni.height) throw InputError(a.in + ": omni images must be square");
  const ViewMap map = buildViewMap(spec, rigOf(a.in, a.scene, omni.width).camera());
  writeImageAtomic(a.out, applyViewMap(map, omni));
  std::printf("wrote %s (%dx%d %s, %s)\n", a.out.c_str(), map.width, map.height, a.as.c_str(), a.variant.c_str());
}

}  // namespace

void addViewCommand(CLI::App& app) {
  auto args = std::make_shared<ViewArgs>();
  CLI::App* cmd = app.add_subcommand("view", "Bird's-eye, panorama or perspective view of an omni image");
  cmd->add_option("in", args->in, "Omni image (PNG/EXR; its sidecar, if any, gives the camera)")->required();
  cmd->add_option("--as", args->as, "birdseye (default), panorama or perspective");
  cmd->add_option("--variant", args->variant, "exact (default) or thesis (Eq. 3.4 / Eqs. 3.6-3.7)");
  cmd->add_option("--size", args->size, "WIDTHxHEIGHT (defaults 400x400, 1080x300, 400x300)");
  cmd->add_option("--zw", args->zw, "birdseye: ground plane, pixel units below the viewpoint (default 40)");
  cmd->add_option("--yaw", args->yaw, "perspective: view direction, degrees CCW from forward");
  cmd->add_option("--pitch", args->pitch, "perspective: degrees above the horizon (default -20)");
  cmd->add_option("--fov", args->fov, "perspective: horizontal field of view, degrees (default 90)");
  cmd->add_option("--scene", args->scene, "Take the camera rig from this scene instead");
  cmd->add_option("-o,--output", args->out, "OUT.png or OUT.exr")->required();
  cmd->callback([args] { runView(*args); });
}

}  // namespace omnicam::cli
